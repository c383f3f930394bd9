// Step 1: the circle packing metric (paper Definition 2.1 and Algorithm 2).
//
// A vertex carries a circle of radius gamma_i = exp(u_i), an edge the intersection angle
// phi_ij in [0, pi/2] of the circles at its ends; the edge length follows from the law of
// cosines. Keeping phi fixed and varying u moves within one conformal class, and for
// phi <= pi/2 every u gives valid triangles (Thurston), so Newton never leaves the domain.

#ifndef ICM_CIRCLE_PACKING_METRIC_H
#define ICM_CIRCLE_PACKING_METRIC_H

#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace ICM {

/// Corner angles of one face of a metric, and the Jacobian entries of its three edges.
struct Face_geometry
{
  Triangle_angles angles;
  /// weight[c] = d theta_a / d u_b = d theta_b / d u_a for the edge ab opposite corner c.
  std::array<double, 3> weight;
};

/// The conformal class of a circle packing: one intersection angle per edge, and the log
/// radii `u0` of the initial packing, against which every energy is measured.
class Circle_packing_metric
{
public:
  Eigen::VectorXd u0;                   ///< log radii of the initial packing (Algorithm 2)
  std::vector<double> cos_phi;          ///< per edge, cos of the intersection angle, in [0, 1]
  std::vector<double> one_minus_cos_phi; ///< per edge, 1 - cos phi = 2 sin^2(phi / 2), exact near 0
  int clamped_edges = 0;                ///< edges whose angle was clamped to pi/2 (obtuse overlap)
  int fallback_radii = 0;               ///< vertices whose corner radii were all non-positive
  int relaxed_cycles = 0;               ///< short edge cycles whose angles were reduced

  /// Sets the intersection angles (radians, in [0, pi/2]) of every edge.
  void set_intersection_angles(const std::vector<double>& phi)
  {
    cos_phi.resize(phi.size());
    one_minus_cos_phi.resize(phi.size());
    for(std::size_t e = 0; e < phi.size(); ++e)
    {
      const double half_sine = std::sin(0.5 * phi[e]);
      cos_phi[e] = std::cos(phi[e]);
      one_minus_cos_phi[e] = 2.0 * half_sine * half_sine;
    }
  }

  /// Length of edge `e` for the radii `gi`, `gj` (= exp(u)) of its endpoints.
  double length(int e, double gi, double gj) const
  {
    return std::sqrt(gi * gi + gj * gj + 2.0 * gi * gj * cos_phi[e]);
  }

  /// Angles and Jacobian entries of a face with edges `e[c]` (opposite corner c) of lengths
  /// `l[c]`, and corner radii `g[c]`.
  ///
  /// Newton has to reach conformal factors that differ by e^30 inside one face (a nearly
  /// closed surface squeezed into its hole). There the side lengths are dominated by the big
  /// circles and every textbook formula cancels: the excess s - l_c is computed as a sum of
  /// non-negative parts instead (possible because cos phi >= 0), and the edge weight as
  /// h / l, with h the distance of the face's power centre from the edge, measured from the
  /// edge's smaller circle, where it involves no cancellation either.
  Face_geometry face_geometry(const std::array<int, 3>& e, const std::array<double, 3>& g,
                              const std::array<double, 3>& l) const
  {
    std::array<double, 3> excess;
    for(int c = 0; c < 3; ++c)
    {
      const int n = (c + 1) % 3, p = (c + 2) % 3; // side l[p] joins c and n, l[n] joins c and p
      const double beyond_n = g[c] * (g[c] + 2.0 * g[n] * cos_phi[e[p]]) / (l[p] + g[n]);
      const double beyond_p = g[c] * (g[c] + 2.0 * g[p] * cos_phi[e[n]]) / (l[n] + g[p]);
      const double overlap = 2.0 * g[n] * g[p] * one_minus_cos_phi[e[c]] / (g[n] + g[p] + l[c]);
      excess[c] = 0.5 * (beyond_n + beyond_p + overlap);
    }
    Face_geometry face;
    face.angles = triangle_angles_from_excesses(excess);
    for(int c = 0; c < 3; ++c)
    {
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      const int p = g[a] <= g[b] ? a : b, q = a + b - p; // p: the smaller circle of edge pq
      // The radical axis of pq crosses side pq at distance along_pq = g_p - inside_pq from p.
      const double cos_pq = cos_phi[e[c]], cos_pr = cos_phi[e[q]];
      const double inside_pq = g[p] * g[q] * g[q] * one_minus_cos_phi[e[c]] * (1.0 + cos_pq) /
                               (l[c] * (l[c] + g[p] + g[q] * cos_pq));
      const double inside_pr = g[p] * g[c] * g[c] * one_minus_cos_phi[e[q]] * (1.0 + cos_pr) /
                               (l[q] * (l[q] + g[p] + g[c] * cos_pr));
      const double along_pq = g[p] * (g[p] + g[q] * cos_pq) / l[c];
      // h = (along_pr - along_pq cos theta_p) / sin theta_p, with sin theta_p = 2 A / (l_pq l_pr)
      // and the difference regrouped so that thin faces and tangent circles do not cancel.
      const double h_sin = (inside_pq - inside_pr) + along_pq * face.angles.one_minus_cosine[p];
      face.weight[c] = h_sin * l[q] / (2.0 * face.angles.area);
    }
    return face;
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
inline int keep_short_cycles_flattenable(const internal::Mesh_index& index,
                                         std::vector<double>& phi, double margin = 0.1 * M_PI)
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
/// (see `Initial_radius`), and the intersection angle that reproduces each Euclidean edge
/// length, clamped to [0, pi/2]: disjoint circles become tangent (the edge shortens), heavy
/// overlap becomes orthogonal (the edge lengthens). Short cycles whose inside could not be
/// made flat are then relaxed (`keep_short_cycles_flattenable`).
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
  metric.relaxed_cycles = keep_short_cycles_flattenable(index, phi);
  metric.set_intersection_angles(phi);
  return metric;
}

} // namespace ICM

#endif // ICM_CIRCLE_PACKING_METRIC_H
