// Global overlaps of a layout: where the UV map of a disk folds over itself although every
// face is positively oriented.
//
// A locally injective layout (no flipped face) can still fail to be injective: a horse's leg
// laid out by a conformal map may swing around and lie over another leg. When every face is
// positively oriented and the angles around every interior vertex sum to 2 pi (the layout of
// a metric flat inside, as ICM's), the layout is injective exactly when the image of the
// border is a simple curve. Counting the pairs of border edges that meet in the plane
// therefore measures the overlap in O(n log n + k), n border edges and k candidate pairs,
// instead of testing every pair of faces.
//
// The pipeline calls it on finite layouts only; a caller's bad input (a UV array of the wrong
// size, a non-finite coordinate) is reported by std::invalid_argument, as in Distortion.h.
//
// Robustness: candidate pairs are the pairs of meeting bounding boxes (Box_pairs.h), which
// are exact for double coordinates; every candidate is then decided by the exact orientation
// (Exact_predicates.h). A layout whose two border vertices merely touch is therefore
// reported, however close to the rounding error it is.

#ifndef ICM_LAYOUT_BORDER_OVERLAPS_H
#define ICM_LAYOUT_BORDER_OVERLAPS_H

#include <ICM/internal/Box_pairs.h>
#include <ICM/internal/Exact_predicates.h>
#include <ICM/internal/Mesh_index.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ICM {

/// Pairs of border edges whose UV segments meet.
struct Border_overlaps
{
  /// Number of pairs in `pairs`.
  int crossing_pairs = 0;
  /// Edge ids `(e, f)` of the index, `e < f`, sorted: a deterministic list, whatever order
  /// the box tree visits the candidates in.
  std::vector<std::pair<int, int>> pairs;

  bool empty() const { return crossing_pairs == 0; }
};

