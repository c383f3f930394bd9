// The consumer of the installed package (test/consumer, test/subproject): parameterizes a
// disk through CGAL's parameterize() with ICM's parameterizer and checks the result itself,
// without trusting the report: every vertex has a finite UV and every face keeps its
// orientation. With CHOLMOD (ICM_HAS_CHOLMOD, from ICM::ICM), the same again with CHOLMOD's
// supernodal Cholesky, which must then be linked.
//
//   icm_consumer MESH      prints "CHOLMOD: yes|no" and one line per run; exit 0 when all pass

#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

/// Parameterizes `mesh` with `Parameterizer` and returns the number of problems found.
template <class Parameterizer>
int parameterize_and_check(Mesh& mesh, const std::string& name)
{
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  auto uv = mesh.add_property_map<Mesh::Vertex_index, Point_2>("v:uv_" + name, Point_2(NAN, NAN)).first;
  Parameterizer parameterizer;
  const SMP::Error_code status = SMP::parameterize(mesh, parameterizer, bhd, uv);
  const ICM::Parameterization_report& report = parameterizer.report();
  if(status != SMP::OK)
  {
    std::cerr << name << ": " << ICM::error_message(status) << ": " << report.message << "\n";
    return 1;
  }
  int problems = 0;
  for(Mesh::Vertex_index v : vertices(mesh))
    if(!std::isfinite(uv[v].x()) || !std::isfinite(uv[v].y()))
      ++problems;
  int positive = 0, negative = 0;
  for(Mesh::Face_index f : faces(mesh))
  {
    const auto h = halfedge(f, mesh);
    const Point_2 &a = uv[source(h, mesh)], &b = uv[target(h, mesh)], &c = uv[target(next(h, mesh), mesh)];
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    (area > 0 ? positive : negative) += 1;
  }
  // One orientation for every face (the layout may be mirrored as a whole).
  problems += std::min(positive, negative);
  if(report.vertices != static_cast<int>(num_vertices(mesh)) || report.flipped_faces != 0)
    ++problems;
  std::cout << name << ": " << report.vertices << " vertices, " << report.newton_iterations
            << " Newton iterations, max interior curvature " << report.max_curvature_error << ", "
            << std::min(positive, negative) << " flipped faces, " << problems << " problems\n";
  return problems;
}

int main(int argc, char** argv)
{
  if(argc != 2)
  {
    std::cerr << "usage: icm_consumer MESH\n";
    return 2;
  }
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(argv[1], mesh))
  {
    std::cerr << "cannot read " << argv[1] << "\n";
    return 1;
  }
  int problems = parameterize_and_check<ICM::Inverse_curvature_map_parameterizer_3<Mesh>>(mesh, "default");
#ifdef ICM_HAS_CHOLMOD
  std::cout << "CHOLMOD: yes\n";
  problems +=
    parameterize_and_check<ICM::Inverse_curvature_map_parameterizer_3<Mesh, CGAL::Default, ICM::Cholmod_solver>>(
      mesh, "cholmod");
#else
  std::cout << "CHOLMOD: no\n";
#endif
  return problems == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
