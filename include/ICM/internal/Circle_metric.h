// What the two metrics with circles at the vertices share: the inversive circle packing and
// the paper's circle packing (its special case with inversive distances in [0, 1]).
//
// A vertex carries a circle of radius gamma_i = exp(u_i), an edge the inversive distance
// I_ij of the circles at its ends, and l_ij^2 = gamma_i^2 + gamma_j^2 + 2 I_ij gamma_i gamma_j.
// For circles meeting at angle phi, I = cos phi; I > 1 for disjoint circles.

#ifndef ICM_INTERNAL_CIRCLE_METRIC_H
#define ICM_INTERNAL_CIRCLE_METRIC_H

#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace ICM {

/// How a vertex radius is made from its corner radii (l_ki + l_ij - l_jk)/2, the radii of
/// the three mutually tangent circles centred at a face's corners.
enum class Initial_radius
{
  /// Their mean. The corner radii of an edge inside one face sum to its length, so the mean
  /// keeps neighbouring circles close to tangent-or-orthogonal: far fewer angles need
  /// clamping to pi/2 than with the maximum.
  Mean_corner,
  /// Their maximum, the paper's Algorithm 2. Circles overlap heavily on irregular meshes.
  Max_corner,
  /// Their minimum: the circles of every edge are then disjoint or tangent (I >= 1), as the
  /// corner radii at the ends of an edge sum to at most its length.
  Min_corner
};

namespace internal {

/// Euclidean length of every edge of the indexed mesh.
inline std::vector<double> euclidean_edge_lengths(const Mesh_index& index)
{
  std::vector<double> lengths(index.number_of_edges());
  for(int e = 0; e < index.number_of_edges(); ++e)
    lengths[e] = edge_length(index, e);
  return lengths;
}

/// One radius per vertex from its corner radii (see `Initial_radius`). A vertex whose corner
/// values are all non-positive (only possible on numerically degenerate faces) gets half its
/// shortest edge; `fallbacks` counts them.
inline std::vector<double> vertex_radii_from_corners(const Mesh_index& index, const std::vector<double>& lengths,
                                                     Initial_radius rule, int& fallbacks)
{
  const int nv = index.number_of_vertices();
  std::vector<int> degree(nv, 0);
  for(const auto& f : index.faces)
    for(int v : f)
      ++degree[v];
  const double start = rule == Initial_radius::Max_corner   ? -std::numeric_limits<double>::infinity()
                       : rule == Initial_radius::Min_corner ? std::numeric_limits<double>::infinity()
                                                            : 0.0;
  std::vector<double> radius(nv, start);
  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const double opposite = lengths[index.face_edges[f][c]];
      const double next = lengths[index.face_edges[f][(c + 1) % 3]];
      const double prev = lengths[index.face_edges[f][(c + 2) % 3]];
      const double corner = 0.5 * (next + prev - opposite);
      const int v = index.faces[f][c];
      switch(rule)
      {
      case Initial_radius::Max_corner:
        radius[v] = std::max(radius[v], corner);
        break;
      case Initial_radius::Min_corner:
        radius[v] = std::min(radius[v], corner);
        break;
      case Initial_radius::Mean_corner:
        radius[v] += corner / degree[v];
        break;
      }
    }
  std::vector<double> shortest(nv, std::numeric_limits<double>::infinity());
  for(int e = 0; e < index.number_of_edges(); ++e)
    for(int v : index.edges[e])
      shortest[v] = std::min(shortest[v], lengths[e]);
  fallbacks = 0;
  for(int v = 0; v < nv; ++v)
    if(!(radius[v] > 1e-12 * shortest[v]))
    {
      radius[v] = 0.5 * shortest[v];
      ++fallbacks;
    }
  return radius;
}

/// Lengths, angles and Jacobian weights of a metric with circles at the vertices and a fixed
/// inversive distance per edge.
class Circle_metric
{
public:
  Eigen::VectorXd u0;                               ///< log radii of the initial circles
  std::vector<double> inversive_distance;           ///< per edge, I_ij
  std::vector<double> one_minus_inversive_distance; ///< per edge, 1 - I_ij, kept exact near I = 1

  /// Length of edge `e` for the radii `gi`, `gj` (= exp(u)) of its endpoints.
  double length(int e, double gi, double gj) const
  {
    return std::sqrt(gi * gi + gj * gj + 2.0 * gi * gj * inversive_distance[e]);
  }

  /// Angles and Jacobian entries of a face with edges `e[c]` (opposite corner c) of lengths
  /// `l[c]`, and corner radii `g[c]`.
  ///
  /// Newton has to reach conformal factors that differ by e^30 inside one face (a nearly
  /// closed surface squeezed into its hole). There the side lengths are dominated by the big
  /// circles and every textbook formula cancels: the excess s - l_c is computed as a sum of
  /// parts that are non-negative when I >= 0, and the edge weight as h / l, with h the
  /// distance of the face's power centre from the edge, measured from the edge's smaller
  /// circle, where it involves no cancellation either. The identities hold for any I; only
  /// their freedom from cancellation needs I in [0, 1].
  Face_geometry face_geometry(const std::array<int, 3>& e, const std::array<double, 3>& g,
                              const std::array<double, 3>& l) const
  {
    const std::vector<double>& I = inversive_distance;
    const std::vector<double>& one_minus_I = one_minus_inversive_distance;
    std::array<double, 3> excess;
    for(int c = 0; c < 3; ++c)
    {
      const int n = (c + 1) % 3, p = (c + 2) % 3; // side l[p] joins c and n, l[n] joins c and p
      const double beyond_n = g[c] * (g[c] + 2.0 * g[n] * I[e[p]]) / (l[p] + g[n]);
      const double beyond_p = g[c] * (g[c] + 2.0 * g[p] * I[e[n]]) / (l[n] + g[p]);
      const double overlap = 2.0 * g[n] * g[p] * one_minus_I[e[c]] / (g[n] + g[p] + l[c]);
      excess[c] = 0.5 * (beyond_n + beyond_p + overlap);
    }
    Face_geometry face;
    face.valid = is_valid_triangle(excess);
    face.angles = triangle_angles_from_excesses(excess);
    for(int c = 0; c < 3; ++c)
    {
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      const int p = g[a] <= g[b] ? a : b, q = a + b - p; // p: the smaller circle of edge pq
      // The radical axis of pq crosses side pq at distance along_pq = g_p - inside_pq from p.
      const double I_pq = I[e[c]], I_pr = I[e[q]];
      const double inside_pq =
        g[p] * g[q] * g[q] * one_minus_I[e[c]] * (1.0 + I_pq) / (l[c] * (l[c] + g[p] + g[q] * I_pq));
      const double inside_pr =
        g[p] * g[c] * g[c] * one_minus_I[e[q]] * (1.0 + I_pr) / (l[q] * (l[q] + g[p] + g[c] * I_pr));
      const double along_pq = g[p] * (g[p] + g[q] * I_pq) / l[c];
      // h = (along_pr - along_pq cos theta_p) / sin theta_p, with sin theta_p = 2 A / (l_pq l_pr)
      // and the difference regrouped so that thin faces and tangent circles do not cancel.
      const double h_sin = (inside_pq - inside_pr) + along_pq * face.angles.one_minus_cosine[p];
      face.weight[c] = h_sin * l[q] / (2.0 * face.angles.area);
    }
    return face;
  }
};

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_CIRCLE_METRIC_H
