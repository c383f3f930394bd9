// CGAL's `seam_Polyhedron_3` example with ICM's parameterizer: a closed surface has no
// border, so it is cut open along seams given in a CGAL selection file (pairs of vertex
// indices on its third line). The cut surface is a `CGAL::Seam_mesh` over a `Polyhedron_3`,
// a topological disk whose border runs along both sides of every seam, and CGAL's
// `parameterize()` maps it to the plane. The layout is written as an OFF file (z = 0).
//
//   seam_Polyhedron_3 [INPUT SEAMS.selection.txt [OUTPUT.off]]
//                     (defaults: sphere966.off, sphere966.selection.txt, result.off)
//
// `ICM::parameterize` on the seam mesh reads the seams as cuts of one surface: the metric is
// flat across them, so the two sides of a seam get one length and fit together by a rigid
// motion, and the seams' ends and branch points are the cones. CGAL's `parameterize()` with
// `ICM::Inverse_curvature_map_parameterizer_3<Seam_mesh>` would read each side as free border
// of the disk instead, as CGAL's own parameterizers do.

#include <ICM/parameterize.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Unique_hash_map.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
// After the graph traits of the mesh under it.
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/Surface_mesh_parameterization/IO/File_off.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

using Poly_vertex = boost::graph_traits<Polyhedron>::vertex_descriptor;
using Poly_halfedge = boost::graph_traits<Polyhedron>::halfedge_descriptor;
using Poly_edge = boost::graph_traits<Polyhedron>::edge_descriptor;

// Which edges and vertices of the polyhedron are on a seam.
using Seam_edge_table = CGAL::Unique_hash_map<Poly_edge, bool>;
using Seam_vertex_table = CGAL::Unique_hash_map<Poly_vertex, bool>;
using Seam_edge_map = boost::associative_property_map<Seam_edge_table>;
using Seam_vertex_map = boost::associative_property_map<Seam_vertex_table>;
using Seam_mesh = CGAL::Seam_mesh<Polyhedron, Seam_edge_map, Seam_vertex_map>;
using halfedge_descriptor = boost::graph_traits<Seam_mesh>::halfedge_descriptor;

// One UV per vertex of the seam mesh: a vertex on a seam has one copy per side, each named
// by a halfedge of the polyhedron, so the UVs are stored per polyhedron halfedge.
using Uv_table = CGAL::Unique_hash_map<Poly_halfedge, Point_2>;
using Uv_map = boost::associative_property_map<Uv_table>;

namespace SMP = CGAL::Surface_mesh_parameterization;

int main(int argc, char** argv)
{
  const std::string input = argc > 2 ? argv[1] : ICM_EXAMPLE_DATA_DIR "/sphere966.off";
  const std::string seams = argc > 2 ? argv[2] : ICM_EXAMPLE_DATA_DIR "/sphere966.selection.txt";
  const std::string output = argc > 3 ? argv[3] : "result.off";

  Polyhedron polyhedron;
  if(!CGAL::IO::read_polygon_mesh(input, polyhedron))
  {
    std::cerr << "cannot read " << input << "\n";
    return EXIT_FAILURE;
  }

  Seam_edge_table seam_edge_table(false);
  Seam_vertex_table seam_vertex_table(false);
  Seam_mesh mesh(polyhedron, Seam_edge_map(seam_edge_table), Seam_vertex_map(seam_vertex_table));
  // Vertex indices in the file are positions in vertices(polyhedron), the order of the OFF.
  if(mesh.add_seams(seams.c_str()) == boost::graph_traits<Polyhedron>::null_halfedge())
  {
    std::cerr << "no seam edge read from " << seams << "\n";
    return EXIT_FAILURE;
  }
  std::cout << mesh.number_of_seam_edges() << " seam edges: " << num_vertices(polyhedron) << " vertices, "
            << num_vertices(mesh) << " in the cut surface\n";

  // A border halfedge of the cut surface: one side of a seam.
  const halfedge_descriptor bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;

  Uv_table uv_table;
  Uv_map uv_map(uv_table);

  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, uv_map);
  if(report.status != SMP::OK)
  {
    std::cerr << ICM::error_message(report.status) << ": " << report.message << "\n";
    return EXIT_FAILURE;
  }
  const ICM::Chart_report& chart = report.charts.front();
  std::cout << input << ": " << chart.vertices << " vertices, " << chart.faces << " faces, " << chart.cones.size()
            << " cones, " << chart.newton_iterations << " Newton iterations, max curvature off the cones "
            << chart.max_curvature_error << ", metric " << chart.metric << ", " << chart.flipped_faces
            << " flipped faces, " << report.seconds_total << " s\n";

  std::ofstream out(output);
  SMP::IO::output_uvmap_to_off(mesh, bhd, uv_map, out);
  out.close();
  if(!out)
  {
    std::cerr << "cannot write " << output << "\n";
    return EXIT_FAILURE;
  }
  std::cout << "wrote " << output << "\n";
  return EXIT_SUCCESS;
}
