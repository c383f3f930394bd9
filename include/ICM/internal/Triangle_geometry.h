// Angles and area of one triangle, to full relative precision even when it is needle-thin.
//
// Everything is expressed through the corner excesses x_c = s - l_c (s the semi-perimeter,
// l_c the side opposite corner c): Heron's area sqrt(s x0 x1 x2) and the half-angle formula
// tan(theta_c / 2) = sqrt(x_{c+1} x_{c+2} / (s x_c)) involve no subtraction once the excesses
// are known. Whoever knows where the lengths come from can compute the excesses without
// cancellation (the circle packing metric does, from its radii); from bare lengths Kahan's
// ordering of the differences gives the best that is possible.

#ifndef ICM_INTERNAL_TRIANGLE_GEOMETRY_H
#define ICM_INTERNAL_TRIANGLE_GEOMETRY_H

#include <algorithm>
#include <array>
#include <cmath>

namespace ICM {

/// Angles and area of a triangle; corner `c` is opposite side `c`.
struct Triangle_angles
{
  std::array<double, 3> angle;
  std::array<double, 3> cosine;
  std::array<double, 3> one_minus_cosine; ///< 2 sin^2(theta / 2), exact for small angles
  double area;
};

/// From the excesses x_c = s - l_c >= 0 (a zero excess is a flat corner of angle pi).
inline Triangle_angles triangle_angles_from_excesses(const std::array<double, 3>& x)
{
  const double s = x[0] + x[1] + x[2];
  Triangle_angles t;
  t.area = std::sqrt(s * x[0] * x[1] * x[2]);
  for(int c = 0; c < 3; ++c)
  {
    const double across = x[(c + 1) % 3] * x[(c + 2) % 3]; // tan^2(theta/2) = across / along
    const double along = s * x[c];
    t.angle[c] = 2.0 * std::atan2(std::sqrt(across), std::sqrt(along));
    t.cosine[c] = (along - across) / (along + across);
    t.one_minus_cosine[c] = 2.0 * across / (along + across);
  }
  return t;
}

/// From side lengths: Kahan's ordering (a >= b >= c, parenthesised differences) computes the
/// excesses as accurately as the lengths allow. Lengths violating the triangle inequality
/// are treated as flat (an excess of zero).
inline Triangle_angles triangle_angles(const std::array<double, 3>& l)
{
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&l](int i, int j) { return l[i] > l[j]; });
  const double a = l[order[0]], b = l[order[1]], c = l[order[2]];
  std::array<double, 3> x;
  x[order[0]] = std::max(0.5 * (c - (a - b)), 0.0);
  x[order[1]] = 0.5 * (c + (a - b));
  x[order[2]] = 0.5 * (a + (b - c));
  return triangle_angles_from_excesses(x);
}

} // namespace ICM

#endif // ICM_INTERNAL_TRIANGLE_GEOMETRY_H
