// The vertex scaling metric (Luo 2004; Springborn, Schroeder, Pinkall 2008, "Conformal
// equivalence of triangle meshes"), a model of the `Metric` concept (doc/concepts.md).
//
// l_ij = exp((u_i + u_j) / 2) l0_ij with l0 the mesh's own lengths: at u0 = 0 the metric is
// the mesh, so optimising in this class optimises in the mesh's own conformal structure. The
// Jacobian of the curvature is the cotangent Laplacian (weight cot theta / 2 per face). Not
// every u gives triangles: Newton's line search keeps every face valid, and where the
// optimum lies outside the valid region the parameterizer falls back to the circle packing.

#ifndef ICM_METRICS_VERTEX_SCALING_METRIC_H
#define ICM_METRICS_VERTEX_SCALING_METRIC_H

#include <ICM/internal/Circle_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

namespace internal {

/// Angles and cotangent weights of a face whose sides are `l0[c] * sqrt(g_a g_b)` (side c
/// opposite corner c, g = exp(u) at the corners). Dividing every side by sqrt(g0 g1 g2)
/// leaves side c = l0_c / sqrt(g_c): the shape of the face without the common scale, so the
/// excesses, angles and weights do not depend on how large the factors are, only on how
/// they differ.
inline Face_geometry vertex_scaling_face_geometry(const std::array<double, 3>& l0, const std::array<double, 3>& g)
{
  std::array<double, 3> side, excess;
  for(int c = 0; c < 3; ++c)
    side[c] = l0[c] / std::sqrt(g[c]);
  for(int c = 0; c < 3; ++c)
    excess[c] = 0.5 * (side[(c + 1) % 3] + side[(c + 2) % 3] - side[c]);
  Face_geometry face;
  face.valid = is_valid_triangle(excess);
  face.angles = triangle_angles_from_excesses(excess);
  // cot theta_c = (s x_c - x_a x_b) / (2 A) with A = sqrt(s x0 x1 x2): the half-angle form of
  // the law of cosines. d theta_a / d u_b = cot theta_c / 2 (the cotangent Laplacian).
  const double s = excess[0] + excess[1] + excess[2];
  for(int c = 0; c < 3; ++c)
    face.weight[c] = (s * excess[c] - excess[(c + 1) % 3] * excess[(c + 2) % 3]) / (4.0 * face.angles.area);
  face.angles.area *= g[0] * g[1] * g[2];
  return face;
}

} // namespace internal

/// \brief The vertex scaling metric (Luo 2004; Springborn, Schroeder, Pinkall 2008):
/// l_ij = exp((u_i + u_j) / 2) l0_ij on the mesh's own edges, with l0 the mesh's lengths.
///
/// At u0 = 0 the metric is the mesh, so optimising in this class optimises in the mesh's own
/// conformal structure; the Jacobian is the cotangent Laplacian. Not every u gives
/// triangles: Newton's line search keeps every face valid, and where the optimum lies outside
/// the valid region the parameterizer falls back to `Circle_packing_metric`.
///
/// \cgalModels{\ref Metric}
class Vertex_scaling_metric
{
public:
  static constexpr const char* name = "vertex-scaling";

  Eigen::VectorXd u0;               ///< zero: the mesh itself
  std::vector<double> mesh_lengths; ///< l0 per edge

  Vertex_scaling_metric() = default;
  explicit Vertex_scaling_metric(const internal::Mesh_index& index)
    : u0(Eigen::VectorXd::Zero(index.number_of_vertices())), mesh_lengths(internal::euclidean_edge_lengths(index))
  {}

  /// Length of edge `e` for the factors `gi`, `gj` (= exp(u)) of its endpoints; the square
  /// roots are taken apart so that factors near the overflow threshold still work.
  double length(int e, double gi, double gj) const { return std::sqrt(gi) * std::sqrt(gj) * mesh_lengths[e]; }

  /// Angles and cotangent weights of a face with edges `e[c]` (opposite corner c) and corner
  /// factors `g[c]` (see `internal::vertex_scaling_face_geometry`).
  Face_geometry face_geometry(const std::array<int, 3>& e, const std::array<double, 3>& g,
                              const std::array<double, 3>& /* l */) const
  {
    return internal::vertex_scaling_face_geometry({mesh_lengths[e[0]], mesh_lengths[e[1]], mesh_lengths[e[2]]}, g);
  }

  std::string summary() const { return "the mesh's own lengths"; }
};

} // namespace ICM

#endif // ICM_METRICS_VERTEX_SCALING_METRIC_H
