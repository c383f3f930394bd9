// The `Metric` concept, checked for every model on the same meshes: at u0 the metric is what
// the metric promises (the mesh itself for vertex scaling and inversive distance), the
// Jacobian is symmetric with zero row sums and equals finite differences of K, Gauss-Bonnet
// holds, Newton converges quadratically, and a target that would make a face invalid is
// refused with a reason instead of a hang.

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Unflip.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <iostream>
#include <string>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ICM::internal::Mesh_index;

using icm_test::index_of;

using icm_test::dense_laplacian;

template <class Metric>
class MetricConcept : public testing::Test
{};
using Metrics = testing::Types<ICM::Circle_packing_metric, ICM::Inversive_distance_metric, ICM::Vertex_scaling_metric,
                               ICM::Intrinsic_delaunay_metric>;
TYPED_TEST_SUITE(MetricConcept, Metrics, icm_test::Metric_test_names);

TYPED_TEST(MetricConcept, JacobianIsSymmetricWithZeroRowSumsAndEqualsFiniteDifferences)
{
  for(const char* name : {"nefertiti.off", "three_peaks.off"})
  {
    const Mesh_index index = index_of(icm_test::data_path(name));
    const TypeParam metric(index);
    ICM::Curvature_map<TypeParam> curvature(index, metric);
    // Small enough that every face of every metric stays a triangle (three_peaks has
    // slivers that 0.05 already breaks).
    const Eigen::VectorXd u = icm_test::random_perturbation(metric.u0, 0.01, 11);
    Eigen::VectorXd k;
    std::vector<double> w;
    ASSERT_EQ(curvature.evaluate(u, k, &w), 0) << name;
    // The weights are per edge of the metric's triangulation (its own, for a flipping one).
    const Eigen::MatrixXd delta = dense_laplacian(curvature.mesh_index(), w);
    EXPECT_LT((delta - delta.transpose()).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(delta.rowwise().sum().cwiseAbs().maxCoeff(), 1e-10 * delta.cwiseAbs().maxCoeff());

    const double worst = icm_test::jacobian_finite_difference_error(curvature, u, delta, 13);
    EXPECT_LT(worst, 1e-6) << name;
    EXPECT_NEAR(ICM::gauss_bonnet_defect(index, k), 0.0, 1e-9) << name;
  }
}

TYPED_TEST(MetricConcept, NewtonConvergesQuadraticallyToTheFreeBoundaryOptimum)
{
  const Mesh_index index = index_of(icm_test::data_path("mushroom.off"));
  const TypeParam metric(index);
  Eigen::VectorXd u;
  ICM::Newton_options options;
  options.tolerance = 1e-13;
  const ICM::Newton_report report =
    ICM::free_boundary_optimum(index, metric, ICM::boundary_singular_set(index), u, options);
  ASSERT_TRUE(report.converged) << report.message;
  EXPECT_LE(report.iterations, 8);
  const std::vector<double>& r = report.residual_history;
  icm_test::expect_quadratic_convergence(r);
}

/// The mesh's angle defect per vertex (pi or 2 pi minus the angle sum).
Eigen::VectorXd angle_defect(const Mesh_index& index)
{
  Eigen::VectorXd defect(index.number_of_vertices());
  for(int v = 0; v < index.number_of_vertices(); ++v)
    defect[v] = index.is_boundary_vertex[v] ? M_PI : 2 * M_PI;
  for(const auto& f : index.faces)
    for(int c = 0; c < 3; ++c)
    {
      const auto &p = index.points[f[c]], &a = index.points[f[(c + 1) % 3]], &b = index.points[f[(c + 2) % 3]];
      const Eigen::Vector3d x(a[0] - p[0], a[1] - p[1], a[2] - p[2]), y(b[0] - p[0], b[1] - p[1], b[2] - p[2]);
      defect[f[c]] -= std::atan2(x.cross(y).norm(), x.dot(y));
    }
  return defect;
}

// The metrics that are the mesh at u0.
template <class Metric>
class ExactMetric : public testing::Test
{};
using Exact_metrics = testing::Types<ICM::Inversive_distance_metric, ICM::Vertex_scaling_metric>;
TYPED_TEST_SUITE(ExactMetric, Exact_metrics, icm_test::Metric_test_names);

TYPED_TEST(ExactMetric, ReproducesTheMeshAtU0)
{
  const Mesh_index index = index_of(icm_test::data_path("three_peaks.off"));
  const TypeParam metric(index);
  ICM::Curvature_map<TypeParam> curvature(index, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(metric.u0);
  const std::vector<double> mesh = ICM::internal::euclidean_edge_lengths(index);
  double worst = 0;
  for(int e = 0; e < index.number_of_edges(); ++e)
    worst = std::max(worst, std::abs(lengths[e] / mesh[e] - 1.0));
  EXPECT_LT(worst, 1e-12);
  // And the curvature at u0 is the mesh's angle defect.
  Eigen::VectorXd k;
  ASSERT_EQ(curvature.evaluate(metric.u0, k), 0);
  EXPECT_LT((k - angle_defect(index)).cwiseAbs().maxCoeff(), 1e-10);
}

TYPED_TEST(ExactMetric, TargetOutsideTheValidRegionIsRefusedWithAReason)
{
  // Ask a small disk for curvature it can only reach by degenerating faces: all of the
  // interior's 2 pi chi concentrated on one interior vertex, the border straight. In the
  // circle packing every u is valid; here Newton has to stop at the region's edge and say so.
  const Mesh_index index = index_of(icm_test::data_path("nefertiti.off"));
  const TypeParam metric(index);
  int apex = 0;
  while(index.is_boundary_vertex[apex])
    ++apex;
  Eigen::VectorXd k_target = Eigen::VectorXd::Zero(index.number_of_vertices());
  k_target[apex] = 2 * M_PI * index.euler_characteristic() - 1e-3;
  int first_border = 0;
  while(!index.is_boundary_vertex[first_border])
    ++first_border;
  k_target[first_border] = 1e-3;
  Eigen::VectorXd u;
  const ICM::Newton_report report = ICM::inverse_curvature_map(index, metric, k_target, u);
  EXPECT_FALSE(report.converged);
  EXPECT_TRUE(report.left_valid_region) << report.message;
  EXPECT_NE(report.message.find("valid region"), std::string::npos) << report.message;
  EXPECT_LE(report.iterations, ICM::Newton_options().max_iterations);
}

TEST(VertexScalingMetric, CotangentWeightsOfARightTriangle)
{
  // Legs 3 and 4, hypotenuse 5, all factors 1: cot of the right angle is 0, of the others
  // 3/4 and 4/3; the weight of each edge is half the cotangent of the opposite angle.
  Mesh_index index;
  index.points = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}};
  index.faces = {{0, 1, 2}};
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  const ICM::Vertex_scaling_metric metric(index);
  const ICM::Face_geometry face = metric.face_geometry(index.face_edges[0], {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0});
  EXPECT_TRUE(face.valid);
  EXPECT_NEAR(face.angles.angle[0], M_PI / 2, 1e-15);
  EXPECT_NEAR(face.weight[0], 0.0, 1e-15);
  EXPECT_NEAR(face.weight[1], 0.5 * 3.0 / 4.0, 1e-15); // corner 1 at (3,0): tan = 4/3
  EXPECT_NEAR(face.weight[2], 0.5 * 4.0 / 3.0, 1e-15); // corner 2 at (0,4): tan = 3/4
  EXPECT_NEAR(face.angles.area, 6.0, 1e-14);
  // A factor e^8 at vertex 1 scales its edges 01 and 12 by e^4: sides 3e^4, 5e^4 and 4,
  // and 3e^4 + 4 < 5e^4, so the lengths no longer close a triangle.
  const ICM::Face_geometry far = metric.face_geometry(index.face_edges[0], {1.0, std::exp(8.0), 1.0}, {0.0, 0.0, 0.0});
  EXPECT_FALSE(far.valid);
}

