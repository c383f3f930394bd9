// Copyright (c) the ICM authors.
//
// The checks and repairs that make a triangle mesh of a polygon soup read from a file
// (read_triangle_mesh.h): which points no polygon uses, how the faces meet along each edge
// (an edge in at most two faces, the faces around each vertex in fans, orientations that can
// be made to agree), whether every coordinate difference is a finite double, which triangles
// have no area and which polygons can be triangulated. Each check returns why the soup is
// refused, naming the faces (with their lines) and the vertices (as the file numbers them),
// or nothing.

#ifndef ICM_IO_SOUP_CHECKS_H
#define ICM_IO_SOUP_CHECKS_H

#include <ICM/IO/Soup_reading.h>
#include <ICM/Status.h>
#include <ICM/internal/Box_pairs.h>
#include <ICM/internal/Exact_predicates.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

/// Drops the points of no polygon, keeping the others in their order (CGAL's
/// `remove_isolated_points_in_polygon_soup` moves the last points into the holes, which
/// would renumber vertices the user may refer to). Returns the old index of each point kept.
inline std::vector<std::size_t> remove_isolated_points_in_order(Polygon_soup& soup, std::vector<std::size_t>& isolated)
{
  std::vector<char> used(soup.points.size(), 0);
  for(const auto& polygon : soup.polygons)
    for(std::size_t i : polygon)
      used[i] = 1;
  std::vector<std::size_t> kept, new_index(soup.points.size());
  std::size_t next = 0;
  for(std::size_t i = 0; i < soup.points.size(); ++i)
  {
    if(!used[i])
    {
      isolated.push_back(i);
      continue;
    }
    new_index[i] = next;
    soup.points[next++] = soup.points[i];
    kept.push_back(i);
  }
  soup.points.resize(next);
  for(auto& polygon : soup.polygons)
    for(std::size_t& i : polygon)
      i = new_index[i];
  return kept;
}

/// Union-find over the corners of a soup, to group the corners of one vertex into fans.
class Corner_sets
{
public:
  explicit Corner_sets(std::size_t n) : parent_(n)
  {
    for(std::size_t i = 0; i < n; ++i)
      parent_[i] = i;
  }
  std::size_t find(std::size_t i)
  {
    while(parent_[i] != i)
      i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

private:
  std::vector<std::size_t> parent_;
};

/// Union-find over the polygons of a soup that also keeps, for each polygon, whether it runs
/// against the first polygon of its set: two polygons that run along their common edge the
/// same way must end up on opposite sides of that parity. A pair that cannot is the proof
/// that the surface cannot be oriented.
class Orientation_sets
{
public:
  explicit Orientation_sets(std::size_t n) : parent_(n), against_parent_(n, 0)
  {
    for(std::size_t i = 0; i < n; ++i)
      parent_[i] = i;
  }

  /// The set of `i`, and in `against` whether `i` runs against the set's root.
  std::size_t find(std::size_t i, bool& against)
  {
    std::size_t root = i;
    bool parity = false;
    for(; parent_[root] != root; root = parent_[root])
      parity = parity != (against_parent_[root] != 0);
    against = parity;
    // Every polygon on the way now points at the root, with its parity to it.
    while(parent_[i] != root && parent_[i] != i)
    {
      const std::size_t next = parent_[i];
      const bool own = against_parent_[i] != 0;
      parent_[i] = root;
      against_parent_[i] = parity ? 1 : 0;
      parity = parity != own;
      i = next;
    }
    return root;
  }

