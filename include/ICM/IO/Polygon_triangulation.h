// Copyright (c) the ICM authors.
//
// The triangulation of a large polygon of a file, in time n log n for n corners. CGAL's
// triangulate_face inserts the corners into its constrained Delaunay triangulation one at a
// time in the order of the polygon, each located from nowhere in particular: on a polygon
// whose corners run along long straight sides (a tall, thin tube's faces), each location
// walks across much of the triangulation built so far, and a million triangles cost four
// times the reading of a million-triangle file. Here the corners of the polygon on its
// best-fit plane (already checked to be a simple polygon, Soup_checks.h) are inserted in
// spatial order, each located from the last one, and the mesh face is then split one ear at
// a time along the triangulation's diagonals, each split of constant cost.

#ifndef ICM_IO_POLYGON_TRIANGULATION_H
#define ICM_IO_POLYGON_TRIANGULATION_H

#include <ICM/internal/Vector_geometry.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <array>
#include <cstddef>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

/// A triangle of a polygon's triangulation: three corner numbers of the polygon, and the
/// corner whose two sides are on the polygon's border or cut off before (its ear tip) when
/// the triangles are taken in the order given.
struct Polygon_ear
{
  std::size_t before, tip, after;
};

/// The constrained Delaunay triangulation of a polygon's corners: a vertex's info is its
/// corner number, a face's is -1 outside the polygon and, inside, the number of its inside
/// neighbours not cut off yet (`cut` once it is cut off itself).
namespace polygon_triangulation {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vertex_base = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using Face_base =
  CGAL::Constrained_triangulation_face_base_2<Kernel, CGAL::Triangulation_face_base_with_info_2<int, Kernel>>;
using Triangulation =
  CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vertex_base, Face_base>,
                                             CGAL::No_constraint_intersection_tag>;
using Face_handle = Triangulation::Face_handle;
constexpr int outside = -1, not_reached = -2, cut = -3;

/// Inserts the corners of `q` in spatial order, each located from the one before, then its
/// sides as constraints. False when they do not make a triangulation with the corners as
/// its only vertices (sides that cross, corners at one point or all on a line).
inline bool triangulate(const std::vector<Uv>& q, Triangulation& cdt)
{
  const std::size_t n = q.size();
  std::vector<Kernel::Point_2> points(n);
  std::vector<std::size_t> order(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    points[i] = Kernel::Point_2(q[i][0], q[i][1]);
    order[i] = i;
  }
  using Point_map = CGAL::Pointer_property_map<Kernel::Point_2>::type;
  CGAL::spatial_sort(order.begin(), order.end(),
                     CGAL::Spatial_sort_traits_adapter_2<Kernel, Point_map>(CGAL::make_property_map(points)));
  std::vector<Triangulation::Vertex_handle> vertex(n);
  Face_handle hint;
  for(std::size_t i : order)
  {
    vertex[i] = cdt.insert(points[i], hint);
    vertex[i]->info() = i;
    hint = vertex[i]->face();
  }
  if(cdt.number_of_vertices() != n || cdt.dimension() != 2)
    return false;
  try
  {
    for(std::size_t i = 0; i < n; ++i)
      cdt.insert_constraint(vertex[i], vertex[(i + 1) % n]);
  }
  catch(const Triangulation::Intersection_of_constraints_exception&)
  {
    return false;
  }
  return cdt.number_of_vertices() == n;
}

/// The faces inside the polygon: reached from the infinite face across one constrained edge
/// (the polygon is simple), each given its number of inside neighbours.
inline std::vector<Face_handle> inside_faces(const Triangulation& cdt)
{
  for(Face_handle f : cdt.all_face_handles())
    f->info() = not_reached;
  std::vector<Face_handle> stack{cdt.infinite_face()}, inside;
  cdt.infinite_face()->info() = outside;
  while(!stack.empty())
  {
    const Face_handle f = stack.back();
    stack.pop_back();
    for(int k = 0; k < 3; ++k)
    {
      const Face_handle g = f->neighbor(k);
      const bool crosses = cdt.is_constrained({f, k});
      if(g->info() != not_reached || (f->info() != outside && crosses))
        continue; // the outside is reached from the infinite face without crossing
      g->info() = f->info() == outside && !crosses ? outside : 0;
      if(g->info() == 0)
        inside.push_back(g);
      stack.push_back(g);
    }
  }
  for(Face_handle f : inside)
    for(int k = 0; k < 3; ++k)
      f->info() += !cdt.is_constrained({f, k}) && f->neighbor(k)->info() >= 0 ? 1 : 0;
  return inside;
}

/// Cuts the leaves of the dual tree of the inside faces one at a time: a triangle with one
/// neighbour left is an ear, its tip the corner across from that neighbour. The faces turn
/// counter-clockwise; the polygon's order around an ear is theirs when the polygon turns
/// that way too.
inline std::vector<Polygon_ear> cut_ears(const Triangulation& cdt, const std::vector<Face_handle>& inside,
                                         bool counter_clockwise)
{
  std::vector<Polygon_ear> ears;
  ears.reserve(inside.size());
  std::vector<Face_handle> leaves;
  for(Face_handle f : inside)
    if(f->info() == 1)
      leaves.push_back(f);
  while(!leaves.empty() && ears.size() + 1 < inside.size())
  {
    const Face_handle f = leaves.back();
    leaves.pop_back();
    if(f->info() != 1)
      continue; // cut off already
    int k = 0;
    while(cdt.is_constrained({f, k}) || f->neighbor(k)->info() < 0) // outside, or cut off
      ++k;
    const std::size_t right = f->vertex(Triangulation::cw(k))->info(), left = f->vertex(Triangulation::ccw(k))->info();
    const std::size_t tip = f->vertex(k)->info();
    ears.push_back(counter_clockwise ? Polygon_ear{right, tip, left} : Polygon_ear{left, tip, right});
    f->info() = cut;
    const Face_handle g = f->neighbor(k);
    if(--g->info() == 1)
      leaves.push_back(g);
  }
  for(Face_handle f : inside)
    if(f->info() != cut)
      ears.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return ears;
}

} // namespace polygon_triangulation

