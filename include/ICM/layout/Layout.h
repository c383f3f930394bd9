// Step 7: isometric layout of a flat metric in the plane (paper Sec. III-F).
//
// Two methods:
// - propagation: place a central face, then unfold neighbours breadth first, each new vertex
//   from the two already placed ones and the metric's corner angle (the paper, for small
//   meshes: rounding error grows with the depth of the face tree);
// - harmonic: by Lemma 5.4 the isometric embedding of a flat circle packing metric is
//   harmonic for the dynamic Laplacian of that metric. The border is walked once with the
//   metric's edge lengths and turning angles (the boundary curvatures), then the interior is
//   the solution of Delta_NN x = b — one global solve with the Newton system's own
//   pattern, so no error accumulates across the mesh.
// Both require a topological disk whose metric is flat at every interior vertex.

#ifndef ICM_LAYOUT_LAYOUT_H
#define ICM_LAYOUT_LAYOUT_H

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <string>
#include <vector>

namespace ICM {

/// The face farthest (in face hops) from the border, or face 0 on a closed mesh: unfolding
/// from the middle keeps the face tree shallow.
inline int central_face(const internal::Mesh_index& index)
{
  const int nf = index.number_of_faces();
  std::vector<int> depth(nf, -1);
  std::vector<int> queue; // breadth first: each face enters once, in order of depth
  queue.reserve(nf);
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(index.edge_faces[e][1] < 0 && depth[index.edge_faces[e][0]] < 0)
    {
      depth[index.edge_faces[e][0]] = 0;
      queue.push_back(index.edge_faces[e][0]);
    }
  int last = 0;
  for(std::size_t next = 0; next < queue.size(); ++next)
  {
    last = queue[next];
    for(int e : index.face_edges[last])
      for(int g : index.edge_faces[e])
        if(g >= 0 && depth[g] < 0)
        {
          depth[g] = depth[last] + 1;
          queue.push_back(g);
        }
  }
  return last;
}

/// The faces around each vertex, in compressed rows: those of v are
/// `faces[first[v]] .. faces[first[v + 1] - 1]`.
struct Faces_around_vertices
{
  std::vector<int> first, faces;

  explicit Faces_around_vertices(const internal::Mesh_index& index)
    : Faces_around_vertices(index.faces, index.number_of_vertices())
  {}