namespace internal {

/// Rejects input the exact predicates cannot decide: NaN compares false with everything, so a
/// non-finite coordinate would silently drop its edges from every box.
inline void check_uv_input(const Mesh_index& index, const std::vector<Uv>& uv, const char* caller)
{
  if(uv.size() != static_cast<std::size_t>(index.number_of_vertices()))
    throw std::invalid_argument(std::string(caller) + ": " + std::to_string(uv.size()) + " UVs for " +
                                std::to_string(index.number_of_vertices()) + " vertices");
  for(std::size_t v = 0; v < uv.size(); ++v)
    if(!std::isfinite(uv[v][0]) || !std::isfinite(uv[v][1]))
      throw std::invalid_argument(std::string(caller) + ": vertex " + std::to_string(v) + " has a non-finite UV");
}

/// Whether border edges `e` and `f` meet beyond what the mesh itself makes them share.
/// Edges with a common vertex always meet there; they overlap only when they leave that
/// vertex along the same ray (collinear, the common vertex not between the two far ends).
inline bool border_edges_meet(const Mesh_index& index, const std::vector<Uv>& uv, int e, int f)
{
  const auto& a = index.edges[e];
  const auto& b = index.edges[f];
  for(int i = 0; i < 2; ++i)
    for(int j = 0; j < 2; ++j)
      if(a[i] == b[j])
      {
        const Uv &shared = uv[a[i]], &far_a = uv[a[1 - i]], &far_b = uv[b[1 - j]];
        return orientation(shared, far_a, far_b) == 0 && !collinear_are_ordered_along_line(far_a, shared, far_b);
      }
  return segments_meet(uv[a[0]], uv[a[1]], uv[b[0]], uv[b[1]]);
}

/// Sorted `(min, max)` pairs, so that results do not depend on the traversal order.
inline std::vector<std::pair<int, int>> normalized_pairs(std::vector<std::pair<int, int>> pairs)
{
  for(auto& p : pairs)
    if(p.first > p.second)
      std::swap(p.first, p.second);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// Whether the line of some edge of triangle `t` (of orientation `o`, so its interior is on
/// the `o` side of each edge) has no corner of `u` strictly on the interior side: that line
/// then separates the two interiors.
inline bool separated_by_an_edge_of(const std::array<Uv, 3>& t, int o, const std::array<Uv, 3>& u)
{
  for(int i = 0; i < 3; ++i)
  {
    const Uv &p = t[i], &q = t[(i + 1) % 3];
    if(orientation(p, q, u[0]) != o && orientation(p, q, u[1]) != o && orientation(p, q, u[2]) != o)
      return true;
  }
  return false;
}

/// Whether the open interiors of two triangles intersect, exactly. Two convex polygons with
/// disjoint interiors are separated by the line of one of their edges, so six edge lines
/// decide it; sharing a vertex or an edge, or touching, is not an overlap. A zero-area
/// triangle has no interior and overlaps nothing.
inline bool triangle_interiors_overlap(const std::array<Uv, 3>& t, const std::array<Uv, 3>& u)
{
  const int ot = orientation(t[0], t[1], t[2]);
  const int ou = orientation(u[0], u[1], u[2]);
  if(ot == 0 || ou == 0)
    return false;
  return !separated_by_an_edge_of(t, ot, u) && !separated_by_an_edge_of(u, ou, t);
}

inline std::array<Uv, 3> uv_triangle(const Mesh_index& index, const std::vector<Uv>& uv, int f)
{
  const auto& v = index.faces[f];
  return {uv[v[0]], uv[v[1]], uv[v[2]]};
}

/// Face pairs of `faces` whose UV interiors overlap; stops after the first one when
/// `first_only`.
inline std::vector<std::pair<int, int>> face_overlaps(const Mesh_index& index, const std::vector<Uv>& uv,
                                                      const std::vector<int>& faces, bool first_only)
{
  check_uv_input(index, uv, "face overlaps");
  std::vector<Box2> boxes;
  boxes.reserve(faces.size());
  for(int f : faces)
  {
    if(f < 0 || f >= index.number_of_faces())
      throw std::invalid_argument("face overlaps: no face " + std::to_string(f));
    const auto& v = index.faces[f];
    Box2 box = Box2::around(uv[v[0]]);
    box.extend(uv[v[1]]);
    box.extend(uv[v[2]]);
    boxes.push_back(box);
  }
  std::vector<std::pair<int, int>> pairs;
  Box_tree(boxes).for_each_meeting_pair([&](int i, int j) {
    if(triangle_interiors_overlap(uv_triangle(index, uv, faces[i]), uv_triangle(index, uv, faces[j])))
      pairs.emplace_back(faces[i], faces[j]);
    return !(first_only && !pairs.empty());
  });
  return normalized_pairs(std::move(pairs));
}

} // namespace internal

/// Counts the pairs of border edges (`edge_faces[e][1] < 0`, every boundary loop together)
/// whose UV segments meet: they cross, touch, or one passes through a vertex of the other.
/// Two edges with a common vertex are counted only when they also overlap along a segment,
/// since meeting at their own vertex is what the mesh prescribes.
///
/// With no flipped face, a non-empty result is exactly a global overlap of the layout; with
/// flipped faces the border may be simple and the layout still folded (see
/// `has_overlapping_faces`).
///
/// \pre `uv.size() == index.number_of_vertices()` and every UV is finite (else
///      std::invalid_argument).
inline Border_overlaps count_border_overlaps(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  internal::check_uv_input(index, uv, "count_border_overlaps");
  std::vector<int> border;
  std::vector<internal::Box2> boxes;
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(index.edge_faces[e][1] < 0)
    {
      border.push_back(e);
      internal::Box2 box = internal::Box2::around(uv[index.edges[e][0]]);
      box.extend(uv[index.edges[e][1]]);
      boxes.push_back(box);
    }

  std::vector<std::pair<int, int>> pairs;
  internal::Box_tree(boxes).for_each_meeting_pair([&](int i, int j) {
    if(internal::border_edges_meet(index, uv, border[i], border[j]))
      pairs.emplace_back(border[i], border[j]);
    return true;
  });

  Border_overlaps result;
  result.pairs = internal::normalized_pairs(std::move(pairs));
  result.crossing_pairs = static_cast<int>(result.pairs.size());
  return result;
}

/// The pairs `(f, g)`, `f < g`, of faces of `faces` (face ids of `index`) whose UV triangles
/// overlap in their interiors. Faces that share a vertex or an edge and lie side by side do
/// not overlap; a flipped face overlaps the neighbours it folds over, and a zero-area UV
/// triangle overlaps nothing. Complements `count_border_overlaps` when some faces are
/// flipped, or when only a region of the layout matters.
///
/// \pre `uv.size() == index.number_of_vertices()`, every UV finite, every id of `faces` a
///      face of `index` (else std::invalid_argument).
inline std::vector<std::pair<int, int>> overlapping_face_pairs(const internal::Mesh_index& index,
                                                               const std::vector<Uv>& uv, const std::vector<int>& faces)
{
  return internal::face_overlaps(index, uv, faces, false);
}

/// `overlapping_face_pairs` over every face of `index`.
inline std::vector<std::pair<int, int>> overlapping_face_pairs(const internal::Mesh_index& index,
                                                               const std::vector<Uv>& uv)
{
  std::vector<int> all(index.number_of_faces());
  for(int f = 0; f < index.number_of_faces(); ++f)
    all[f] = f;
  return overlapping_face_pairs(index, uv, all);
}

/// Whether any two faces of `faces` overlap in UV; stops at the first overlapping pair.
/// \pre as `overlapping_face_pairs`.
inline bool has_overlapping_faces(const internal::Mesh_index& index, const std::vector<Uv>& uv,
                                  const std::vector<int>& faces)
{
  return !internal::face_overlaps(index, uv, faces, true).empty();
}

} // namespace ICM

#endif // ICM_LAYOUT_BORDER_OVERLAPS_H