TEST(IntrinsicDelaunayMetric, IsTheMeshOnItsDelaunayTriangulationAtU0)
{
  // Euclidean flips change the edges, not the metric: the curvature at u0 is still the
  // mesh's angle defect, and every interior edge is Delaunay (cotangent weight >= 0).
  const Mesh_index index = index_of(icm_test::data_path("three_peaks.off"));
  ICM::Intrinsic_delaunay_metric metric(index);
  const Mesh_index& t = metric.triangulation();
  EXPECT_GT(metric.flips(), 100); // three_peaks is far from Delaunay (578 flips)
  EXPECT_EQ(t.number_of_edges(), index.number_of_edges());
  EXPECT_EQ(t.number_of_faces(), index.number_of_faces());
  ICM::Curvature_map<ICM::Intrinsic_delaunay_metric> curvature(index, metric);
  Eigen::VectorXd k;
  std::vector<double> w;
  ASSERT_EQ(curvature.evaluate(metric.u0, k, &w), 0);
  EXPECT_LT((k - angle_defect(index)).cwiseAbs().maxCoeff(), 1e-10);
  double most_negative = 0;
  for(int e = 0; e < t.number_of_edges(); ++e)
    if(t.edge_faces[e][1] >= 0)
      most_negative = std::min(most_negative, w[e]);
  EXPECT_GT(most_negative, -1e-9);
}

