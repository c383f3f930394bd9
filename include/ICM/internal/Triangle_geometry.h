// Angles and area of one triangle, to full relative precision even when it is needle-thin.
//
// Everything is expressed through the corner excesses x_c = s - l_c (s the semi-perimeter,
// l_c the side opposite corner c): Heron's area sqrt(s x0 x1 x2) and the half-angle formula
// tan(theta_c / 2) = sqrt(x_{c+1} x_{c+2} / (s x_c)) involve no subtraction once the excesses
// are known. Computing the excesses without cancellation needs to know where the lengths
// come from, so each metric computes them itself (the circle metrics from their radii).

#ifndef ICM_INTERNAL_TRIANGLE_GEOMETRY_H
#define ICM_INTERNAL_TRIANGLE_GEOMETRY_H

#include <array>
#include <cmath>

namespace ICM {

/// Angles and area of a triangle; corner `c` is opposite side `c`.
struct Triangle_angles
{
  std::array<double, 3> angle;
  std::array<double, 3> one_minus_cosine; ///< 2 sin^2(theta / 2), exact for small angles
  double area;
};

/// Corner angles of one face of a metric, and the Jacobian entries of its three edges.
struct Face_geometry
{
  Triangle_angles angles;
  /// weight[c] = d theta_a / d u_b = d theta_b / d u_a for the edge ab opposite corner c.
  std::array<double, 3> weight;
  /// False when the lengths violate the triangle inequality (or are not finite): angles and
  /// weights are then meaningless, and Newton's line search must step back.
  bool valid = true;
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
    t.one_minus_cosine[c] = 2.0 * across / (along + across);
  }
  return t;
}

/// Whether excesses describe a real, non-degenerate triangle.
inline bool is_valid_triangle(const std::array<double, 3>& x)
{
  return x[0] > 0 && x[1] > 0 && x[2] > 0 && std::isfinite(x[0] + x[1] + x[2]);
}

} // namespace ICM

#endif // ICM_INTERNAL_TRIANGLE_GEOMETRY_H
