// Step 0 of the pipeline: read a FaceGraph once into flat index arrays.
//
// Everything numeric downstream (metric, curvature, Newton, layout) runs on these arrays and
// never touches the graph again; the graph is only visited here and when UVs are written back.

#ifndef ICM_INTERNAL_MESH_INDEX_H
#define ICM_INTERNAL_MESH_INDEX_H

#include <ICM/Status.h>
#include <ICM/internal/Unit_frame.h>
#include <ICM/internal/Vector_geometry.h>

#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Dynamic_property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace ICM {
namespace internal {

/// Centring and scaling of coordinates: a point p of the input is (p - center) / scale in a
/// `Mesh_index`. Everything downstream (lengths, areas, angles, Newton) then works on
/// numbers near 1 whatever the mesh's units: squared lengths of a mesh at 1e-300 would
/// underflow to zero and areas of one at 1e+300 overflow to infinity.
using Normalisation = Unit_frame<3>;

/// The `Normalisation` of the bounding box of `points`, non-finite points left out.
template <class PointRange>
Normalisation normalisation_of(const PointRange& points)
{
  return unit_frame_of<3>(points);
}

/// Compact, read-only description of one connected triangle mesh.
/// Faces keep the orientation of the input; corner `c` of face `f` is `faces[f][c]`, and
/// `face_edges[f][c]` is the edge opposite that corner.
struct Mesh_index
{
  /// Per vertex, normalised by `normalisation` when built by `index_mesh()`: lengths and
  /// UVs computed from them are in units of `normalisation.scale`.
  std::vector<std::array<double, 3>> points;
  Normalisation normalisation;                // identity unless built by index_mesh()
  std::vector<std::array<int, 3>> faces;      // vertex indices, input orientation
  std::vector<std::array<int, 3>> face_edges; // edge opposite each corner
  std::vector<std::array<int, 2>> edges;      // endpoints, first < second
  std::vector<std::array<int, 2>> edge_faces; // incident faces, second = -1 on the border
  std::vector<char> is_boundary_vertex;
  std::vector<std::vector<int>> boundary_loops;      // vertices in the order of the border halfedges
  std::vector<std::vector<int>> boundary_loop_edges; // edge from loop[i] to loop[i+1]
  /// Per vertex, its place in one fill-reducing elimination order of the vertex graph
  /// (`order_vertices_for_elimination`, internal/Elimination_order.h), which every Laplacian
  /// of the mesh restricted to any vertex subset, of its intrinsic triangulations (copies of
  /// it) and of its cut (each wedge ranked by its vertex) numbers its unknowns in. Empty: each
  /// Laplacian orders its own unknowns.
  std::vector<int> elimination_rank;

