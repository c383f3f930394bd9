// compare's meshes and UV maps: a CGAL::Surface_mesh, and for a surface that is not a disk the
// CGAL::Seam_mesh that cuts it along ICM's seams.

#ifndef ICM_BENCHMARK_COMPARE_MESH_TYPES_H
#define ICM_BENCHMARK_COMPARE_MESH_TYPES_H

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/boost/graph/Seam_mesh.h>

#include <limits>

namespace compare {

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = boost::graph_traits<Mesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;
using edge_descriptor = boost::graph_traits<Mesh>::edge_descriptor;
using UV_map = Mesh::Property_map<vertex_descriptor, Point_2>;

// A mesh that is not a disk, cut along seams without copying it. Its UVs live in a halfedge
// map of the underlying mesh: one UV per corner (the seam mesh reads a seam-mesh vertex's UV
// at its halfedge), which is also the layout ICM::parameterize() writes.
using Seam_edge_map = Mesh::Property_map<edge_descriptor, bool>;
using Seam_vertex_map = Mesh::Property_map<vertex_descriptor, bool>;
using Seam_mesh = CGAL::Seam_mesh<Mesh, Seam_edge_map, Seam_vertex_map>;
using seam_halfedge_descriptor = boost::graph_traits<Seam_mesh>::halfedge_descriptor;
using Corner_UV_map = Mesh::Property_map<halfedge_descriptor, Point_2>;

const double NaN = std::numeric_limits<double>::quiet_NaN();

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_MESH_TYPES_H
