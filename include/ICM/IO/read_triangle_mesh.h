// Copyright (c) the ICM authors.
//
// From an untrusted file to a triangle mesh the parameterizers can take, with the repairs
// users expect and nothing else: the file is read as a polygon soup (read_polygon_soup.h),
// vertices in no face are dropped, a vertex whose faces form several fans is split into one
// vertex per fan, polygons are triangulated when asked to. Everything else that would not
// make a consistently oriented 2-manifold (an edge in three faces, two faces that disagree
// on their orientation, a degenerate face, polygons when triangulation was not asked for) is
// refused, naming the faces (and their lines) and the vertices at fault. Every repair made
// is listed in the report.
//
// Vertex numbering of the result: the file's vertices in the file's order without the
// dropped ones, then one more vertex per extra fan of each split vertex (STL: corners at the
// same point are one vertex, numbered in the order they first appear). `file_vertex` in the
// report maps each vertex of the mesh back to the file.

#ifndef ICM_IO_READ_TRIANGLE_MESH_H
#define ICM_IO_READ_TRIANGLE_MESH_H

#include <ICM/IO/read_polygon_soup.h>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <vector>

namespace ICM {
namespace IO {

/// What `read_triangle_mesh()` may repair, and the reader's limits.
struct Mesh_reading_options
{
  /// Split polygons into triangles (`CGAL::Polygon_mesh_processing::triangulate_face`);
  /// otherwise a polygon is refused.
  bool triangulate = false;
  /// Refuse a triangle of (relatively) zero area, naming it; the parameterizers refuse them
  /// anyway, but without the file's line.
  bool refuse_degenerate_faces = true;
  Soup_reading_limits limits;
};

/// What `read_triangle_mesh()` read, repaired or refused.
struct Mesh_reading_report
{
  std::string message;                  ///< empty on success, else the reason of the refusal
  std::size_t file_vertices = 0, file_faces = 0;
  std::vector<std::size_t> isolated_vertices;  ///< file indices of the vertices dropped
  std::vector<std::size_t> split_vertices;     ///< file index of each vertex copy added
  std::size_t triangulated_faces = 0;          ///< polygons split into triangles
  std::size_t non_triangle_faces = 0;          ///< polygons found (refused unless triangulated)
  /// The file's index of each vertex of the mesh, in `vertices(mesh)` order.
  std::vector<std::size_t> file_vertex;

  bool ok() const { return message.empty(); }