TEST(IntrinsicDelaunayMetric, FlipsKeepMostFacesTriangularWhereVertexScalingBreaksThem)
{
  // Large conformal factors (a random u of amplitude 1) break many of plain vertex scaling's
  // triangles; flipped to Delaunay with Ptolemy's relation, far fewer break (measured: the
  // flips do not remove every invalid face, which is why Newton's line search still checks).
  const Mesh_index index = index_of(icm_test::data_path("nefertiti.off"));
  const Eigen::VectorXd u = icm_test::random_perturbation(Eigen::VectorXd::Zero(index.number_of_vertices()), 1.0, 5);
  const ICM::Vertex_scaling_metric plain(index);
  ICM::Curvature_map<ICM::Vertex_scaling_metric> plain_curvature(index, plain);
  Eigen::VectorXd k;
  const int plain_invalid = plain_curvature.evaluate(u, k);

  const ICM::Intrinsic_delaunay_metric metric(index);
  ICM::Curvature_map<ICM::Intrinsic_delaunay_metric> curvature(index, metric);
  std::vector<double> w;
  const int invalid = curvature.evaluate(u, k, &w);
  EXPECT_LT(invalid, plain_invalid / 4) << plain_invalid;
  EXPECT_GT(curvature.metric().flips(), metric.flips());
  std::cout << "invalid faces: vertex scaling " << plain_invalid << ", flipped " << invalid << "\n";
}

TEST(IntrinsicDelaunayMetric, PtolemyFlipOfACyclicDiamondGivesTheOtherDiagonal)
{
  // A square's diamond is cyclic: Ptolemy's diagonal equals the Euclidean one, sqrt(2).
  Mesh_index index;
  index.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  index.faces = {{0, 1, 2}, {0, 2, 3}};
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  int diagonal = 0;
  while(index.edge_faces[diagonal][1] < 0)
    ++diagonal;
  ICM::internal::Edge_diamond x;
  ASSERT_TRUE(ICM::internal::edge_diamond(index, diagonal, x));
  const ICM::internal::Diamond_sides sides = ICM::internal::diamond_sides(index, x);
  const std::vector<double> l = ICM::internal::euclidean_edge_lengths(index);
  EXPECT_NEAR(ICM::internal::ptolemy_flipped_length(sides, diagonal, l), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(ICM::internal::euclidean_flipped_length(sides, diagonal, l), std::sqrt(2.0), 1e-15);
  ICM::internal::flip_edge(index, diagonal, x);
  EXPECT_EQ(index.edges[diagonal], (std::array<int, 2>{1, 3}));
  // Both faces still counter-clockwise in the plane.
  for(const auto& f : index.faces)
  {
    const auto &a = index.points[f[0]], &b = index.points[f[1]], &c = index.points[f[2]];
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0);
  }
}

} // namespace

