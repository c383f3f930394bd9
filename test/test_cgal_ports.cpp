// CGAL 5.5's Surface_mesh_parameterization examples, each ported by changing only the
// parameterizer's name to ICM's (pipeline/Cgal_arguments.h): the border parameterizer and
// solver traits they pass become ICM's border condition and solver. Each test makes the
// example's calls (its typedefs, its constructor, CGAL's `parameterize()`) on a bundled mesh
// and checks the map: every vertex placed, no face flipped, the border the example asked for.
//
// Not portable by a name change, and why:
//  - iterative_authalic_parameterizer.cpp calls `parameterize(mesh, bhd, uv, iterations)`:
//    ICM's solve stops at its tolerance, there is no iteration count to give;
//  - ARAP_parameterization.cpp passes ARAP's lambda to the constructor, which has no meaning
//    for a conformal map;
//  - orbifold.cpp gives cones to `Orbifold_Tutte_parameterizer_3`, whose orbifold types ICM
//    does not have (`ICM::parameterize` takes cones for any surface instead).

#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/Unique_hash_map.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
// After the graph traits of the meshes under it.
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/Eigen_solver_traits.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <array>
#include <cmath>
#include <fstream>
#include <string>

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Surface_mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

template <class Mesh>
Mesh read_mesh(const std::string& name)
{
  Mesh mesh;
  std::ifstream in(icm_test::data_path(name));
  in >> mesh;
  return mesh;
}

