// CGAL's `simple_parameterization` example with ICM's parameterizer in place of CGAL's
// default one: a mesh with one border (the Nefertiti face of CGAL's example, bundled in
// examples/data) is mapped to the plane by CGAL's `parameterize()`, and the layout is
// written as an OFF file whose vertices are the UVs (z = 0), by CGAL's `output_uvmap_to_off`.
//
//   simple_parameterization [INPUT [OUTPUT.off]]      (defaults: nefertiti.off, result.off)
//
// The only differences from CGAL's example: the parameterizer object passed to
// `parameterize()`, and its report, read after the run (doc/report.md).

#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/IO/File_off.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Surface_mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using vertex_descriptor = boost::graph_traits<Surface_mesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<Surface_mesh>::halfedge_descriptor;

namespace SMP = CGAL::Surface_mesh_parameterization;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : ICM_EXAMPLE_DATA_DIR "/nefertiti.off";
  const std::string output = argc > 2 ? argv[2] : "result.off";

  Surface_mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh))
  {
    std::cerr << "cannot read " << input << "\n";
    return EXIT_FAILURE;
  }

  // The parameterized part is the connected component of this border halfedge; it must be
  // a topological disk. (A closed mesh has no border: longest_border() then returns a null
  // halfedge. Use ICM::parameterize, or cut it first as in seam_Polyhedron_3.cpp.)
  const halfedge_descriptor bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  if(bhd == boost::graph_traits<Surface_mesh>::null_halfedge())
  {
    std::cerr << input << " has no border: not a disk\n";
    return EXIT_FAILURE;
  }

  // One UV per vertex.
  auto uv_map = mesh.add_property_map<vertex_descriptor, Point_2>("v:uv").first;

  // The conformal map with least area distortion: the free-boundary minimum of the
  // curvature entropy (default options: doc/parameterizer.md).
  ICM::Inverse_curvature_map_parameterizer_3<Surface_mesh> parameterizer;
  const SMP::Error_code status = SMP::parameterize(mesh, parameterizer, bhd, uv_map);

  // CGAL's parameterize() copies the parameterizer; copies share one report.
  const ICM::Parameterization_report& report = parameterizer.report();
  if(status != SMP::OK)
  {
    std::cerr << ICM::error_message(status) << ": " << report.message << "\n";
    return EXIT_FAILURE;
  }
  std::cout << input << ": " << report.vertices << " vertices, " << report.faces << " faces, "
            << report.newton_iterations << " Newton iterations, max interior curvature " << report.max_curvature_error
            << ", metric " << report.metric << ", " << report.flipped_faces << " flipped faces, "
            << report.seconds_total << " s\n";

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