  /// Puts `a` and `b` in one set, opposite when `opposite`; false when they are already in
  /// one set with the other parity.
  bool join(std::size_t a, std::size_t b, bool opposite)
  {
    bool against_a = false, against_b = false;
    const std::size_t root_a = find(a, against_a), root_b = find(b, against_b);
    if(root_a == root_b)
      return (against_a != against_b) == opposite;
    parent_[root_a] = root_b;
    against_parent_[root_a] = (against_a != against_b) != opposite ? 1 : 0;
    return true;
  }

private:
  std::vector<std::size_t> parent_;
  std::vector<char> against_parent_;
};

/// What `check_edges()` found when it refused nothing.
struct Edge_check
{
  std::string refusal;                ///< empty, or why the soup cannot be a manifold
  bool has_singular_vertices = false; ///< a vertex whose faces form more than one fan
  bool has_disagreeing_faces = false; ///< two faces run along their common edge the same way
  /// With disagreeing faces, the connected component of each polygon (polygons joined across
  /// edges), named by one of its polygons.
  std::vector<std::size_t> component;
};

/// "the edge between vertices 3 and 9", as the file numbers them.
inline std::string edge_name(std::size_t a, std::size_t b, const std::vector<std::size_t>& file_vertex)
{
  return "the edge between vertices " + std::to_string(file_vertex[a]) + " and " + std::to_string(file_vertex[b]);
}

/// Whether two polygons have the same corners, in any order.
inline bool same_corners(std::vector<std::size_t> a, std::vector<std::size_t> b)
{
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

/// One side of a polygon: the edge it runs along and which way.
struct Polygon_side
{
  std::size_t low, high, polygon, corner; // corner: where the side starts in its polygon
  bool forward;                           // low -> high in the polygon's order
  bool operator<(const Polygon_side& o) const
  {
    return low != o.low ? low < o.low : high != o.high ? high < o.high : polygon < o.polygon;
  }
};

/// Every side of every polygon, sorted by edge; `first_corner[p]` numbers the first corner
/// of polygon `p` among all corners.
inline std::vector<Polygon_side> sorted_sides(const Polygon_soup& soup, std::vector<std::size_t>& first_corner)
{
  first_corner.assign(soup.polygons.size() + 1, 0);
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
    first_corner[p + 1] = first_corner[p] + soup.polygons[p].size();
  std::vector<Polygon_side> sides;
  sides.reserve(first_corner.back());
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
  {
    const auto& polygon = soup.polygons[p];
    for(std::size_t c = 0; c < polygon.size(); ++c)
    {
      const std::size_t a = polygon[c], b = polygon[(c + 1) % polygon.size()];
      sides.push_back({std::min(a, b), std::max(a, b), p, c, a < b});
    }
  }
  std::sort(sides.begin(), sides.end());
  return sides;
}

/// Why the two faces of sides `s` and `t` (one edge) cannot be joined, or empty; joins them
/// in `orientations` and their corners at either end of the edge in `fans`.
inline std::string join_across_edge(const Polygon_soup& soup, const Polygon_side& s, const Polygon_side& t,
                                    const std::vector<std::size_t>& first_corner,
                                    const std::vector<std::size_t>& file_vertex, Corner_sets& fans,
                                    Orientation_sets& orientations, Edge_check& result)
{
  const bool same_way = s.forward == t.forward;
  if(same_way && same_corners(soup.polygons[s.polygon], soup.polygons[t.polygon]))
    return soup.describe_polygon(t.polygon) + " has the corners of " + soup.describe_polygon(s.polygon) +
           ": a face listed twice";
  if(!orientations.join(s.polygon, t.polygon, same_way))
    return soup.describe_polygon(s.polygon) + " and " + soup.describe_polygon(t.polygon) + " run along " +
           edge_name(s.low, s.high, file_vertex) +
           " against any orientation the faces around them can take: the surface is not orientable "
           "(a Moebius strip, for one)";
  result.has_disagreeing_faces = result.has_disagreeing_faces || same_way;
  // The corner of a side at its start (`at_end` false) or at its end.
  auto corner = [&](const Polygon_side& side, bool at_end) {
    const std::size_t n = soup.polygons[side.polygon].size();
    return first_corner[side.polygon] + (at_end ? (side.corner + 1) % n : side.corner);
  };
  // Across the edge the corners at one of its vertices are one fan: the start of one side
  // and the end of the other when the faces run opposite ways, both starts when they agree.
  fans.join(corner(s, false), corner(t, !same_way));
  fans.join(corner(s, true), corner(t, same_way));
  return {};
}

/// Refuses an edge in more than two faces, a face listed twice, or faces whose orientations
/// cannot be made to agree (a surface that is not orientable): the repairs stop at vertices
/// and orientations. Otherwise says whether some vertex has several fans of faces and whether
/// some faces must be reversed, so that CGAL's orient_polygon_soup (the costliest step of
/// reading) runs only when it has something to do. `file_vertex` names vertices as the file
/// does.
inline Edge_check check_edges(const Polygon_soup& soup, const std::vector<std::size_t>& file_vertex)
{
  std::vector<std::size_t> first_corner;
  const std::vector<Polygon_side> sides = sorted_sides(soup, first_corner);
  Corner_sets fans(first_corner.back());
  Orientation_sets orientations(soup.polygons.size());
  Edge_check result;
  for(std::size_t s = 0; s < sides.size();)
  {
    std::size_t t = s + 1;
    while(t < sides.size() && sides[t].low == sides[s].low && sides[t].high == sides[s].high)
      ++t;
    if(t - s > 2)
    {
      result.refusal =
        edge_name(sides[s].low, sides[s].high, file_vertex) + " is shared by " + std::to_string(t - s) + " faces (" +
        soup.describe_polygon(sides[s].polygon) + ", " + soup.describe_polygon(sides[s + 1].polygon) + ", " +
        soup.describe_polygon(sides[s + 2].polygon) + (t - s > 3 ? ", ..." : "") + "): a non-manifold edge";
      return result;
    }
    if(t - s == 2)
      result.refusal =
        join_across_edge(soup, sides[s], sides[s + 1], first_corner, file_vertex, fans, orientations, result);
    if(!result.refusal.empty())
      return result;
    s = t;
  }
  std::vector<std::size_t> fan_of(soup.points.size(), first_corner.back());
  for(std::size_t p = 0; p < soup.polygons.size() && !result.has_singular_vertices; ++p)
    for(std::size_t c = 0; c < soup.polygons[p].size(); ++c)
    {
      std::size_t& fan = fan_of[soup.polygons[p][c]];
      const std::size_t root = fans.find(first_corner[p] + c);
      if(fan != first_corner.back() && fan != root)
        result.has_singular_vertices = true;
      fan = root;
    }
  bool against = false;
  if(result.has_disagreeing_faces)
    for(std::size_t p = 0; p < soup.polygons.size(); ++p)
      result.component.push_back(orientations.find(p, against));
  return result;
}

/// Refuses a soup whose extent along some axis is beyond a double: the difference of two of
/// its coordinates (an edge vector) would overflow, and no length, area or normalisation
/// could be computed.
inline std::string check_extent(const Polygon_soup& soup)
{
  if(soup.points.empty())
    return {};
  for(int k = 0; k < 3; ++k)
  {
    double low = soup.points[0][k], high = low;
    for(const auto& p : soup.points)
    {
      low = std::min(low, p[k]);
      high = std::max(high, p[k]);
    }
    if(!std::isfinite(high - low))
      return std::string("the mesh's extent along ") + "xyz"[k] + ", from " + message_number(low, 3) + " to " +
             message_number(high, 3) +
             ", is beyond the range of a double (the difference of two coordinates "
             "overflows): scale the mesh down";
  }
  return {};
}

/// Whether triangle `a b c` has (relatively) no area: area <= 1e-14 longest edge^2, the test of
/// `Mesh_index`. The edge vectors are divided by their largest coordinate first, so that the
/// squares neither underflow nor overflow whatever the triangle's size and however far it is
/// from the rest of the mesh. `at_one_point` tells a triangle whose corners coincide from
/// one whose corners are collinear. \pre the soup passed `check_extent()`.
inline bool is_degenerate_triangle(const Polygon_soup::Point_3& a, const Polygon_soup::Point_3& b,
                                   const Polygon_soup::Point_3& c, bool& at_one_point)
{
  double e[3][3];
  double largest = 0;
  for(int k = 0; k < 3; ++k)
  {
    e[0][k] = b[k] - a[k];
    e[1][k] = c[k] - a[k];
    e[2][k] = c[k] - b[k];
    for(int i = 0; i < 3; ++i)
      largest = std::max(largest, std::abs(e[i][k]));
  }
  at_one_point = !(largest > 0);
  if(at_one_point)
    return true;
  for(auto& edge : e)
    for(double& x : edge)
      x /= largest;
  const double n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                       e[0][0] * e[1][1] - e[0][1] * e[1][0]};
  const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double longest = 0;
  for(const auto& edge : e)
    longest = std::max(longest, edge[0] * edge[0] + edge[1] * edge[1] + edge[2] * edge[2]);
  return !(area > 1e-14 * longest);
}

/// Refuses the first triangle with (relatively) no area.
inline std::string check_triangle_areas(const Polygon_soup& soup)
{
  for(std::size_t f = 0; f < soup.polygons.size(); ++f)
  {
    const auto& t = soup.polygons[f];
    bool at_one_point = false;
    if(t.size() == 3 && is_degenerate_triangle(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]], at_one_point))
      return soup.describe_polygon(f) + " is degenerate (zero area: its corners are " +
             (at_one_point ? "at one point)" : "collinear)");
  }
  return {};
}

