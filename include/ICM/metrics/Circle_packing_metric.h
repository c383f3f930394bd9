// Step 1: the circle packing metric (paper Definition 2.1 and Algorithm 2), a model of the
// `Metric` concept (doc/concepts.md).
//
// A vertex carries a circle of radius gamma_i = exp(u_i), an edge the intersection angle
// phi_ij in [0, pi/2] of the circles at its ends; the edge length follows from the law of
// cosines. Keeping phi fixed and varying u moves within one conformal class, and for
// phi <= pi/2 every u gives valid triangles (Thurston), so Newton never leaves the domain.
// The price: Algorithm 2 clamps the angles, so at u0 the packing is not the mesh, and its
// conformal class is not the mesh's (see Inversive_distance_metric.h, Vertex_scaling_metric.h).

#ifndef ICM_METRICS_CIRCLE_PACKING_METRIC_H
#define ICM_METRICS_CIRCLE_PACKING_METRIC_H

#include <ICM/internal/Circle_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

/// The conformal class of a circle packing: one intersection angle per edge
/// (`inversive_distance` = cos phi, in [0, 1]), and the log radii `u0` of the initial
/// packing, against which every energy is measured.
///
/// `u0`, `length()` and `face_geometry()` are those of the two metrics with circles at the
/// vertices (their common base, in namespace `internal`): l_ij² = γ_i² + γ_j² + 2 I_ij γ_i γ_j
/// with γ = exp(u), and the Jacobian weights are the power-centre distances h/l.
///
/// \cgalModels{\ref Metric}
class Circle_packing_metric : public internal::Circle_metric
{
public:
  static constexpr const char* name = "circle-packing";

  int clamped_edges = 0;  ///< edges whose angle was clamped to pi/2 (obtuse overlap)
  int fallback_radii = 0; ///< vertices whose corner radii were all non-positive
  int relaxed_cycles = 0; ///< short edge cycles whose angles were reduced

  Circle_packing_metric() = default;
  /// Algorithm 2 on `index` (see `initial_circle_packing_metric`).
  explicit Circle_packing_metric(const internal::Mesh_index& index, Initial_radius rule = Initial_radius::Mean_corner);

  /// Sets the intersection angles (radians, in [0, pi/2]) of every edge.
  void set_intersection_angles(const std::vector<double>& phi)
  {
    inversive_distance.resize(phi.size());
    one_minus_inversive_distance.resize(phi.size());
    for(std::size_t e = 0; e < phi.size(); ++e)
    {
      const double half_sine = std::sin(0.5 * phi[e]);
      inversive_distance[e] = std::cos(phi[e]);
      one_minus_inversive_distance[e] = 2.0 * half_sine * half_sine;
    }
  }

  /// What the parameterizer reports of this metric.
  std::string summary() const
  {
    return std::to_string(clamped_edges) + " edge angles clamped to pi/2, " + std::to_string(relaxed_cycles) +
           " short cycles relaxed";
  }
};