  /// For faces given by their corners' vertex ids, below `vertices`.
  Faces_around_vertices(const std::vector<std::array<int, 3>>& corners, int vertices) : first(vertices + 1, 0)
  {
    for(const auto& f : corners)
      for(int v : f)
        ++first[v + 1];
    for(int v = 0; v < vertices; ++v)
      first[v + 1] += first[v];
    faces.resize(first[vertices]);
    std::vector<int> fill(first.begin(), first.end() - 1);
    for(std::size_t f = 0; f < corners.size(); ++f)
      for(int v : corners[f])
        faces[fill[v]++] = static_cast<int>(f);
  }
};

/// One step of an unfolding: the vertex at `corner` of `face` placed from the face's other two.
struct Unfolding_step
{
  int face, corner;
};

/// Places corner c of a face whose corners are the points `w` of `z`, from the two already
/// placed, a the next corner and b the one after: z_c = z_a + l_ac R(theta_a) (z_b - z_a) /
/// |z_b - z_a|, the metric's length l_ac and angle theta_a. Every face so keeps the input
/// orientation (counter-clockwise = positive area), and every new edge has the metric's
/// length rather than a ratio of lengths times an edge already placed, which would carry
/// that edge's relative error on.
inline void place_corner(const std::array<int, 3>& w, int c, double l_ac, double theta_a, std::vector<Uv>& z)
{
  const Uv &a = z[w[(c + 1) % 3]], &b = z[w[(c + 2) % 3]];
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double scale = l_ac / std::hypot(dx, dy);
  const double cs = std::cos(theta_a), sn = std::sin(theta_a);
  // Rotated, then scaled: the order the energies' reverse mode differentiates (Energy_state.h).
  const double rx = cs * dx - sn * dy, ry = sn * dx + cs * dy;
  z[w[c]] = {a[0] + scale * rx, a[1] + scale * ry};
}

/// Unfolds faces given by their corners (`corners[f]`: ids of points of `z`, vertices or the
/// wedges of a cut) and edges (`face_edges`, into `lengths`) from face `root`, whose first
/// edge is put on the x axis. `angle(f, c)` is the metric's angle at corner c of face f.
/// Returns the steps in their order, the root's third corner first.
///
/// The order is not breadth first but least estimated error first (Dijkstra): placing c from
/// (a, b) carries a's error and turns the direction of (b - a), known to (err_a + err_b) /
/// l_ab, through l_ac, so err_c ~ err_a + (err_a + err_b) l_ac / l_ab. Entering a thin face
/// through its short edge multiplies the error by its aspect ratio; breadth first did that
/// wherever the face tree went, this order takes every point from its best conditioned
/// chain. The estimate only orders the candidates, in units of length (the order does not
/// change with the scale); it grows geometrically with the hops from the root and may
/// overflow to infinity on a long strip, so "placed" is a flag of its own: each (face,
/// corner) is offered at most once and the queue holds at most 3 F. The order depends on the
/// lengths only through comparisons.
template <class Angle>
std::vector<Unfolding_step> unfold(const std::vector<std::array<int, 3>>& corners,
                                   const std::vector<std::array<int, 3>>& face_edges,
                                   const std::vector<double>& lengths, const Angle& angle, int root, std::vector<Uv>& z)
{
  const int points = static_cast<int>(z.size());
  std::vector<Unfolding_step> steps;
  steps.reserve(points);
  const Faces_around_vertices around(corners, points);
  constexpr double eps = std::numeric_limits<double>::epsilon();
  std::vector<double> error(points, 0.0);
  std::vector<char> placed(points, 0);
  const std::array<int, 3>& r = corners[root];
  const double root_length = lengths[face_edges[root][2]];
  z[r[0]] = {0.0, 0.0};
  z[r[1]] = {root_length, 0.0};
  place_corner(r, 2, lengths[face_edges[root][1]], angle(root, 0), z);
  steps.push_back({root, 2});
  for(int p : r)
  {
    error[p] = eps * root_length;
    placed[p] = 1;
  }
  // Candidates: (estimated error of the third point, (face, corner of that point)).
  // A binary heap with the least estimate on top.
  using Candidate = std::pair<double, std::pair<int, int>>;
  std::vector<Candidate> queue;
  const auto later = [](const Candidate& a, const Candidate& b) { return a > b; };
  auto offer_faces_around = [&](int p) {
    for(int i = around.first[p]; i < around.first[p + 1]; ++i)
    {
      const int f = around.faces[i];
      const std::array<int, 3>& w = corners[f];
      for(int c = 0; c < 3; ++c)
      {
        const int a = w[(c + 1) % 3], b = w[(c + 2) % 3];
        if(placed[w[c]] || !placed[a] || !placed[b])
          continue;
        const double l_ab = lengths[face_edges[f][c]], l_ac = lengths[face_edges[f][(c + 2) % 3]];
        queue.push_back({error[a] + (error[a] + error[b]) * l_ac / l_ab + eps * l_ac, {f, c}});
        std::push_heap(queue.begin(), queue.end(), later);
      }
    }
  };
  for(int p : r)
    offer_faces_around(p);
  while(!queue.empty())
  {
    std::pop_heap(queue.begin(), queue.end(), later);
    const auto [estimate, where] = queue.back();
    queue.pop_back();
    const auto [f, c] = where;
    const int third = corners[f][c];
    if(placed[third])
      continue;
    place_corner(corners[f], c, lengths[face_edges[f][(c + 2) % 3]], angle(f, (c + 1) % 3), z);
    steps.push_back({f, c});
    error[third] = estimate;
    placed[third] = 1;
    offer_faces_around(third);
  }
  return steps;
}

/// The metric laid out by unfolding its faces from `root` (`unfold`). `angles` are the
/// metric's own per-face angles (`Curvature_map::face_angles`), which keep full relative
/// precision in faces whose radii differ by e^30; recomputed from the lengths, the tiny
/// angles of such faces lose their digits.
inline std::vector<Uv> layout_by_propagation_from(const internal::Mesh_index& index, const std::vector<double>& lengths,
                                                  const std::vector<Triangle_angles>& angles, int root)
{
  std::vector<Uv> uv(index.number_of_vertices(), Uv{0.0, 0.0});
  if(index.number_of_faces() > 0)
    unfold(
      index.faces, index.face_edges, lengths, [&](int f, int c) { return angles[f].angle[c]; }, root, uv);
  return uv;
}

/// The face whose UV centroid is nearest the centre of the layout's bounding box.
inline int face_nearest_uv_centre(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for(const Uv& p : uv)
    for(int i = 0; i < 2; ++i)
    {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  int best = 0;
  double best_distance = HUGE_VAL;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    double d[2];
    for(int i = 0; i < 2; ++i)
      d[i] =
        (uv[index.faces[f][0]][i] + uv[index.faces[f][1]][i] + uv[index.faces[f][2]][i]) / 3 - 0.5 * (lo[i] + hi[i]);
    if(d[0] * d[0] + d[1] * d[1] < best_distance)
    {
      best_distance = d[0] * d[0] + d[1] * d[1];
      best = f;
    }
  }
  return best;
}

/// Walks the single border loop counter-clockwise with the metric's edge lengths, turning
/// by the boundary curvature k_i (the exterior angle) at each vertex. The closing gap, zero
/// up to rounding when sum k = 2 pi, is spread along the loop.
inline void layout_border(const internal::Mesh_index& index, const std::vector<double>& lengths,
                          const Eigen::VectorXd& k, std::vector<Uv>& uv)
{
  // Border halfedges leave the interior on their right: walk the loop backwards.
  const std::vector<int>& loop = index.boundary_loops.front();
  const std::vector<int>& loop_edges = index.boundary_loop_edges.front();
  const int m = static_cast<int>(loop.size());
  double heading = 0, x = 0, y = 0;
  std::vector<Uv> walk(m + 1);
  for(int s = 0; s < m; ++s)
  {
    const int i = (m - s) % m;            // current vertex, loop[0] first
    const int previous = (i - 1 + m) % m; // next vertex of the backward walk
    walk[s] = {x, y};
    const double l = lengths[loop_edges[previous]];
    x += l * std::cos(heading);
    y += l * std::sin(heading);
    heading += k[loop[previous]];
  }
  walk[m] = {x, y};
  for(int s = 0; s < m; ++s)
  {
    const double t = static_cast<double>(s) / m;
    uv[loop[(m - s) % m]] = {walk[s][0] - t * walk[m][0], walk[s][1] - t * walk[m][1]};
  }
}

/// The harmonic layout's conjugate gradients stop at this residual relative to the right-hand
/// side, or factorize after this many solves.
constexpr double layout_residual = 1e-13;
constexpr int max_layout_preconditioned_solves = 12;

/// Harmonic layout: border walk, then Delta_NN x_N = sum_{j in border} w_ij x_j for the
/// interior. `laplacian` must have the interior vertices as its free set; it is assembled
/// here with the weights `w` of the final metric. When it still holds a factorization of
/// one of Newton's steps, conjugate gradients preconditioned by it solve both coordinates
/// for a few triangular solves, a fraction of a factorization's cost; otherwise, or past
/// their budget, it is refactorized.
template <class SparseSolver>
bool layout_harmonic(const internal::Mesh_index& index, const std::vector<double>& lengths, const Eigen::VectorXd& k,
                     const std::vector<double>& w, Dynamic_laplacian<SparseSolver>& laplacian, std::vector<Uv>& uv,
                     std::string& message)
{
  uv.assign(index.number_of_vertices(), Uv{0.0, 0.0});
  if(index.number_of_boundary_loops() != 1)
  {
    message = "the harmonic layout needs exactly one boundary loop";
    return false;
  }
  layout_border(index, lengths, k, uv);
  const int n = laplacian.size();
  if(n == 0)
    return true;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    const int ia = laplacian.free_index(a), ib = laplacian.free_index(b);
    if(ia >= 0 && ib < 0)
      rhs.row(ia) += w[e] * Eigen::RowVector2d(uv[b][0], uv[b][1]);
    if(ib >= 0 && ia < 0)
      rhs.row(ib) += w[e] * Eigen::RowVector2d(uv[a][0], uv[a][1]);
  }
  laplacian.assemble(w);
  Eigen::MatrixXd x;
  int solves = 0;
  const bool solved = laplacian.has_factorization() &&
                      laplacian.solve_preconditioned(rhs, x, layout_residual, max_layout_preconditioned_solves, solves);
  if(!solved)
  {
    if(!laplacian.factorize())
    {
      message = "the layout Laplacian could not be factorized";
      return false;
    }
    x = laplacian.solve(rhs);
  }
  if(!x.allFinite())
  {
    message = "the harmonic layout produced non-finite coordinates";
    return false;
  }
  for(int i = 0; i < n; ++i)
    uv[laplacian.vertex(i)] = {x(i, 0), x(i, 1)};
  return true;
}