  int number_of_vertices() const { return static_cast<int>(points.size()); }
  int number_of_faces() const { return static_cast<int>(faces.size()); }
  int number_of_edges() const { return static_cast<int>(edges.size()); }
  int number_of_boundary_loops() const { return static_cast<int>(boundary_loops.size()); }
  int euler_characteristic() const { return number_of_vertices() - number_of_edges() + number_of_faces(); }
  /// Genus of the (connected, orientable) surface: chi = 2 - 2g - b.
  int genus() const { return (2 - euler_characteristic() - number_of_boundary_loops()) / 2; }
  bool is_disk() const { return number_of_boundary_loops() == 1 && genus() == 0; }
};

/// "3 boundary loops, genus 0" — the phrase every topology error uses.
inline std::string describe_topology(const Mesh_index& index)
{
  std::ostringstream out;
  out << index.number_of_boundary_loops() << " boundary loop" << (index.number_of_boundary_loops() == 1 ? "" : "s")
      << ", genus " << index.genus();
  return out.str();
}

inline double squared_distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

/// The halfedges of `mesh`, sorted: whether a descriptor belongs to the mesh is then found
/// by comparisons alone, never by dereferencing one that may be foreign or stale.
template <class TriangleMesh>
std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor> sorted_halfedges(const TriangleMesh& mesh)
{
  std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor> all;
  for(auto h : halfedges(mesh))
    all.push_back(h);
  std::sort(all.begin(), all.end());
  return all;
}

/// Per vertex, the number of edges flagged in `is_seam` (per edge) that end there.
inline std::vector<int> seam_degrees(const Mesh_index& index, const std::vector<char>& is_seam)
{
  std::vector<int> degree(index.number_of_vertices(), 0);
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(is_seam[e])
    {
      ++degree[index.edges[e][0]];
      ++degree[index.edges[e][1]];
    }
  return degree;
}

/// The corner (0, 1 or 2) of face `f` at vertex `v`.
inline int corner_of_vertex(const Mesh_index& index, int f, int v)
{
  return index.faces[f][0] == v ? 0 : (index.faces[f][1] == v ? 1 : 2);
}

/// The key of the wedge of corner `c` of face `f`: its vertex, and the seam or border edge
/// that ends the wedge turning counter-clockwise around it (none for an uncut vertex). Two
/// triangulations of one surface with the same vertices, border and seam edges (the mesh
/// and an intrinsic triangulation of it) give their wedges the same keys.
inline long long wedge_key(const Mesh_index& index, const std::vector<char>& is_seam, int f, int c)
{
  const int v = index.faces[f][c];
  const long long base = static_cast<long long>(v) * (index.number_of_edges() + 1);
  for(int g = f, k = c, steps = 0; steps < index.number_of_faces(); ++steps)
  {
    // In face (v, x, y), counter-clockwise, turning past y crosses edge vy.
    const int e = index.face_edges[g][(k + 1) % 3];
    if(is_seam[e] || index.edge_faces[e][1] < 0)
      return base + e + 1;
    g = index.edge_faces[e][0] == g ? index.edge_faces[e][1] : index.edge_faces[e][0];
    k = corner_of_vertex(index, g, v);
    if(g == f)
      break;
  }
  return base;
}

/// The 3D length of edge `e` (normalised units).
inline double edge_length(const Mesh_index& index, int e)
{
  return std::sqrt(squared_distance(index.points[index.edges[e][0]], index.points[index.edges[e][1]]));
}

/// Boundary flags and loops from faces, edges and edge-face incidence; fails on a vertex
/// whose faces form more than one fan. Edges are told apart by id, not by their endpoints,
/// so this also serves a triangulation with two edges between the same vertices.
inline Status build_border(Mesh_index& index)
{
  using namespace CGAL::Surface_mesh_parameterization;
  const int nv = index.number_of_vertices();
  // A manifold vertex has one fan of faces: #edges == #faces inside, #faces + 1 on the border.
  std::vector<int> vertex_faces(nv, 0), vertex_edges(nv, 0), border_out(nv, -1), border_out_edge(nv, -1),
    border_out_count(nv, 0);
  for(const auto& f : index.faces)
    for(int v : f)
      ++vertex_faces[v];
  index.is_boundary_vertex.assign(nv, 0);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    ++vertex_edges[index.edges[e][0]];
    ++vertex_edges[index.edges[e][1]];
    if(index.edge_faces[e][1] >= 0)
      continue;
    // The border halfedge runs opposite to the face's own orientation of the edge.
    const int f = index.edge_faces[e][0];
    int c = 0;
    while(index.face_edges[f][c] != e)
      ++c;
    const int from = index.faces[f][(c + 2) % 3], to = index.faces[f][(c + 1) % 3];
    border_out[from] = to;
    border_out_edge[from] = e;
    ++border_out_count[from];
    index.is_boundary_vertex[from] = index.is_boundary_vertex[to] = 1;
  }
  for(int v = 0; v < nv; ++v)
  {
    const int expected = vertex_faces[v] + (index.is_boundary_vertex[v] ? 1 : 0);
    if(vertex_faces[v] == 0 || vertex_edges[v] != expected || border_out_count[v] > 1)
      return {ERROR_NON_TRIANGULAR_MESH,
              "non-manifold vertex " + std::to_string(v) + " (its faces form more than one fan)"};
  }

  index.boundary_loops.clear();
  index.boundary_loop_edges.clear();
  std::vector<char> visited(nv, 0);
  for(int v = 0; v < nv; ++v)
  {
    if(border_out[v] < 0 || visited[v])
      continue;
    std::vector<int> loop, loop_edges;
    for(int w = v; !visited[w]; w = border_out[w])
    {
      visited[w] = 1;
      loop.push_back(w);
      loop_edges.push_back(border_out_edge[w]);
    }
    index.boundary_loops.push_back(std::move(loop));
    index.boundary_loop_edges.push_back(std::move(loop_edges));
  }
  return {};
}

