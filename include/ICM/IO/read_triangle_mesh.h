// Copyright (c) the ICM authors.
//
// From an untrusted file to a triangle mesh the parameterizers can take, with the repairs
// users expect and nothing else: the file is read as a polygon soup (read_polygon_soup.h),
// vertices in no face are dropped, a vertex whose faces form several fans is split into one
// vertex per fan, faces that disagree with their neighbours on the orientation are reversed,
// polygons are triangulated when asked to. Everything else that would not make an oriented
// 2-manifold (an edge in three faces, a face listed twice, a surface that cannot be oriented,
// coordinates whose differences overflow, a degenerate face, a polygon that crosses itself,
// polygons when triangulation was not asked for) is refused, naming the faces (and their
// lines) and the vertices at fault. Every repair made is listed in the report.
//
// Vertex numbering of the result: the file's vertices in the file's order without the
// dropped ones, then one more vertex per extra fan of each split vertex (STL: corners at the
// same point are one vertex, numbered in the order they first appear). `file_vertex` in the
// report maps each vertex of the mesh back to the file.

#ifndef ICM_IO_READ_TRIANGLE_MESH_H
#define ICM_IO_READ_TRIANGLE_MESH_H

#include <ICM/IO/Polygon_triangulation.h>
#include <ICM/IO/Soup_checks.h>
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
  /// Split polygons into triangles: quadrilaterals by
  /// `CGAL::Polygon_mesh_processing::triangulate_face`, larger polygons along the constrained
  /// Delaunay triangulation of their corners; otherwise a polygon is refused.
  bool triangulate = false;
  /// Refuse a triangle of (relatively) zero area, naming it; the parameterizers refuse them
  /// anyway, but without the file's line.
  bool refuse_degenerate_faces = true;
  Soup_reading_limits limits;
};

/// What `read_triangle_mesh()` read, repaired or refused.
struct Mesh_reading_report
{
  std::string message; ///< empty on success, else the reason of the refusal
  std::size_t file_vertices = 0, file_faces = 0;
  std::vector<std::size_t> isolated_vertices; ///< file indices of the vertices dropped
  std::vector<std::size_t> split_vertices;    ///< file index of each vertex copy added
  /// File indices of the faces reversed to agree with the faces around them (the orientation
  /// most faces of each connected component have is kept).
  std::vector<std::size_t> reoriented_faces;
  std::size_t triangulated_faces = 0; ///< polygons split into triangles
  std::size_t non_triangle_faces = 0; ///< polygons found (refused unless triangulated)
  /// The file's index of each vertex of the mesh, in `vertices(mesh)` order.
  std::vector<std::size_t> file_vertex;

  bool ok() const { return message.empty(); }