/// What every layout is checked for.
struct Layout_check
{
  int flipped_faces = 0; ///< faces with non-positive signed area
  /// max_e |uv length - metric length| / metric length, after forgiving 64 units in the last
  /// place of the edge's coordinates: a nearly closed surface squeezes whole protrusions
  /// into 1e-12 of its hole, where an edge spans only millions of representable steps and
  /// the unfolding cannot be exact to more than ~1e-7 of its length.
  double max_relative_length_error = 0;
};

/// Faces of `index` whose UV triangle does not have positive area.
inline int count_flipped_faces(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  int flipped = 0;
  for(const auto& f : index.faces)
    flipped += !(internal::twice_signed_area(uv[f[0]], uv[f[1]], uv[f[2]]) > 0);
  return flipped;
}

/// The layout `uv` of `index` scaled about the origin to its 3D scale: UV area = 3D area (in
/// the index's normalised units). A conformal map keeps shapes, not sizes: this is the size
/// at which a texel covers the same 3D area on every chart.
inline void scale_to_3d_area(const internal::Mesh_index& index, std::vector<Uv>& uv)
{
  double uv_area = 0, area = 0;
  for(const auto& f : index.faces)
  {
    uv_area += 0.5 * internal::twice_signed_area(uv[f[0]], uv[f[1]], uv[f[2]]);
    area += internal::triangle_area(index.points[f[0]], index.points[f[1]], index.points[f[2]]);
  }
  if(!(uv_area > 0 && area > 0 && std::isfinite(uv_area)))
    return; // a layout folded over itself, left as it is for its checks to tell
  const double scale = std::sqrt(area / uv_area);
  for(Uv& p : uv)
    p = {p[0] * scale, p[1] * scale};
}