  /// One line per repair made, for a user: "dropped 2 isolated vertices (3, 9)".
  std::vector<std::string> repairs() const
  {
    std::vector<std::string> lines;
    if(!isolated_vertices.empty())
      lines.push_back("dropped " + std::to_string(isolated_vertices.size()) + " isolated vert" +
                      (isolated_vertices.size() == 1 ? "ex" : "ices") + " (in no face): " +
                      list_of(isolated_vertices));
    if(!split_vertices.empty())
    {
      std::vector<std::size_t> distinct = split_vertices;
      std::sort(distinct.begin(), distinct.end());
      distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
      lines.push_back("split " + std::to_string(distinct.size()) + " non-manifold vert" +
                      (distinct.size() == 1 ? "ex" : "ices") + " into one vertex per fan of faces (" +
                      std::to_string(split_vertices.size()) + " added): " + list_of(distinct));
    }
    if(triangulated_faces > 0)
      lines.push_back("triangulated " + std::to_string(triangulated_faces) + " polygon" +
                      (triangulated_faces == 1 ? "" : "s"));
    return lines;
  }

private:
  /// "3, 9, 12" or "3, 9, 12, ... (40 in all)".
  static std::string list_of(const std::vector<std::size_t>& v)
  {
    std::string s;
    for(std::size_t i = 0; i < v.size() && i < 10; ++i)
      s += (i ? ", " : "") + std::to_string(v[i]);
    if(v.size() > 10)
      s += ", ... (" + std::to_string(v.size()) + " in all)";
    return s;
  }
};

} // namespace IO

namespace internal {
namespace reading {

/// Drops the points of no polygon, keeping the others in their order (CGAL's
/// `remove_isolated_points_in_polygon_soup` moves the last points into the holes, which
/// would renumber vertices the user may refer to). Returns the old index of each point kept.
inline std::vector<std::size_t> remove_isolated_points_in_order(Polygon_soup& soup,
                                                                std::vector<std::size_t>& isolated)
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

/// What `check_edges()` found when it refused nothing.
struct Edge_check
{
  std::string refusal;               ///< empty, or why the soup cannot be a manifold
  bool has_singular_vertices = false; ///< a vertex whose faces form more than one fan
};

/// Refuses an edge in more than two faces, or in two faces that run along it the same way
/// (inconsistent orientations, or a surface that cannot be oriented): the repairs stop at
/// vertices. Otherwise says whether some vertex has several fans of faces, so that the
/// splitting (CGAL's orient_polygon_soup, the costliest step of reading) runs only when it
/// has something to do. `file_vertex` names vertices as the file does.
inline Edge_check check_edges(const Polygon_soup& soup, const std::vector<std::size_t>& file_vertex)
{
  struct Side
  {
    std::size_t low, high, polygon, corner; // corner: where the side starts in its polygon
    bool forward;                            // low -> high in the polygon's order
    bool operator<(const Side& o) const
    {
      return low != o.low ? low < o.low : high != o.high ? high < o.high : polygon < o.polygon;
    }
  };
  std::vector<std::size_t> first_corner(soup.polygons.size() + 1, 0);
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
    first_corner[p + 1] = first_corner[p] + soup.polygons[p].size();
  std::vector<Side> sides;
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
  auto edge_name = [&](const Side& s) {
    return "the edge between vertices " + std::to_string(file_vertex[s.low]) + " and " +
           std::to_string(file_vertex[s.high]);
  };
  // The corner of `polygon` at the start (`at_end` false) or the end of side `s`.
  auto corner = [&](const Side& s, bool at_end) {
    const std::size_t n = soup.polygons[s.polygon].size();
    return first_corner[s.polygon] + (at_end ? (s.corner + 1) % n : s.corner);
  };
  Corner_sets fans(first_corner.back());
  Edge_check result;
  for(std::size_t s = 0; s < sides.size();)
  {
    std::size_t t = s + 1;
    while(t < sides.size() && sides[t].low == sides[s].low && sides[t].high == sides[s].high)
      ++t;
    if(t - s > 2)
    {
      result.refusal = edge_name(sides[s]) + " is shared by " + std::to_string(t - s) + " faces (" +
                       soup.describe_polygon(sides[s].polygon) + ", " + soup.describe_polygon(sides[s + 1].polygon) +
                       ", " + soup.describe_polygon(sides[s + 2].polygon) + (t - s > 3 ? ", ..." : "") +
                       "): a non-manifold edge";
      return result;
    }
    if(t - s == 2)
    {
      if(sides[s].forward == sides[s + 1].forward)
      {
        result.refusal = soup.describe_polygon(sides[s].polygon) + " and " +
                         soup.describe_polygon(sides[s + 1].polygon) + " run along " + edge_name(sides[s]) +
                         " in the same direction: their orientations disagree (the faces are not consistently "
                         "oriented, or the surface is not orientable)";
        return result;
      }
      // The two faces run along the edge in opposite directions: the start of one side is
      // the end of the other, and across the edge the corners there are one fan.
      fans.join(corner(sides[s], false), corner(sides[s + 1], true));
      fans.join(corner(sides[s], true), corner(sides[s + 1], false));
    }
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
  return result;
}

/// Refuses a triangle with (relatively) no area: area <= 1e-14 longest edge^2, the test of
/// `Mesh_index`, on coordinates scaled to the soup's bounding box so that tiny or huge
/// meshes neither underflow nor overflow.
inline std::string check_triangle_areas(const Polygon_soup& soup)
{
  if(soup.points.empty())
    return {};
  std::array<double, 3> low{}, high{};
  for(int k = 0; k < 3; ++k)
    low[k] = high[k] = soup.points[0][k];
  for(const auto& p : soup.points)
    for(int k = 0; k < 3; ++k)
    {
      low[k] = std::min(low[k], p[k]);
      high[k] = std::max(high[k], p[k]);
    }
  double extent = 0;
  for(int k = 0; k < 3; ++k)
    extent = std::max(extent, high[k] / 2 - low[k] / 2); // halves: no overflow near DBL_MAX
  if(!(extent > 0))
    extent = 1;
  auto scaled = [&](std::size_t i) {
    const auto& p = soup.points[i];
    return std::array<double, 3>{(p[0] - (low[0] / 2 + high[0] / 2)) / extent,
                                 (p[1] - (low[1] / 2 + high[1] / 2)) / extent,
                                 (p[2] - (low[2] / 2 + high[2] / 2)) / extent};
  };
  for(std::size_t f = 0; f < soup.polygons.size(); ++f)
  {
    const auto& t = soup.polygons[f];
    if(t.size() != 3)
      continue;
    const std::array<double, 3> a = scaled(t[0]), b = scaled(t[1]), c = scaled(t[2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double longest = std::max({u[0] * u[0] + u[1] * u[1] + u[2] * u[2], v[0] * v[0] + v[1] * v[1] + v[2] * v[2],
                                     w[0] * w[0] + w[1] * w[1] + w[2] * w[2]});
    if(!(area > 1e-14 * longest))
      return soup.describe_polygon(f) + " is degenerate (zero area: its corners are " +
             (longest > 0 ? "collinear)" : "at one point)");
  }
  return {};
}

/// Records the vertices `orient_polygon_soup` duplicates, and whether it had to reverse a
/// polygon (it must not: orientations were checked before).
struct Split_recorder : CGAL::Polygon_mesh_processing::Default_orientation_visitor
{
  std::vector<std::array<std::size_t, 2>>* duplicated = nullptr;
  bool* reversed = nullptr;
  void duplicated_vertex(std::size_t original, std::size_t copy) { duplicated->push_back({original, copy}); }
  void polygon_orientation_reversed(std::size_t) { *reversed = true; }
};

} // namespace reading
} // namespace internal

namespace IO {

/// Builds a triangle mesh from `soup` (which it changes), with the repairs of the file
/// comment. Returns false with `report.message` naming the reason when the soup cannot be
/// one; `mesh` is then left empty.
///
/// \tparam PolygonMesh a model of `MutableFaceGraph` with an internal point map whose points
///         are constructible from three doubles (`CGAL::Surface_mesh`, `CGAL::Polyhedron_3`)
template <class PolygonMesh>
bool polygon_soup_to_triangle_mesh(Polygon_soup& soup, PolygonMesh& mesh, Mesh_reading_report& report,
                                   const Mesh_reading_options& options = Mesh_reading_options())
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  namespace internal = ICM::internal::reading;
  clear(mesh);
  const std::size_t file_vertices = soup.points.size(), file_faces = soup.polygons.size();
  report = Mesh_reading_report();
  report.file_vertices = file_vertices;
  report.file_faces = file_faces;
  auto refuse = [&](const std::string& why) {
    report.message = why;
    clear(mesh);
    return false;
  };
  if(soup.polygons.empty())
    return refuse("the file has no faces" +
                  (file_vertices > 0 ? " (only " + std::to_string(file_vertices) + " vertices)" : std::string()));

  report.file_vertex = internal::remove_isolated_points_in_order(soup, report.isolated_vertices);

  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
    if(soup.polygons[p].size() > 3)
    {
      if(report.non_triangle_faces++ == 0 && !options.triangulate)
        report.message = "non-triangle faces: " + soup.describe_polygon(p) + " has " +
                         std::to_string(soup.polygons[p].size()) + " sides";
    }
  if(!report.message.empty())
    return refuse(report.message + (report.non_triangle_faces > 1
                                      ? " (" + std::to_string(report.non_triangle_faces) + " faces have more than 3)"
                                      : std::string()));

  const internal::Edge_check edges = internal::check_edges(soup, report.file_vertex);
  std::string why = edges.refusal;
  if(why.empty() && options.refuse_degenerate_faces)
    why = internal::check_triangle_areas(soup);
  if(!why.empty())
    return refuse(why);

  // A vertex whose faces form several fans becomes one vertex per fan: CGAL's
  // orient_polygon_soup does that on a soup (duplicate_non_manifold_vertices needs a mesh,
  // and a mesh cannot be built through such a vertex); with orientations already consistent
  // it reverses nothing.
  std::vector<std::array<std::size_t, 2>> duplicated;
  bool reversed = false;
  internal::Split_recorder recorder;
  recorder.duplicated = &duplicated;
  recorder.reversed = &reversed;
  if(edges.has_singular_vertices)
    PMP::orient_polygon_soup(soup.points, soup.polygons, CGAL::parameters::visitor(recorder));
  if(reversed)
    return refuse("the faces could not keep their orientation when non-manifold vertices were split");
  for(const auto& [original, copy] : duplicated)
  {
    if(copy != report.file_vertex.size())
      return refuse("the non-manifold vertices could not be split in order");
    report.file_vertex.push_back(report.file_vertex[original]);
    report.split_vertices.push_back(report.file_vertex[original]);
  }
  // Edges in at most two faces, orientations consistent, one fan per vertex: the soup is a
  // polygon mesh (polygon_soup_to_polygon_mesh asserts it in debug builds; checking it
  // again here would cost a fifth of the reading time).
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, mesh);

  if(report.non_triangle_faces > 0)
  {
    // Faces of the mesh are the soup's polygons in order: polygon p is the p-th face.
    std::vector<typename boost::graph_traits<PolygonMesh>::face_descriptor> polygons;
    std::vector<std::size_t> numbers;
    std::size_t p = 0;
    for(auto f : faces(mesh))
    {
      if(degree(f, mesh) > 3)
      {
        polygons.push_back(f);
        numbers.push_back(p);
      }
      ++p;
    }
    for(std::size_t i = 0; i < polygons.size(); ++i)
    {
      bool done = false;
      try
      {
        done = PMP::triangulate_face(polygons[i], mesh);
      }
      catch(const std::exception&)
      {
        done = false;
      }
      if(!done)
        return refuse(soup.describe_polygon(numbers[i]) + " (" + std::to_string(soup.polygons[numbers[i]].size()) +
                      " sides) cannot be triangulated (its corners do not span a plane polygon, or its sides cross)");
      ++report.triangulated_faces;
    }
  }
  if(!CGAL::is_triangle_mesh(mesh))
    return refuse("the mesh is not a triangle mesh after triangulation");
  return true;
}

/// Reads the mesh file `path` (OFF, OBJ, PLY or STL, by its extension) into `mesh`, safely,
/// with the repairs of the file comment. Returns false with `report.message` (starting with
/// the file's name) on any refusal; `mesh` is then empty.
template <class PolygonMesh>
bool read_triangle_mesh(const std::string& path, PolygonMesh& mesh, Mesh_reading_report& report,
                        const Mesh_reading_options& options = Mesh_reading_options())
{
  report = Mesh_reading_report();
  Polygon_soup soup;
  std::string error;
  if(!read_polygon_soup(path, soup, error, options.limits))
  {
    clear(mesh);
    report.message = error;
    return false;
  }
  if(!polygon_soup_to_triangle_mesh(soup, mesh, report, options))
  {
    report.message = "'" + path + "': " + report.message;
    return false;
  }
  return true;
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_READ_TRIANGLE_MESH_H
