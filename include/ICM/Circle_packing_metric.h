// Step 1: the circle packing metric (paper Definition 2.1 and Algorithm 2).
//
// A vertex carries a circle of radius gamma_i = exp(u_i), an edge the intersection angle
// phi_ij in [0, pi/2] of the circles at its ends; the edge length follows from the law of
// cosines. Keeping phi fixed and varying u moves within one conformal class, and for
// phi <= pi/2 every u gives valid triangles (Thurston), so Newton never leaves the domain.

#ifndef ICM_CIRCLE_PACKING_METRIC_H
#define ICM_CIRCLE_PACKING_METRIC_H

#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ICM {

/// The conformal class of a circle packing: one cosine of intersection angle per edge, and
/// the log radii `u0` of the initial packing, against which every energy is measured.
class Circle_packing_metric
{
public:
  Eigen::VectorXd u0;            ///< log radii of the initial packing (Algorithm 2)
  std::vector<double> cos_phi;   ///< per edge, cos of the intersection angle, in [0, 1]
  int clamped_edges = 0;         ///< edges whose angle was clamped to pi/2 (obtuse overlap)
  int fallback_radii = 0;        ///< vertices whose corner radii were all non-positive
  int reduced_links = 0;         ///< degree 3/4 vertices whose link angles were reduced

  /// Length of edge `e` for the radii `gi`, `gj` (= exp(u)) of its endpoints.
  double length(int e, double gi, double gj) const
  {
    return std::sqrt(gi * gi + gj * gj + 2.0 * gi * gj * cos_phi[e]);
  }

  /// d length / d u_i, the derivative with respect to the log radius of the first endpoint.
  double length_derivative(int e, double gi, double gj, double length) const
  {
    return (gi * gi + gi * gj * cos_phi[e]) / length;
  }
};

/// How Algorithm 2 turns the corner radii (l_ki + l_ij - l_jk)/2 of a vertex into its radius.
enum class Initial_radius
{
  /// Their mean (default). The corner radii of an edge inside one face sum to its length,
  /// so the mean keeps neighbouring circles close to tangent-or-orthogonal: on the horse
  /// 9 034 of 60 333 angles need clamping to pi/2, against 41 912 with the maximum, and the
  /// packing stays close to the Euclidean metric (mean |log l/l_mesh| 0.12 against 0.24).
  Mean_corner,
  /// Their maximum, the paper's choice. Circles overlap heavily on irregular meshes; most
  /// angles are clamped and some vertex sets can then not be flattened at all (horse).
  Max_corner
};

/// As the radius of an interior vertex shrinks to 0, its angle in face ijk tends to
/// pi - phi_jk, so its angle sum can never exceed sum over its link of (pi - phi): with
/// Algorithm 2's angles clamped to pi/2 a degree-3 vertex tops out at 3 pi/2 and can never
/// be made flat (Thurston's condition that a non-facial 3-cycle has angle sum < pi, and a
/// non-trivial 4-cycle < 2 pi). Such links are scaled down to (d - 2) pi - `margin`,
/// which keeps every flat target reachable. Returns the number of vertices changed.
inline int keep_low_degree_vertices_flattenable(const internal::Mesh_index& index,
                                                std::vector<double>& phi,
                                                double margin = 0.1 * M_PI)
{
  const int nv = index.number_of_vertices();
  std::vector<int> degree(nv, 0);
  std::vector<double> link_sum(nv, 0.0);
  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      ++degree[index.faces[f][c]];
      link_sum[index.faces[f][c]] += phi[index.face_edges[f][c]];
    }
  std::vector<double> vertex_scale(nv, 1.0);
  int changed = 0;
  for(int v = 0; v < nv; ++v)
  {
    const double limit = (degree[v] - 2) * M_PI - margin;
    if(index.is_boundary_vertex[v] || degree[v] > 4 || link_sum[v] <= limit)
      continue;
    ++changed;
    vertex_scale[v] = std::max(limit, 0.0) / link_sum[v];
  }
  // A link edge can belong to two offending vertices: the smaller scale wins.
  std::vector<double> edge_scale(phi.size(), 1.0);
  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      double& s = edge_scale[index.face_edges[f][c]];
      s = std::min(s, vertex_scale[index.faces[f][c]]);
    }
  for(std::size_t e = 0; e < phi.size(); ++e)
    phi[e] *= edge_scale[e];
  return changed;
}

/// Algorithm 2: corner radii (l_ki + l_ij - l_jk)/2, one radius per vertex from its corners
/// (see `Initial_radius`), and the intersection angle that reproduces each Euclidean edge
/// length, clamped to [0, pi/2]: disjoint circles become tangent (the edge shortens), heavy
/// overlap becomes orthogonal (the edge lengthens). Links that would make a vertex
/// impossible to flatten are then relaxed (`keep_low_degree_vertices_flattenable`).
///
/// A vertex whose corner values are all non-positive (only possible on numerically
/// degenerate faces) gets half its shortest incident edge; it is counted in
/// `fallback_radii`.
inline Circle_packing_metric initial_circle_packing_metric(
  const internal::Mesh_index& index, Initial_radius rule = Initial_radius::Mean_corner)
{
  const int nv = index.number_of_vertices();
  const int ne = index.number_of_edges();
  std::vector<double> euclidean(ne);
  for(int e = 0; e < ne; ++e)
    euclidean[e] = std::sqrt(
      internal::squared_distance(index.points[index.edges[e][0]], index.points[index.edges[e][1]]));

  std::vector<int> degree(nv, 0);
  for(const auto& f : index.faces)
    for(int v : f)
      ++degree[v];
  std::vector<double> radius(nv, rule == Initial_radius::Max_corner
                                   ? -std::numeric_limits<double>::infinity()
                                   : 0.0);
  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const double opposite = euclidean[index.face_edges[f][c]];
      const double next = euclidean[index.face_edges[f][(c + 1) % 3]];
      const double prev = euclidean[index.face_edges[f][(c + 2) % 3]];
      const double corner = 0.5 * (next + prev - opposite);
      const int v = index.faces[f][c];
      if(rule == Initial_radius::Max_corner)
        radius[v] = std::max(radius[v], corner);
      else
        radius[v] += corner / degree[v];
    }

  Circle_packing_metric metric;
  std::vector<double> shortest(nv, std::numeric_limits<double>::infinity());
  for(int e = 0; e < ne; ++e)
    for(int v : index.edges[e])
      shortest[v] = std::min(shortest[v], euclidean[e]);
  metric.u0.resize(nv);
  for(int v = 0; v < nv; ++v)
  {
    if(!(radius[v] > 1e-12 * shortest[v]))
    {
      radius[v] = 0.5 * shortest[v];
      ++metric.fallback_radii;
    }
    metric.u0[v] = std::log(radius[v]);
  }

  std::vector<double> phi(ne);
  for(int e = 0; e < ne; ++e)
  {
    const double gi = radius[index.edges[e][0]], gj = radius[index.edges[e][1]];
    const double l = euclidean[e];
    const double c = (l * l - gi * gi - gj * gj) / (2.0 * gi * gj);
    if(c < 0.0)
      ++metric.clamped_edges;
    phi[e] = std::acos(std::clamp(c, 0.0, 1.0));
  }
  metric.reduced_links = keep_low_degree_vertices_flattenable(index, phi);
  metric.cos_phi.resize(ne);
  for(int e = 0; e < ne; ++e)
    metric.cos_phi[e] = std::cos(phi[e]);
  return metric;
}

} // namespace ICM

#endif // ICM_CIRCLE_PACKING_METRIC_H