/// Builds edges, edge-face incidence, boundary flags and loops from `index.faces`.
/// Edges come from sorting the corner pairs, so nothing here depends on the graph type.
/// Fails on a non-manifold edge or vertex, which a halfedge graph can still encode at vertices.
inline Status build_connectivity(Mesh_index& index)
{
  using namespace CGAL::Surface_mesh_parameterization;
  const int nf = index.number_of_faces();

  // (min vertex, max vertex, face, corner opposite the edge), in lexicographic order:
  // bucketed by min vertex, then each bucket (a few sides) sorted in place, which costs a
  // fraction of sorting all 3F sides at once.
  const int nv = index.number_of_vertices();
  std::vector<int> bucket_start(nv + 1, 0);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
      ++bucket_start[std::min(index.faces[f][(c + 1) % 3], index.faces[f][(c + 2) % 3]) + 1];
  for(int v = 0; v < nv; ++v)
    bucket_start[v + 1] += bucket_start[v];
  std::vector<std::array<int, 4>> sides(3 * static_cast<std::size_t>(nf));
  std::vector<int> next(bucket_start.begin(), bucket_start.end() - 1);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int a = index.faces[f][(c + 1) % 3], b = index.faces[f][(c + 2) % 3];
      sides[next[std::min(a, b)]++] = {std::min(a, b), std::max(a, b), f, c};
    }
  for(int v = 0; v < nv; ++v)
    std::sort(sides.begin() + bucket_start[v], sides.begin() + bucket_start[v + 1]);

  index.edges.clear();
  index.edge_faces.clear();
  index.face_edges.assign(nf, {-1, -1, -1});
  for(std::size_t s = 0; s < sides.size();)
  {
    std::size_t t = s + 1;
    while(t < sides.size() && sides[t][0] == sides[s][0] && sides[t][1] == sides[s][1])
      ++t;
    if(t - s > 2)
      return {ERROR_NON_TRIANGULAR_MESH, "non-manifold edge shared by " + std::to_string(t - s) + " faces"};
    const int e = index.number_of_edges();
    index.edges.push_back({sides[s][0], sides[s][1]});
    index.edge_faces.push_back({sides[s][2], t - s == 2 ? sides[s + 1][2] : -1});
    for(std::size_t r = s; r < t; ++r)
      index.face_edges[sides[r][2]][sides[r][3]] = e;
    s = t;
  }
  return build_border(index);
}

/// Checks the geometry the numeric core relies on: finite coordinates, no zero-area face.
inline Status check_geometry(const Mesh_index& index)
{
  using namespace CGAL::Surface_mesh_parameterization;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    for(double x : index.points[v])
      if(!std::isfinite(x))
        return {ERROR_WRONG_PARAMETER, "vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or inf)"};
  int degenerate = 0, first = -1;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    const auto& p = index.points;
    const auto& t = index.faces[f];
    const double longest = std::max(
      {squared_distance(p[t[0]], p[t[1]]), squared_distance(p[t[1]], p[t[2]]), squared_distance(p[t[2]], p[t[0]])});
    // Relative to the face's own size: a sliver is fine, a face with no area is not.
    if(!(triangle_area(p[t[0]], p[t[1]], p[t[2]]) > 1e-14 * longest))
    {
      if(first < 0)
        first = f;
      ++degenerate;
    }
  }
  if(degenerate > 0)
    return {ERROR_WRONG_PARAMETER,
            std::to_string(degenerate) + " degenerate (zero-area) face(s), the first is face " + std::to_string(first)};
  return {};
}

/// Calls `visit(h)` for the halfedges of face `f` from `halfedge(f)` on, in the order of
/// `CGAL::halfedges_around_face`, until `visit` returns false. A loop over `next`: CGAL's
/// circulator ranges would bring the BGL iterator header into every TU of the disk
/// parameterizer for these few loops.
template <class TriangleMesh, class Visit>
void for_each_halfedge_of_face(typename boost::graph_traits<TriangleMesh>::face_descriptor f, const TriangleMesh& mesh,
                               Visit&& visit)
{
  const auto first = halfedge(f, mesh);
  auto h = first;
  do
  {
    if(!visit(h))
      return;
    h = next(h, mesh);
  } while(h != first);
}