/// The constrained Delaunay triangulation of the simple plane polygon `q` (its corners in
/// order, no two at one point, no two sides meeting but neighbours at their common corner),
/// as the n - 2 ears that cut it down to its last triangle, in the order they are cut: each
/// ear's tip has `before` and `after` as its neighbours on what is left of the polygon.
/// The last entry is the last triangle (its `tip` is any of its corners). Empty when the
/// triangulation does not have the polygon's corners as its vertices (a polygon that is not
/// simple after all).
inline std::vector<Polygon_ear> ears_of_simple_polygon(const std::vector<Uv>& q)
{
  namespace pt = polygon_triangulation;
  const std::size_t n = q.size();
  pt::Triangulation cdt;
  if(n < 3 || !pt::triangulate(q, cdt))
    return {};
  const std::vector<pt::Face_handle> inside = pt::inside_faces(cdt);
  if(inside.size() != n - 2)
    return {};
  double twice_area = 0;
  for(std::size_t i = 0; i < n; ++i)
    twice_area += q[i][0] * q[(i + 1) % n][1] - q[(i + 1) % n][0] * q[i][1];
  std::vector<Polygon_ear> ears = pt::cut_ears(cdt, inside, twice_area > 0);
  if(ears.size() != n - 2)
    return {};
  return ears;
}

/// Splits face `f` of `mesh`, whose corners are those of `q` in order (`halfedge(f)`
/// entering corner 0), into the triangles of `ears_of_simple_polygon(q)`. Returns false,
/// leaving `f` as it is, when `q` has none.
template <class PolygonMesh>
bool split_face_into_ears(typename boost::graph_traits<PolygonMesh>::face_descriptor f, const std::vector<Uv>& q,
                          PolygonMesh& mesh)
{
  using halfedge_descriptor = typename boost::graph_traits<PolygonMesh>::halfedge_descriptor;
  const std::vector<Polygon_ear> ears = ears_of_simple_polygon(q);
  if(ears.empty())
    return false;
  // entering[c]: the halfedge into corner c on the border of what is left of the face.
  std::vector<halfedge_descriptor> entering(q.size());
  halfedge_descriptor h = halfedge(f, mesh);
  for(std::size_t c = 0; c < q.size(); ++c, h = next(h, mesh))
    entering[c] = h;
  for(std::size_t e = 0; e + 1 < ears.size(); ++e)
  {
    // The ear before -> tip -> after is cut off along a new edge from `before` to `after`,
    // which then enters `after` on the rest of the face.
    const halfedge_descriptor into_tip = entering[ears[e].tip];
    entering[ears[e].after] = CGAL::Euler::split_face(prev(into_tip, mesh), next(into_tip, mesh), mesh);
  }
  return true;
}

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_POLYGON_TRIANGULATION_H