/// Thurston's condition, in the form that matters for intersection angles in [0, pi/2]: the
/// interior vertices of a disk bounded by an edge cycle gamma can be made flat only if
/// sum over gamma of (pi - phi_e) > 2 pi. As their radii shrink to 0 their angle sums rise
/// to exactly that bound (each face on gamma contributes pi - phi_e, every other face pi),
/// so at equality Newton chases radii to 0 forever. Cycles of five or more edges always
/// pass; a 3-cycle needs sum phi < pi and a 4-cycle sum phi < 2 pi. Clamping makes many
/// angles exactly pi/2, so four orthogonal edges fencing a few vertices (the link of a
/// degree-4 vertex is the smallest case) or a 3-cycle with two right angles occur on real
/// meshes (bull.off: 226 such cycles). Every 3- and 4-cycle that does not bound one or two faces is checked, and the
/// angles of a failing one are scaled down to (m - 2) pi - `margin`. Angles only decrease,
/// so a cycle once satisfied stays satisfied. Returns the number of cycles relaxed.
inline int keep_short_cycles_flattenable(const internal::Mesh_index& index, std::vector<double>& phi,
                                         double margin = 0.1 * M_PI)
{
  const int nv = index.number_of_vertices();
  // Sorted neighbours of every vertex, each with the connecting edge.
  std::vector<std::vector<std::pair<int, int>>> around(nv);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    around[index.edges[e][0]].push_back({index.edges[e][1], e});
    around[index.edges[e][1]].push_back({index.edges[e][0], e});
  }
  for(auto& list : around)
    std::sort(list.begin(), list.end());
  auto edge_between = [&around](int a, int b) {
    const auto& list = around[a];
    const auto it = std::lower_bound(list.begin(), list.end(), std::make_pair(b, -1));
    return it != list.end() && it->first == b ? it->second : -1;
  };
  auto is_face = [&](int a, int b, int c) { // is {a, b, c} a face?
    const int e = edge_between(a, b);
    if(e < 0)
      return false;
    for(int f : index.edge_faces[e])
      if(f >= 0)
        for(int corner = 0; corner < 3; ++corner)
          if(index.face_edges[f][corner] == e && index.faces[f][corner] == c)
            return true;
    return false;
  };
  int relaxed = 0;
  auto enforce = [&](std::initializer_list<int> cycle_edges) {
    const double limit = (static_cast<int>(cycle_edges.size()) - 2) * M_PI - margin;
    double sum = 0;
    for(int e : cycle_edges)
      sum += phi[e];
    if(sum <= limit)
      return;
    ++relaxed;
    for(int e : cycle_edges)
      phi[e] *= limit / sum;
  };

  // 3-cycles i < j < k.
  for(int i = 0; i < nv; ++i)
    for(const auto& [j, ij] : around[i])
      if(j > i)
        for(const auto& [k, jk] : around[j])
          if(k > j)
          {
            const int ik = edge_between(i, k);
            if(ik >= 0 && !is_face(i, j, k))
              enforce({ij, jk, ik});
          }
  // 4-cycles i-j-k-l with i the smallest vertex: paths i-j-k collected per far end k.
  std::vector<std::vector<std::pair<int, int>>> paths_to(nv); // (j, edge jk) per k
  std::vector<int> touched;
  for(int i = 0; i < nv; ++i)
  {
    for(const auto& [j, ij] : around[i])
      if(j > i)
        for(const auto& [k, jk] : around[j])
          if(k > i)
          {
            if(paths_to[k].empty())
              touched.push_back(k);
            paths_to[k].push_back({j, jk});
          }
    for(int k : touched)
    {
      const auto& paths = paths_to[k];
      for(std::size_t a = 0; a < paths.size(); ++a)
        for(std::size_t b = a + 1; b < paths.size(); ++b)
        {
          const int j = paths[a].first, l = paths[b].first;
          // Not a cycle around vertices if it is the rim of two faces sharing a diagonal.
          const bool diamond = (is_face(i, j, k) && is_face(i, k, l)) || (is_face(j, k, l) && is_face(j, l, i));
          if(!diamond)
            enforce({edge_between(i, j), paths[a].second, paths[b].second, edge_between(i, l)});
        }
      paths_to[k].clear();
    }
    touched.clear();
  }
  return relaxed;
}

/// Algorithm 2: corner radii (l_ki + l_ij - l_jk)/2, one radius per vertex from its corners
/// (see `Initial_radius`; the mean by default, where the paper takes the maximum), and the
/// intersection angle that reproduces each Euclidean edge length, clamped to [0, pi/2]:
/// disjoint circles become tangent (the edge shortens), heavy overlap becomes orthogonal (the
/// edge lengthens). Short cycles whose inside could not be made flat are then relaxed
/// (`keep_short_cycles_flattenable`).
inline Circle_packing_metric::Circle_packing_metric(const internal::Mesh_index& index, Initial_radius rule)
{
  const std::vector<double> euclidean = internal::euclidean_edge_lengths(index);
  const std::vector<double> radius = internal::vertex_radii_from_corners(index, euclidean, rule, fallback_radii);
  u0 = Eigen::Map<const Eigen::VectorXd>(radius.data(), radius.size()).array().log();

  std::vector<double> phi(index.number_of_edges());
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const double gi = radius[index.edges[e][0]], gj = radius[index.edges[e][1]];
    const double l = euclidean[e];
    const double c = (l * l - gi * gi - gj * gj) / (2.0 * gi * gj);
    if(c < 0.0)
      ++clamped_edges;
    phi[e] = std::acos(std::clamp(c, 0.0, 1.0));
  }
  relaxed_cycles = keep_short_cycles_flattenable(index, phi);
  set_intersection_angles(phi);
}

/// Algorithm 2 (the paper's name for the constructor).
inline Circle_packing_metric initial_circle_packing_metric(const internal::Mesh_index& index,
                                                           Initial_radius rule = Initial_radius::Mean_corner)
{
  return Circle_packing_metric(index, rule);
}

} // namespace ICM

#endif // ICM_METRICS_CIRCLE_PACKING_METRIC_H