TEST(CirclePackingMetric, EquilateralGridIsReproducedExactly)
{
  const ICM::internal::Mesh_index grid = icm_test::equilateral_grid(6);
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(grid);
  EXPECT_EQ(metric.clamped_edges, 0);
  ICM::Curvature_map<> curvature(grid, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(metric.u0);
  for(int e = 0; e < grid.number_of_edges(); ++e)
  {
    EXPECT_NEAR(metric.inversive_distance[e], 1.0, 1e-12); // tangent circles
    EXPECT_NEAR(lengths[e], 1.0, 1e-12);
  }
}

TEST(CirclePackingMetric, FaceGeometryKeepsItsPrecisionAcrossScales)
{
  // Three tangent circles of radii 1, 1, t: the excess s - l_c of corner c is its radius,
  // so tan(theta_c / 2) = sqrt(r_a r_b / (s r_c)), and every power-centre distance is the
  // inradius sqrt(r1 r2 r3 / s). With t = 1e-20 the sides are 2, 1 + t, 1 + t = 1 in double:
  // formulas from the lengths give theta_1 = 0, Newton then sees no coupling at all.
  ICM::Circle_packing_metric metric;
  metric.set_intersection_angles({0.0, 0.0, 0.0});
  for(double t : {1e-3, 1e-12, 1e-20})
  {
    const std::array<double, 3> g = {1.0, 1.0, t};
    const std::array<double, 3> l = {metric.length(0, g[1], g[2]), metric.length(1, g[0], g[2]),
                                     metric.length(2, g[0], g[1])};
    const ICM::Face_geometry face = metric.face_geometry({0, 1, 2}, g, l);
    const double s = 2.0 + t;
    const double big_angle = 2.0 * std::atan(std::sqrt(t / s));
    EXPECT_NEAR(face.angles.angle[0] / big_angle, 1.0, 1e-14) << t;
    EXPECT_NEAR(face.angles.angle[1] / big_angle, 1.0, 1e-14) << t;
    EXPECT_NEAR(face.angles.angle[2], M_PI - 2.0 * big_angle, 1e-15) << t;
    const double inradius = std::sqrt(t / s);
    EXPECT_NEAR(face.weight[2] / (inradius / 2.0), 1.0, 1e-13) << t;       // edge 01
    EXPECT_NEAR(face.weight[0] / (inradius / (1.0 + t)), 1.0, 1e-13) << t; // edge 12
    EXPECT_NEAR(face.weight[1] / (inradius / (1.0 + t)), 1.0, 1e-13) << t; // edge 02
  }
}

TEST(CirclePackingMetric, AnglesStayInTheRangeThatKeepsTrianglesValid)
{
  const ICM::internal::Mesh_index index = icm_test::index_file("three_peaks.off");
  for(ICM::Initial_radius rule : {ICM::Initial_radius::Mean_corner, ICM::Initial_radius::Max_corner})
  {
    const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index, rule);
    for(double c : metric.inversive_distance)
    {
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
    }
    // Thurston: with phi in [0, pi/2] any radii give triangles; try wild ones.
    ICM::Curvature_map<> curvature(index, metric);
    Eigen::VectorXd k;
    curvature.evaluate(icm_test::random_perturbation(metric.u0, 3.0, 7), k);
    EXPECT_TRUE(k.allFinite());
  }
}
