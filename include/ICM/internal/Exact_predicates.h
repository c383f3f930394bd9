// The exact orientation of three UV points, and the segment tests built on it.
//
// Whether two border edges of a layout cross, or merely touch, is decided at the level of the
// rounding error: a layout whose two border vertices touch must be reported however close
// they are. The orientation is therefore exact for double coordinates. A floating-point
// filter decides almost every call (Shewchuk's error bound for the 2x2 determinant); the
// rest are decided by expansion arithmetic (Knuth's two-sum and an fma two-product turn the
// determinant into a sum of 16 doubles, summed without error), the method of Shewchuk's
// "Adaptive precision floating-point arithmetic and fast robust geometric predicates" (1997).
// CGAL's exact number types would decide the same, at more than the preprocessed size of the
// whole disk parameterizer's own code.
//
// Exact as long as no product of coordinate differences underflows: with the coordinates
// scaled to unit size, two points nearer than about 1e-150 of the largest coordinate
// (a layout's faces are far larger than that; Unit_frame.h).

#ifndef ICM_INTERNAL_EXACT_PREDICATES_H
#define ICM_INTERNAL_EXACT_PREDICATES_H

#include <ICM/internal/Vector_geometry.h>

#include <algorithm>
#include <cmath>

namespace ICM {
namespace internal {

namespace expansion {

/// a + b == sum + error exactly (Knuth's two-sum; no ordering of |a|, |b| needed).
inline void two_sum(double a, double b, double& sum, double& error)
{
  sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  error = (a - a_virtual) + (b - b_virtual);
}

/// a * b == product + error exactly, unless the product underflows.
inline void two_product(double a, double b, double& product, double& error)
{
  product = a * b;
  error = std::fma(a, b, -product);
}

/// Adds `b` to the nonoverlapping expansion e[0..n) (increasing magnitude), exactly, dropping
/// zero components; returns the new length (at most n + 1).
inline int grow(double* e, int n, double b)
{
  int m = 0;
  double q = b;
  for(int i = 0; i < n; ++i)
  {
    double h;
    two_sum(q, e[i], q, h);
    if(h != 0)
      e[m++] = h;
  }
  if(q != 0)
    e[m++] = q;
  return m;
}

/// The sign of the expansion's sum: that of its largest component, which outweighs the rest.
inline int sign(const double* e, int n)
{
  return n == 0 ? 0 : (e[n - 1] > 0 ? 1 : -1);
}

/// The sign of (q - p) x (r - p) computed without error.
inline int exact_orientation(Uv p, Uv q, Uv r)
{
  // Far from unit size, a common power of two brings the largest coordinate to [0.5, 1), so
  // that no difference or product below overflows (the sign is the same).
  const double largest =
    std::max({std::abs(p[0]), std::abs(p[1]), std::abs(q[0]), std::abs(q[1]), std::abs(r[0]), std::abs(r[1])});
  if(largest > 0x1p500 || largest < 0x1p-500)
  {
    int exponent = 0;
    std::frexp(largest, &exponent);
    for(Uv* point : {&p, &q, &r})
      for(double& x : *point)
        x = std::ldexp(x, -exponent);
  }

  double qx[2], qy[2], rx[2], ry[2]; // each difference as value + rounding error
  two_sum(q[0], -p[0], qx[1], qx[0]);
  two_sum(q[1], -p[1], qy[1], qy[0]);
  two_sum(r[0], -p[0], rx[1], rx[0]);
  two_sum(r[1], -p[1], ry[1], ry[0]);

  double e[33];
  int n = 0;
  for(int i = 0; i < 2; ++i)
    for(int j = 0; j < 2; ++j)
    {
      double product, error;
      two_product(qx[i], ry[j], product, error);
      n = grow(e, grow(e, n, error), product);
      two_product(-qy[i], rx[j], product, error);
      n = grow(e, grow(e, n, error), product);
    }
  return sign(e, n);
}

} // namespace expansion

/// The side of r relative to the directed line pq, exactly: +1 to the left (counterclockwise
/// p, q, r), -1 to the right, 0 on the line.
inline int orientation(const Uv& p, const Uv& q, const Uv& r)
{
  const double left = (q[0] - p[0]) * (r[1] - p[1]);
  const double right = (q[1] - p[1]) * (r[0] - p[0]);
  const double determinant = left - right;
  // Shewchuk's bound on the rounding error of `determinant`, valid while the products are
  // normal numbers (the bound's 1e-290 floor) and finite.
  const double magnitude = std::abs(left) + std::abs(right);
  const double bound = 3.3306690738754716e-16 * magnitude;
  if(magnitude > 1e-290 && magnitude < 1e300)
  {
    if(determinant > bound)
      return 1;
    if(-determinant > bound)
      return -1;
  }
  return expansion::exact_orientation(p, q, r);
}

/// For collinear p, q, r: whether q lies on the closed segment pr (exact comparisons of
/// coordinates).
inline bool collinear_are_ordered_along_line(const Uv& p, const Uv& q, const Uv& r)
{
  for(int i = 0; i < 2; ++i)
  {
    if(p[i] < q[i])
      return !(r[i] < q[i]);
    if(q[i] < p[i])
      return !(q[i] < r[i]);
  }
  return true; // q == p
}

/// Whether p lies on the closed segment rs.
inline bool segment_has_on(const Uv& r, const Uv& s, const Uv& p)
{
  return orientation(r, s, p) == 0 && collinear_are_ordered_along_line(r, p, s);
}

/// Whether the closed segments pq and rs have a point in common, exactly. A segment of zero
/// length is a point, which can still lie on the other.
inline bool segments_meet(const Uv& p, const Uv& q, const Uv& r, const Uv& s)
{
  const bool pq_point = (p == q), rs_point = (r == s);
  if(pq_point && rs_point)
    return p == r;
  if(pq_point)
    return segment_has_on(r, s, p);
  if(rs_point)
    return segment_has_on(p, q, r);
  const int pq_r = orientation(p, q, r), pq_s = orientation(p, q, s);
  const int rs_p = orientation(r, s, p), rs_q = orientation(r, s, q);
  if(pq_r * pq_s > 0 || rs_p * rs_q > 0)
    return false;            // one segment lies strictly on one side of the other's line
  if(pq_r == 0 && pq_s == 0) // on one line: they meet where one holds an end of the other
    return segment_has_on(p, q, r) || segment_has_on(p, q, s) || segment_has_on(r, s, p);
  return true;
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_EXACT_PREDICATES_H