/// The corners of polygon `p` on its best-fit plane, the plane of Newell's normal (for a
/// plane polygon, its own plane, along which CGAL's triangulate_face projects it too), in
/// units of its largest coordinate difference. Empty when that normal is zero: the corners
/// are collinear, or the polygon's loops cancel out.
inline std::vector<Uv> corners_on_best_fit_plane(const Polygon_soup& soup, std::size_t p)
{
  const auto& polygon = soup.polygons[p];
  const auto& origin = soup.points[polygon[0]];
  std::vector<std::array<double, 3>> x(polygon.size());
  double largest = 0;
  for(std::size_t i = 0; i < polygon.size(); ++i)
    for(int k = 0; k < 3; ++k)
    {
      x[i][k] = soup.points[polygon[i]][k] - origin[k];
      largest = std::max(largest, std::abs(x[i][k]));
    }
  for(auto& corner : x)
    for(double& c : corner)
      c /= largest > 0 ? largest : 1;
  std::array<double, 3> n{0, 0, 0};
  for(std::size_t i = 0; i < x.size(); ++i)
  {
    const auto& a = x[i];
    const auto& b = x[(i + 1) % x.size()];
    n[0] += a[1] * b[2] - a[2] * b[1];
    n[1] += a[2] * b[0] - a[0] * b[2];
    n[2] += a[0] * b[1] - a[1] * b[0];
  }
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if(!(length > 1e-14))
    return {};
  for(double& c : n)
    c /= length;
  // Two unit vectors across the normal: u along the axis the normal leans on least.
  const int axis = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0
                   : std::abs(n[1]) <= std::abs(n[2])                                   ? 1
                                                                                        : 2;
  std::array<double, 3> u{0, 0, 0};
  u[axis] = 1;
  const double along = u[axis] * n[axis];
  for(int k = 0; k < 3; ++k)
    u[k] -= along * n[k];
  const double u_length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for(double& c : u)
    c /= u_length;
  const std::array<double, 3> v{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  std::vector<Uv> plane(x.size());
  for(std::size_t i = 0; i < x.size(); ++i)
    plane[i] = {x[i][0] * u[0] + x[i][1] * u[1] + x[i][2] * u[2], x[i][0] * v[0] + x[i][1] * v[1] + x[i][2] * v[2]};
  return plane;
}

/// Two sides of a polygon that meet where they should not, by the corners they start at.
struct Side_meeting
{
  std::size_t first = 0, second = 0;
  bool found = false;
};

/// Two sides of the plane polygon `q` that meet other than at their common corner (a side
/// folding back onto the next counts), or none. Only sides whose bounding boxes meet are
/// compared, the pairs found through a box tree: n log n for n sides plus the pairs of
/// meeting boxes, even when many sides share one abscissa (a tall polygon's long vertical
/// sides), where a sweep along one axis compares them all with each other.
inline Side_meeting sides_that_meet(const std::vector<Uv>& q)
{
  const std::size_t n = q.size();
  auto end_of = [&](std::size_t side) { return q[(side + 1) % n]; };
  std::vector<Box2> boxes(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    boxes[i] = Box2::around(q[i]);
    boxes[i].extend(end_of(i));
  }
  auto folds_back_at_corner_after = [&](std::size_t side) {
    const auto &a0 = q[side], &corner = q[(side + 1) % n], &a2 = q[(side + 2) % n];
    return orientation(a0, corner, a2) == 0 && !collinear_are_ordered_along_line(a0, corner, a2);
  };
  Side_meeting meeting;
  Box_tree(boxes).for_each_meeting_pair([&](int i, int j) {
    const std::size_t first = static_cast<std::size_t>(i), second = static_cast<std::size_t>(j);
    bool meet = false;
    if(second == first + 1)
      meet = folds_back_at_corner_after(first); // neighbours meet at their common corner only
    else if(first == 0 && second == n - 1)
      meet = folds_back_at_corner_after(second);
    else
      meet = segments_meet(q[first], end_of(first), q[second], end_of(second));
    if(meet)
      meeting = {first, second, true};
    return !meet;
  });
  return meeting;
}

/// Why polygon `p` cannot be triangulated, or empty. CGAL's triangulate_face projects a
/// polygon on the plane of its normal and builds a constrained Delaunay triangulation of its
/// sides; a polygon whose sides cross there is no boundary of a region (and CGAL 5.5 crashes
/// on some), so it is refused here, naming two sides that meet.
inline std::string why_not_triangulable(const Polygon_soup& soup, std::size_t p,
                                        const std::vector<std::size_t>& file_vertex)
{
  const auto& polygon = soup.polygons[p];
  const std::string face = soup.describe_polygon(p) + " (" + std::to_string(polygon.size()) + " sides)";
  const std::vector<Uv> plane = corners_on_best_fit_plane(soup, p);
  if(plane.empty())
    return face + " cannot be triangulated: its corners do not span a plane polygon (they are collinear, or its "
                  "loops cancel out)";
  for(std::size_t i = 0; i < plane.size(); ++i)
    if(plane[i] == plane[(i + 1) % plane.size()])
      return face + " cannot be triangulated: its corners " + std::to_string(file_vertex[polygon[i]]) + " and " +
             std::to_string(file_vertex[polygon[(i + 1) % polygon.size()]]) + " are at one point of its plane";
  const Side_meeting meeting = sides_that_meet(plane);
  if(!meeting.found)
    return {};
  auto side = [&](std::size_t i) {
    return "its side from vertex " + std::to_string(file_vertex[polygon[i]]) + " to vertex " +
           std::to_string(file_vertex[polygon[(i + 1) % polygon.size()]]);
  };
  return face + " cannot be triangulated: " + side(meeting.first) + " meets " + side(meeting.second) +
         " on its best-fit plane (the polygon crosses itself, it is not simple)";
}

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_SOUP_CHECKS_H