/// The faces of the connected component of `seed`, in the order of CGAL's
/// `Polygon_mesh_processing::connected_component` (depth first, each face where it is first
/// taken from the stack). CGAL marks the faces seen in a std::set, a large share of the
/// indexing's time; a face property map does it in linear time.
template <class TriangleMesh>
std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>
faces_of_component(const TriangleMesh& mesh, typename boost::graph_traits<TriangleMesh>::face_descriptor seed)
{
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  auto seen = get(CGAL::dynamic_face_property_t<bool>(), mesh);
  for(face_descriptor f : faces(mesh))
    put(seen, f, false); // dynamic maps start with an unspecified value
  std::vector<face_descriptor> component, stack{seed};
  while(!stack.empty())
  {
    const face_descriptor f = stack.back();
    stack.pop_back();
    if(get(seen, f))
      continue;
    put(seen, f, true);
    component.push_back(f);
    for_each_halfedge_of_face(f, mesh, [&](auto h) {
      const face_descriptor g = face(opposite(h, mesh), mesh);
      if(g != boost::graph_traits<TriangleMesh>::null_face())
        stack.push_back(g);
      return true;
    });
  }
  return component;
}

/// Indexes the connected component of `mesh` that contains face `seed`, as CGAL's
/// parameterizers do with the component of their border halfedge.
/// `vertices` receives the descriptor of each compact vertex index, so results can be written
/// back through any vertex property map; `face_descriptors`, when given, that of each face,
/// whose corners follow `halfedges_around_face(halfedge(f))` (corner c = target of the c-th).
/// The points are normalised by `normalisation` when given (several components in one
/// frame), else centred and scaled to the component's own bounding box; UVs computed from
/// the index are multiplied by `index.normalisation.scale` to be in the mesh's units.
template <class TriangleMesh, class VertexPointMap>
Status index_mesh(const TriangleMesh& mesh, typename boost::graph_traits<TriangleMesh>::face_descriptor seed,
                  VertexPointMap vpm, Mesh_index& index,
                  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
                  std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>* face_descriptors = nullptr,
                  const Normalisation* normalisation = nullptr)
{
  using namespace CGAL::Surface_mesh_parameterization;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;

  index = Mesh_index();
  vertices.clear();
  if(faces(mesh).empty() || seed == boost::graph_traits<TriangleMesh>::null_face())
    return {ERROR_EMPTY_MESH, "the mesh has no faces"};

  const std::vector<face_descriptor> component = faces_of_component(mesh, seed);
  if(face_descriptors)
    *face_descriptors = component;

  using Vertex_int_tag = CGAL::dynamic_vertex_property_t<int>;
  auto local = get(Vertex_int_tag(), mesh);
  // Dynamic maps start with an unspecified value: mark every vertex of the component unseen.
  for(face_descriptor f : component)
    for_each_halfedge_of_face(f, mesh, [&](auto h) {
      put(local, target(h, mesh), -1);
      return true;
    });

  index.faces.reserve(component.size());
  for(face_descriptor f : component)
  {
    std::array<int, 3> tri{};
    int corners = 0;
    bool more_than_3 = false;
    for_each_halfedge_of_face(f, mesh, [&](auto h) {
      if(corners == 3)
        return !(more_than_3 = true);
      const vertex_descriptor v = target(h, mesh);
      int id = get(local, v);
      if(id < 0)
      {
        id = static_cast<int>(vertices.size());
        put(local, v, id);
        vertices.push_back(v);
        const auto& p = get(vpm, v);
        index.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
      }
      tri[corners++] = id;
      return true;
    });
    if(more_than_3)
      return {ERROR_NON_TRIANGULAR_MESH, "the mesh has a face with more than 3 sides"};
    if(corners != 3)
      return {ERROR_NON_TRIANGULAR_MESH, "the mesh has a face with fewer than 3 sides"};
    index.faces.push_back(tri);
  }

  // Finite coordinates first, named by the vertex, before they enter a bounding box.
  for(int v = 0; v < index.number_of_vertices(); ++v)
    for(double x : index.points[v])
      if(!std::isfinite(x))
        return {ERROR_WRONG_PARAMETER, "vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or inf)"};
  index.normalisation = normalisation ? *normalisation : normalisation_of(index.points);
  for(auto& p : index.points)
    p = index.normalisation.apply(p);

  Status status = build_connectivity(index);
  if(!status.ok())
    return status;
  return check_geometry(index);
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_MESH_INDEX_H