  /// One line per repair made, for a user: "dropped 2 isolated vertices (3, 9)".
  std::vector<std::string> repairs() const
  {
    std::vector<std::string> lines;
    if(!isolated_vertices.empty())
      lines.push_back("dropped " + std::to_string(isolated_vertices.size()) + " isolated vert" +
                      (isolated_vertices.size() == 1 ? "ex" : "ices") + " (in no face): " + list_of(isolated_vertices));
    if(!split_vertices.empty())
    {
      std::vector<std::size_t> distinct = split_vertices;
      std::sort(distinct.begin(), distinct.end());
      distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
      lines.push_back("split " + std::to_string(distinct.size()) + " non-manifold vert" +
                      (distinct.size() == 1 ? "ex" : "ices") + " into one vertex per fan of faces (" +
                      std::to_string(split_vertices.size()) + " added): " + list_of(distinct));
    }
    if(!reoriented_faces.empty())
      lines.push_back("reoriented " + std::to_string(reoriented_faces.size()) + " face" +
                      (reoriented_faces.size() == 1 ? "" : "s") + " to agree with the faces around " +
                      (reoriented_faces.size() == 1 ? "it" : "them") + ": " + list_of(reoriented_faces));
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

/// Records the vertices `orient_polygon_soup` duplicates and the polygons it reverses.
struct Orientation_recorder : CGAL::Polygon_mesh_processing::Default_orientation_visitor
{
  std::vector<std::array<std::size_t, 2>>* duplicated = nullptr;
  std::vector<char>* reversed = nullptr;
  void duplicated_vertex(std::size_t original, std::size_t copy) { duplicated->push_back({original, copy}); }
  void polygon_orientation_reversed(std::size_t p) { (*reversed)[p] ^= 1; }
};

/// Turns every component whose majority orient_polygon_soup reversed back over (it keeps the
/// orientation of each component's first polygon, which may be the odd one out): the faces
/// reversed are then the fewest that make the component agree.
inline void keep_majority_orientation(Polygon_soup& soup, const std::vector<std::size_t>& component,
                                      std::vector<char>& reversed)
{
  std::vector<std::size_t> size(soup.polygons.size(), 0), reversed_in(soup.polygons.size(), 0);
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
  {
    ++size[component[p]];
    reversed_in[component[p]] += reversed[p];
  }
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
    if(2 * reversed_in[component[p]] > size[component[p]])
    {
      std::reverse(soup.polygons[p].begin(), soup.polygons[p].end());
      reversed[p] ^= 1;
    }
}

/// Reverses the faces that disagree with their component and makes a vertex whose faces form
/// several fans one vertex per fan, both with CGAL's orient_polygon_soup (on a soup:
/// duplicate_non_manifold_vertices needs a mesh, and a mesh cannot be built through such a
/// vertex). Returns why it could not, or empty; the repairs go into `report`.
inline std::string orient_and_split(Polygon_soup& soup, const Edge_check& edges, IO::Mesh_reading_report& report)
{
  if(!edges.has_singular_vertices && !edges.has_disagreeing_faces)
    return {};
  std::vector<std::array<std::size_t, 2>> duplicated;
  std::vector<char> reversed(soup.polygons.size(), 0);
  Orientation_recorder recorder;
  recorder.duplicated = &duplicated;
  recorder.reversed = &reversed;
  CGAL::Polygon_mesh_processing::orient_polygon_soup(soup.points, soup.polygons, CGAL::parameters::visitor(recorder));
  if(edges.has_disagreeing_faces)
    keep_majority_orientation(soup, edges.component, reversed);
  else if(std::find(reversed.begin(), reversed.end(), 1) != reversed.end())
    return "the faces could not keep their orientation when non-manifold vertices were split";
  for(std::size_t p = 0; p < reversed.size(); ++p)
    if(reversed[p])
      report.reoriented_faces.push_back(p); // the soup's polygons are the file's faces, in order
  for(const auto& [original, copy] : duplicated)
  {
    if(copy != report.file_vertex.size())
      return "the non-manifold vertices could not be split in order";
    report.file_vertex.push_back(report.file_vertex[original]);
    report.split_vertices.push_back(report.file_vertex[original]);
  }
  return {};
}

/// Why the soup cannot be a triangle mesh with the repairs of `options`, or empty: counts
/// its polygons into `report` and refuses them unless triangulation was asked for, then
/// checks its edges, its extent, its triangles and its polygons.
inline std::string check_soup(const Polygon_soup& soup, const IO::Mesh_reading_options& options,
                              IO::Mesh_reading_report& report, Edge_check& edges)
{
  std::string why;
  for(std::size_t p = 0; p < soup.polygons.size(); ++p)
    if(soup.polygons[p].size() > 3 && report.non_triangle_faces++ == 0 && !options.triangulate)
      why = "non-triangle faces: " + soup.describe_polygon(p) + " has " + std::to_string(soup.polygons[p].size()) +
            " sides";
  if(!why.empty())
    return why + (report.non_triangle_faces > 1
                    ? " (" + std::to_string(report.non_triangle_faces) + " faces have more than 3)"
                    : std::string());
  edges = check_edges(soup, report.file_vertex);
  why = edges.refusal;
  if(why.empty())
    why = check_extent(soup);
  if(why.empty() && options.refuse_degenerate_faces)
    why = check_triangle_areas(soup);
  for(std::size_t p = 0; p < soup.polygons.size() && why.empty(); ++p)
    if(soup.polygons[p].size() > 3)
      why = why_not_triangulable(soup, p, report.file_vertex);
  return why;
}

/// Splits face `f` of `mesh`, polygon `p` of `soup`, into the triangles of the constrained
/// Delaunay triangulation of its corners on its best-fit plane (Polygon_triangulation.h).
/// Returns false, leaving it as it is, when its corners cannot be matched with the
/// polygon's or it has no such triangulation.
template <class PolygonMesh>
bool split_polygon_into_ears(typename boost::graph_traits<PolygonMesh>::face_descriptor f, PolygonMesh& mesh,
                             const Polygon_soup& soup, std::size_t p)
{
  const auto& polygon = soup.polygons[p];
  const auto points = get(CGAL::vertex_point, mesh);
  auto is_corner = [&](auto h, std::size_t c) {
    const auto& x = get(points, target(h, mesh));
    const auto& y = soup.points[polygon[c]];
    return x.x() == y.x() && x.y() == y.y() && x.z() == y.z();
  };
  // The face's corners are the polygon's in order, from some corner on: no two corners of
  // a polygon that passed the checks are at one point, so the first one is found by its point.
  auto h = halfedge(f, mesh);
  for(std::size_t k = 0; k < polygon.size() && !is_corner(h, 0); ++k)
    h = next(h, mesh);
  for(std::size_t c = 0; c < polygon.size(); ++c, h = next(h, mesh))
    if(!is_corner(h, c))
      return false;
  set_halfedge(f, h, mesh);
  return split_face_into_ears(f, corners_on_best_fit_plane(soup, p), mesh);
}

/// Triangulates the faces of `mesh` with more than 3 sides (the soup's polygons, in order),
/// counting them into `report`; returns why one could not be, or empty. Quadrilaterals go
/// through CGAL's triangulate_face (its choice of diagonal), larger polygons are split
/// along their constrained Delaunay triangulation in n log n (Polygon_triangulation.h).
template <class PolygonMesh>
std::string triangulate_polygons(PolygonMesh& mesh, const Polygon_soup& soup, IO::Mesh_reading_report& report)
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
    bool done = soup.polygons[numbers[i]].size() > 4 && split_polygon_into_ears(polygons[i], mesh, soup, numbers[i]);
    try
    {
      if(!done)
        done = CGAL::Polygon_mesh_processing::triangulate_face(polygons[i], mesh);
    }
    catch(const std::exception&)
    {
      done = false;
    }
    if(!done)
      return soup.describe_polygon(numbers[i]) + " (" + std::to_string(soup.polygons[numbers[i]].size()) +
             " sides) cannot be triangulated (its corners do not span a plane polygon, or its sides cross)";
    ++report.triangulated_faces;
  }
  return {};
}

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
  internal::Edge_check edges;
  std::string why = internal::check_soup(soup, options, report, edges);
  if(why.empty())
    why = internal::orient_and_split(soup, edges, report);
  if(!why.empty())
    return refuse(why);
  // Edges in at most two faces, orientations consistent, one fan per vertex: the soup is a
  // polygon mesh (polygon_soup_to_polygon_mesh asserts it in debug builds; checking it
  // again here would cost a fifth of the reading time).
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, mesh);
  if(report.non_triangle_faces > 0)
    why = internal::triangulate_polygons(mesh, soup, report);
  if(!why.empty())
    return refuse(why);
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
