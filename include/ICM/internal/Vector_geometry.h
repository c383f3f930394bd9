// The 2- and 3-vectors every stage shares, and the two area formulas on them: a UV point is a
// `Uv`, a 3D point a `Point3`, and each area is written once here.

#ifndef ICM_INTERNAL_VECTOR_GEOMETRY_H
#define ICM_INTERNAL_VECTOR_GEOMETRY_H

#include <array>
#include <cmath>

namespace ICM {

/// A point or a vector of the parameter plane.
using Uv = std::array<double, 2>;

namespace internal {

using Point3 = std::array<double, 3>;

inline Uv difference(const Uv& a, const Uv& b)
{
  return {a[0] - b[0], a[1] - b[1]};
}
inline Point3 difference(const Point3& a, const Point3& b)
{
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

inline double dot(const Uv& a, const Uv& b)
{
  return a[0] * b[0] + a[1] * b[1];
}
inline double dot(const Point3& a, const Point3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The z component of the cross product of two plane vectors.
inline double cross(const Uv& a, const Uv& b)
{
  return a[0] * b[1] - a[1] * b[0];
}
/// The norm of the cross product, by hypot: neither its squares nor their sum can overflow.
inline double cross_norm(const Point3& a, const Point3& b)
{
  return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

/// Twice the signed area of UV triangle (a, b, c): positive when it turns counterclockwise.
/// Rounded; `orientation` in Exact_predicates.h gives its sign exactly.
inline double twice_signed_area(const Uv& a, const Uv& b, const Uv& c)
{
  return cross(difference(b, a), difference(c, a));
}

/// Area of the 3D triangle (a, b, c), half the norm of the cross product of two sides.
/// Callers pass points of a unit frame (Unit_frame.h), so the squares neither overflow nor
/// underflow.
inline double triangle_area(const Point3& a, const Point3& b, const Point3& c)
{
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  return 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_VECTOR_GEOMETRY_H
