// The inversive distance circle packing metric (Bowers & Stephenson 2004; Guo 2011; Luo
// 2011; Yang, Guo, Luo, Hu, Gu 2009), a model of the `Metric` concept (doc/concepts.md).
//
// Circles at the vertices as in the paper's packing, but the inversive distance
// I_ij = (l_ij^2 - gamma_i^2 - gamma_j^2) / (2 gamma_i gamma_j) of every edge is taken from
// the mesh exactly, so at u0 the metric is the mesh and the conformal class is the mesh's
// own. The price: not every u gives triangles, so Newton's line search keeps every face valid.

#ifndef ICM_METRICS_INVERSIVE_DISTANCE_METRIC_H
#define ICM_METRICS_INVERSIVE_DISTANCE_METRIC_H

#include <ICM/internal/Circle_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ICM {

/// Circles with the mesh's own inversive distances. The radii default to the smallest corner
/// radius of each vertex: the circles of every edge are then disjoint or tangent (I >= 1),
/// the regime of Guo's and Luo's rigidity theorems, and small circles keep the metric close
/// to vertex scaling, its limit as the radii shrink.
///
/// `u0`, `length()` and `face_geometry()` are those of the two metrics with circles at the
/// vertices (their common base, in namespace `internal`): l_ij² = γ_i² + γ_j² + 2 I_ij γ_i γ_j
/// with γ = exp(u), and the Jacobian weights are the power-centre distances h/l.
///
/// \cgalModels{\ref Metric}
class Inversive_distance_metric : public internal::Circle_metric
{
public:
  static constexpr const char* name = "inversive-distance";

  int fallback_radii = 0; ///< vertices whose corner radii were all non-positive

  Inversive_distance_metric() = default;
  explicit Inversive_distance_metric(const internal::Mesh_index& index,
                                     Initial_radius rule = Initial_radius::Min_corner)
  {
    const std::vector<double> l = internal::euclidean_edge_lengths(index);
    const std::vector<double> radius = internal::vertex_radii_from_corners(index, l, rule, fallback_radii);
    u0 = Eigen::Map<const Eigen::VectorXd>(radius.data(), radius.size()).array().log();
    inversive_distance.resize(index.number_of_edges());
    one_minus_inversive_distance.resize(index.number_of_edges());
    for(int e = 0; e < index.number_of_edges(); ++e)
    {
      const double gi = radius[index.edges[e][0]], gj = radius[index.edges[e][1]];
      inversive_distance[e] = (l[e] * l[e] - gi * gi - gj * gj) / (2.0 * gi * gj);
      // 1 - I = (gi + gj - l)(gi + gj + l) / (2 gi gj): exact for tangent circles.
      one_minus_inversive_distance[e] = (gi + gj - l[e]) * (gi + gj + l[e]) / (2.0 * gi * gj);
    }
  }

  std::string summary() const { return std::to_string(fallback_radii) + " fallback radii"; }
};

} // namespace ICM

#endif // ICM_METRICS_INVERSIVE_DISTANCE_METRIC_H
