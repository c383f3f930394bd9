// The smallest use of ICM: a disk-like Surface_mesh through CGAL's parameterize(), with the
// ICM parameterizer dropped in where CGAL's own would go.
#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <iostream>

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : ICM_EXAMPLE_MESH;
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(path, mesh))
  {
    std::cerr << "cannot read " << path << "\n";
    return 1;
  }
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  auto uvmap = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;

  ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
  const SMP::Error_code status = SMP::parameterize(mesh, parameterizer, bhd, uvmap);
  const ICM::Parameterization_report& report = parameterizer.report();
  if(status != SMP::OK)
  {
    std::cerr << ICM::error_message(status) << ": " << report.message << "\n";
    return 1;
  }
  std::cout << report.vertices << " vertices, " << report.newton_iterations
            << " Newton iterations, max interior curvature " << report.max_curvature_error << ", "
            << report.flipped_faces << " flipped faces, " << report.seconds_total << " s\n";
  return 0;
}