/// Twice the signed UV area of every face is positive, and every vertex has a finite UV.
template <class Mesh, class UvMap>
void expect_embedded(const Mesh& mesh, const UvMap& uv)
{
  int flipped = 0;
  for(auto f : faces(mesh))
  {
    std::array<Point_2, 3> p;
    int c = 0;
    for(auto v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
      p[c++] = get(uv, v);
    for(const Point_2& q : p)
      ASSERT_TRUE(std::isfinite(q.x()) && std::isfinite(q.y()));
    flipped += CGAL::orientation(p[0], p[1], p[2]) != CGAL::LEFT_TURN;
  }
  EXPECT_EQ(flipped, 0);
}

TEST(CgalPorts, DiscreteConformalWithSquareBorderOnFourCorners)
{
  // square_border_parameterizer.cpp: a Polyhedron_3, a square border with four given corners.
  Polyhedron mesh = read_mesh<Polyhedron>("nefertiti.off");
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  std::vector<boost::graph_traits<Polyhedron>::vertex_descriptor> loop;
  for(auto h : CGAL::halfedges_around_face(bhd, mesh))
    loop.push_back(target(h, mesh));
  const std::size_t n = loop.size();
  using Border_parameterizer = SMP::Square_border_uniform_parameterizer_3<Polyhedron>;
  using Parameterizer = ICM::Inverse_curvature_map_parameterizer_3<Polyhedron, Border_parameterizer>;
  Border_parameterizer border_param(loop[0], loop[n / 4], loop[n / 2], loop[3 * n / 4]);
  CGAL::Unique_hash_map<boost::graph_traits<Polyhedron>::vertex_descriptor, Point_2> uv_table;
  boost::associative_property_map<decltype(uv_table)> uv_map(uv_table);
  Parameterizer parameterizer(border_param);
  ASSERT_EQ(SMP::parameterize(mesh, parameterizer, bhd, uv_map), SMP::OK) << parameterizer.report().message;
  EXPECT_EQ(parameterizer.report().border_condition, "square");
  expect_embedded(mesh, uv_map);
  // The four corners turn by a right angle: the border is a rectangle.
  for(std::size_t i : {std::size_t(0), n / 4, n / 2, 3 * n / 4})
  {
    const Point_2 a = get(uv_map, loop[(i + n - 1) % n]), b = get(uv_map, loop[i]), c = get(uv_map, loop[(i + 1) % n]);
    const double turn = std::atan2((b.x() - a.x()) * (c.y() - b.y()) - (b.y() - a.y()) * (c.x() - b.x()),
                                   (b.x() - a.x()) * (c.x() - b.x()) + (b.y() - a.y()) * (c.y() - b.y()));
    EXPECT_NEAR(std::abs(turn), M_PI / 2, 1e-6);
  }
}

TEST(CgalPorts, DiscreteAuthalicWithItsDefaultCircularBorder)
{
  // discrete_authalic.cpp: a Surface_mesh, the border parameterizer named explicitly.
  Surface_mesh sm = read_mesh<Surface_mesh>("nefertiti.off");
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  auto uv_map = sm.add_property_map<Surface_mesh::Vertex_index, Point_2>("v:uv").first;
  using Border_parameterizer = SMP::Circular_border_arc_length_parameterizer_3<Surface_mesh>;
  using Parameterizer = ICM::Inverse_curvature_map_parameterizer_3<Surface_mesh, Border_parameterizer>;
  Parameterizer parameterizer;
  ASSERT_EQ(SMP::parameterize(sm, parameterizer, bhd, uv_map), SMP::OK) << parameterizer.report().message;
  EXPECT_EQ(parameterizer.report().border_condition, "circle");
  EXPECT_LT(parameterizer.report().circle_deviation, 1e-6);
  expect_embedded(sm, uv_map);
}

TEST(CgalPorts, SimpleParameterizationWithASolverTraits)
{
  // simple_parameterization.cpp with the solver traits spelled out, as CGAL users do to pick
  // a direct solver: a Cholesky traits gives its Eigen solver, the default BiCGSTAB ICM's own.
  Surface_mesh sm = read_mesh<Surface_mesh>("nefertiti.off");
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  auto uv_map = sm.add_property_map<Surface_mesh::Vertex_index, Point_2>("v:uv").first;
  using Eigen_matrix = CGAL::Eigen_sparse_matrix<double>::EigenType;
  using Cholesky_traits = CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen_matrix>>;
  using Parameterizer = ICM::Inverse_curvature_map_parameterizer_3<Surface_mesh, CGAL::Default, Cholesky_traits>;
  static_assert(std::is_same<Parameterizer::Solver,
                             Eigen::SimplicialLDLT<ICM::Sparse_matrix, Eigen::Upper, Eigen::AMDOrdering<int>>>::value,
                "a Cholesky traits gives its solver, on the upper triangle the Laplacian fills");
  static_assert(
    std::is_same<
      ICM::Inverse_curvature_map_parameterizer_3<Surface_mesh, CGAL::Default, CGAL::Eigen_solver_traits<>>::Solver,
      ICM::Default_sparse_solver>::value,
    "CGAL's default traits (BiCGSTAB) gives ICM's solver");
  Parameterizer parameterizer;
  ASSERT_EQ(SMP::parameterize(sm, parameterizer, bhd, uv_map), SMP::OK) << parameterizer.report().message;
  EXPECT_EQ(parameterizer.report().border_condition, "free");
  expect_embedded(sm, uv_map);
}

TEST(CgalPorts, LscmOnASeamMeshWithTwoVertices)
{
  // lscm.cpp: a Seam_mesh cut along a selection, LSCM's two-vertices border parameterizer,
  // which becomes the free border (ICM pins no vertex).
  using Seam_edge_pmap = Surface_mesh::Property_map<Surface_mesh::Edge_index, bool>;
  using Seam_vertex_pmap = Surface_mesh::Property_map<Surface_mesh::Vertex_index, bool>;
  using Mesh = CGAL::Seam_mesh<Surface_mesh, Seam_edge_pmap, Seam_vertex_pmap>;
  Surface_mesh sm = read_mesh<Surface_mesh>("sphere966.off");
  Seam_edge_pmap seam_edges = sm.add_property_map<Surface_mesh::Edge_index, bool>("e:on_seam", false).first;
  Seam_vertex_pmap seam_vertices = sm.add_property_map<Surface_mesh::Vertex_index, bool>("v:on_seam", false).first;
  Mesh mesh(sm, seam_edges, seam_vertices);
  ASSERT_NE(mesh.add_seams(icm_test::data_path("sphere966.selection.txt").c_str()), Surface_mesh::Halfedge_index());
  auto uv_pm = sm.add_property_map<Surface_mesh::Halfedge_index, Point_2>("h:uv").first;
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  using Border_parameterizer = SMP::Two_vertices_parameterizer_3<Mesh>;
  using Parameterizer = ICM::Inverse_curvature_map_parameterizer_3<Mesh, Border_parameterizer>;
  Parameterizer parameterizer;
  ASSERT_EQ(SMP::parameterize(mesh, parameterizer, bhd, uv_pm), SMP::OK) << parameterizer.report().message;
  EXPECT_EQ(parameterizer.report().border_condition, "free");
  expect_embedded(mesh, uv_pm);
}

} // namespace