inline Layout_check check_layout(const internal::Mesh_index& index, const std::vector<double>& lengths,
                                 const std::vector<Uv>& uv)
{
  Layout_check check;
  check.flipped_faces = count_flipped_faces(index, uv);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const Uv &a = uv[index.edges[e][0]], &b = uv[index.edges[e][1]];
    const double ulp = std::numeric_limits<double>::epsilon() *
                       std::max({std::abs(a[0]), std::abs(a[1]), std::abs(b[0]), std::abs(b[1])});
    const double error =
      std::max(std::abs(std::hypot(a[0] - b[0], a[1] - b[1]) - lengths[e]) - 64.0 * ulp, 0.0) / lengths[e];
    check.max_relative_length_error =
      std::max(check.max_relative_length_error, std::isfinite(error) ? error : HUGE_VAL);
  }
  return check;
}

/// The propagation layout, unfolded from the middle of the chart where that is more exact.
/// Each vertex the unfolding goes around is flat only to Newton's residual (~1e-14 rad), so
/// the direction drifts with the number of vertices between an edge and the root, and the
/// position error with its distance from the root: a long cut disk closes its seams better
/// unfolded from the middle of its first layout than from the face farthest from the border
/// in face hops. But a nearly closed disk squeezes most of its surface into a speck around
/// that farthest face, which only keeps its digits near the origin, where re-rooting would
/// lose them: the more exact of the two layouts is kept.
inline std::vector<Uv> layout_by_propagation(const internal::Mesh_index& index, const std::vector<double>& lengths,
                                             const std::vector<Triangle_angles>& angles)
{
  std::vector<Uv> first = layout_by_propagation_from(index, lengths, angles, central_face(index));
  if(index.number_of_faces() == 0)
    return first;
  std::vector<Uv> second = layout_by_propagation_from(index, lengths, angles, face_nearest_uv_centre(index, first));
  return check_layout(index, lengths, second).max_relative_length_error <
             check_layout(index, lengths, first).max_relative_length_error
           ? second
           : first;
}

} // namespace ICM

#endif // ICM_LAYOUT_LAYOUT_H
