// The numeric core on flat arrays: mesh index, circle packing metric, curvature map and its
// Jacobian, Newton (Algorithm 1), the free-boundary optimum in both forms, the layouts.

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <random>
#include <string>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ICM::internal::Mesh_index;

Mesh_index index_file(const std::string& name) { return icm_test::index_of(icm_test::data_path(name)); }

/// A planar grid of equilateral triangles: every circle packing with tangent circles of
/// radius l/2 reproduces it exactly.
Mesh_index equilateral_grid(int n)
{
  Mesh_index index;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
      index.points.push_back({i + 0.5 * j, j * std::sqrt(3.0) / 2, 0.0});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      index.faces.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      index.faces.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  EXPECT_TRUE(ICM::internal::build_connectivity(index).ok());
  return index;
}

/// A strip of 2 m equilateral triangles in a row, one unit wide: every hop of the layout's
/// face tree doubles its error estimate, which overflows after some 1000 hops.
Mesh_index equilateral_strip(int m)
{
  Mesh_index index;
  for(int i = 0; i <= m; ++i)
  {
    index.points.push_back({double(i), 0.0, 0.0});
    index.points.push_back({i + 0.5, std::sqrt(3.0) / 2, 0.0});
  }
  for(int i = 0; i < m; ++i)
  {
    index.faces.push_back({2 * i, 2 * i + 2, 2 * i + 1});
    index.faces.push_back({2 * i + 1, 2 * i + 2, 2 * i + 3});
  }
  EXPECT_TRUE(ICM::internal::build_connectivity(index).ok());
  return index;
}

using icm_test::random_perturbation;

std::vector<char> interior_of(const Mesh_index& index)
{
  std::vector<char> interior(index.number_of_vertices());
  for(int v = 0; v < index.number_of_vertices(); ++v)
    interior[v] = !index.is_boundary_vertex[v];
  return interior;
}

} // namespace

TEST(MeshIndex, TopologyOfRealMeshes)
{
  const Mesh_index disk = index_file("nefertiti.off");
  EXPECT_EQ(disk.number_of_vertices(), 299);
  EXPECT_EQ(disk.number_of_faces(), 562);
  EXPECT_EQ(disk.number_of_boundary_loops(), 1);
  EXPECT_EQ(disk.euler_characteristic(), 1);
  EXPECT_TRUE(disk.is_disk());
  // Every edge appears in the face_edges of its faces, border edges in one face only.
  int border_edges = 0;
  for(int e = 0; e < disk.number_of_edges(); ++e)
    border_edges += disk.edge_faces[e][1] < 0;
  EXPECT_EQ(border_edges, static_cast<int>(disk.boundary_loops[0].size()));

  const Mesh_index sphere = index_file("sphere966.off");
  EXPECT_EQ(sphere.number_of_boundary_loops(), 0);
  EXPECT_EQ(sphere.euler_characteristic(), 2);
  EXPECT_EQ(sphere.genus(), 0);
  EXPECT_FALSE(sphere.is_disk());
}

TEST(MeshIndex, NonManifoldVertexIsRefused)
{
  Mesh_index bowtie;
  bowtie.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  bowtie.faces = {{0, 1, 2}, {0, 3, 4}}; // two triangles sharing only vertex 0
  const ICM::Status status = ICM::internal::build_connectivity(bowtie);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("non-manifold vertex"), std::string::npos) << status.message;
}

TEST(CirclePackingMetric, EquilateralGridIsReproducedExactly)
{
  const Mesh_index grid = equilateral_grid(6);
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
  const Mesh_index index = index_file("three_peaks.off");
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
    curvature.evaluate(random_perturbation(metric.u0, 3.0, 7), k);
    EXPECT_TRUE(k.allFinite());
  }
}

TEST(CurvatureMap, GaussBonnetHoldsForAnyMetric)
{
  for(const char* name : {"nefertiti.off", "sphere966.off", "mushroom.off"})
  {
    const Mesh_index index = index_file(name);
    const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
    ICM::Curvature_map<> curvature(index, metric);
    Eigen::VectorXd k;
    for(unsigned seed : {1u, 2u, 3u})
    {
      curvature.evaluate(random_perturbation(metric.u0, 1.0, seed), k);
      EXPECT_NEAR(ICM::gauss_bonnet_defect(index, k), 0.0, 1e-9) << name;
    }
  }
}

TEST(CurvatureMap, LaplacianIsSymmetricWithZeroRowSumsAndEqualsFiniteDifferences)
{
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Curvature_map<> curvature(index, metric);
  const Eigen::VectorXd u = random_perturbation(metric.u0, 0.3, 11);
  Eigen::VectorXd k;
  std::vector<double> w;
  curvature.evaluate(u, k, &w);
  for(double weight : w)
    EXPECT_GT(weight, -1e-12); // Thurston: phi <= pi/2 keeps the power centre inside

  // The full Delta (nothing pinned) as a dense matrix.
  const Eigen::MatrixXd delta = icm_test::dense_laplacian(index, w);
  EXPECT_LT((delta - delta.transpose()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT(delta.rowwise().sum().cwiseAbs().maxCoeff(), 1e-12);

  // dk = Delta du: central differences of K, column by column on a sample of vertices.
  EXPECT_LT(icm_test::jacobian_finite_difference_error(curvature, u, delta, 7), 1e-6);
}

TEST(DynamicLaplacian, RestrictedMatrixMatchesTheWeights)
{
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Curvature_map<> curvature(index, metric);
  Eigen::VectorXd k;
  std::vector<double> w;
  curvature.evaluate(metric.u0, k, &w);
  ICM::Dynamic_laplacian<ICM::Simplicial_solver> laplacian(index, interior_of(index));
  laplacian.assemble(w);
  ASSERT_TRUE(laplacian.factorize()); // positive definite: the border is fixed
  const Eigen::MatrixXd dense = Eigen::MatrixXd(laplacian.matrix()).selfadjointView<Eigen::Upper>();
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int i = laplacian.free_index(index.edges[e][0]), j = laplacian.free_index(index.edges[e][1]);
    if(i >= 0 && j >= 0)
    {
      EXPECT_DOUBLE_EQ(dense(i, j), -w[e]);
    }
  }
  // Interior rows see their border neighbours only on the diagonal: rows sum to >= 0.
  EXPECT_GT(dense.rowwise().sum().minCoeff(), -1e-12);
}

TEST(InverseCurvatureMap, RecoversAMetricFromItsCurvature)
{
  // Algorithm 1 on a closed surface: K^{-1}(K(u*)) = u* up to the constant of the kernel.
  const Mesh_index index = index_file("sphere966.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Curvature_map<> curvature(index, metric);
  const Eigen::VectorXd u_star = random_perturbation(metric.u0, 0.5, 5);
  Eigen::VectorXd k_star;
  curvature.evaluate(u_star, k_star);
  Eigen::VectorXd u;
  const ICM::Newton_report report = ICM::inverse_curvature_map(index, metric, k_star, u);
  ASSERT_TRUE(report.converged) << report.message;
  EXPECT_LE(report.iterations, 10);
  const Eigen::VectorXd difference = u - u_star;
  EXPECT_LT((difference.array() - difference.mean()).abs().maxCoeff(), 1e-8);
  EXPECT_NEAR((u - metric.u0).sum(), 0.0, 1e-8); // normalised as the paper's sum u = 0
}

TEST(InverseCurvatureMap, NewtonConvergesQuadratically)
{
  const Mesh_index index = index_file("sphere966.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  // Uniform curvature 4 pi / n: the "round" metric of Algorithm 3's first step.
  const Eigen::VectorXd k_target =
    Eigen::VectorXd::Constant(index.number_of_vertices(), 4 * M_PI / index.number_of_vertices());
  Eigen::VectorXd u;
  ICM::Newton_options options;
  options.tolerance = 1e-13;
  const ICM::Newton_report report = ICM::inverse_curvature_map(index, metric, k_target, u, options);
  ASSERT_TRUE(report.converged) << report.message;
  const std::vector<double>& r = report.residual_history;
  ASSERT_GE(r.size(), 3u);
  icm_test::expect_quadratic_convergence(r);
}

TEST(InverseCurvatureMap, RefusesCurvatureThatViolatesGaussBonnet)
{
  const Mesh_index index = index_file("sphere966.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  Eigen::VectorXd u;
  const ICM::Newton_report report = ICM::inverse_curvature_map(
    index, metric, Eigen::VectorXd::Zero(index.number_of_vertices()), u);
  EXPECT_FALSE(report.converged);
  EXPECT_NE(report.message.find("Gauss-Bonnet"), std::string::npos) << report.message;
}

TEST(OptimalMetric, DiffusionAndNewtonReachTheSameOptimum)
{
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  const std::vector<char> singular = ICM::boundary_singular_set(index);

  Eigen::VectorXd u_newton;
  const ICM::Newton_report newton = ICM::free_boundary_optimum(index, metric, singular, u_newton);
  ASSERT_TRUE(newton.converged) << newton.message;
  EXPECT_LE(newton.iterations, 10);

  Eigen::VectorXd u_diffusion;
  ICM::Diffusion_options options;
  options.tolerance = 1e-10;
  const ICM::Diffusion_report diffusion =
    ICM::free_boundary_curvature_diffusion(index, metric, singular, u_diffusion, options);
  ASSERT_TRUE(diffusion.converged) << diffusion.message;
  EXPECT_GT(diffusion.iterations, newton.iterations); // the point of the Newton form

  // Lemma 3.4 / Theorem 3.2: u - u0 is one constant on the singular set...
  const Eigen::VectorXd shift = u_diffusion - metric.u0;
  double lo = 1e300, hi = -1e300;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(singular[v])
    {
      lo = std::min(lo, shift[v]);
      hi = std::max(hi, shift[v]);
    }
  EXPECT_LT(hi - lo, 1e-12);
  // ...and the two metrics agree up to that global scale.
  const Eigen::VectorXd difference = u_diffusion - u_newton;
  EXPECT_LT((difference.array() - lo).abs().maxCoeff(), 1e-7);
}

#ifdef ICM_HAS_CHOLMOD
TEST(OptimalMetric, CholmodAndSimplicialSolversAgree)
{
  const Mesh_index index = index_file("three_peaks.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  const std::vector<char> singular = ICM::boundary_singular_set(index);
  Eigen::VectorXd u_simplicial, u_cholmod, u_nested;
  const ICM::Newton_report a =
    ICM::free_boundary_optimum<ICM::Simplicial_solver>(index, metric, singular, u_simplicial);
  const ICM::Newton_report b =
    ICM::free_boundary_optimum<ICM::Cholmod_solver>(index, metric, singular, u_cholmod);
  const ICM::Newton_report c =
    ICM::free_boundary_optimum<ICM::Nested_dissection_solver>(index, metric, singular, u_nested);
  ASSERT_TRUE(a.converged) << a.message;
  ASSERT_TRUE(b.converged) << b.message;
  ASSERT_TRUE(c.converged) << c.message;
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.iterations, c.iterations);
  EXPECT_LT((u_simplicial - u_cholmod).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((u_simplicial - u_nested).cwiseAbs().maxCoeff(), 1e-9);

  // The default picks by size: three_peaks is far below the nested dissection threshold.
  ICM::Dynamic_laplacian<ICM::Size_adaptive_solver> small(index, interior_of(index));
  EXPECT_LT(small.size(), ICM::Size_adaptive_solver::nested_dissection_min_unknowns);
  ICM::Size_adaptive_solver solver;
  solver.analyzePattern(small.matrix());
  EXPECT_FALSE(solver.uses_nested_dissection());
}
#endif

TEST(OptimalMetric, DegreeThreeVertexCanBeFlattened)
{
  // A fan whose centre has degree 3 inside a larger disk: with link angles clamped to pi/2
  // its angle sum could never reach 2 pi; the metric relaxes that link.
  Mesh_index index;
  index.points = {{0.2, 0.1, 0}, {2, 0, 0}, {-1, 1.7, 0}, {-1, -1.7, 0},
                  {3, 2, 0}, {-3, 0.5, 0}, {1, -3, 0}};
  index.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 4, 2}, {2, 5, 3}, {3, 6, 1}};
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  std::vector<double> phi(index.number_of_edges(), M_PI / 2);
  EXPECT_GE(ICM::keep_short_cycles_flattenable(index, phi), 1);
  double link = 0;
  for(int f = 0; f < 3; ++f)
    link += phi[index.face_edges[f][0]];
  EXPECT_NEAR(link, M_PI - 0.1 * M_PI, 1e-12);
  metric.set_intersection_angles(phi);
  Eigen::VectorXd u;
  const ICM::Newton_report report =
    ICM::free_boundary_optimum(index, metric, ICM::boundary_singular_set(index), u);
  EXPECT_TRUE(report.converged) << report.message;
}

TEST(OptimalMetric, FourCycleAroundSeveralVerticesIsRelaxed)
{
  // Nested squares: border c0..c3, inner square d0..d3 (degree 5 each), centre m. With every
  // angle orthogonal the border 4-cycle gives sum (pi - phi) = 2 pi exactly: the five inner
  // vertices reach flatness only as their radii tend to 0. No vertex link sees this cycle.
  Mesh_index index;
  index.points = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0},
                  {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, 0}};
  for(int i = 0; i < 4; ++i)
  {
    const int c = i, c_next = (i + 1) % 4, d = 4 + i, d_next = 4 + (i + 1) % 4;
    index.faces.push_back({c, c_next, d});
    index.faces.push_back({d, c_next, d_next});
    index.faces.push_back({d, d_next, 8});
  }
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ASSERT_TRUE(index.is_disk());
  std::vector<double> phi(index.number_of_edges(), M_PI / 2);
  // Relaxed: the link of m and the border square.
  EXPECT_EQ(ICM::keep_short_cycles_flattenable(index, phi), 2);
  double border = 0;
  for(int e : index.boundary_loop_edges.front())
    border += phi[e];
  EXPECT_NEAR(border, 2 * M_PI - 0.1 * M_PI, 1e-12);

  ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  metric.set_intersection_angles(phi);
  Eigen::VectorXd u;
  const ICM::Newton_report report =
    ICM::free_boundary_optimum(index, metric, ICM::boundary_singular_set(index), u);
  EXPECT_TRUE(report.converged) << report.message;
  EXPECT_LE(report.iterations, 10);
}

TEST(Layout, PropagationAndHarmonicReproduceTheMetric)
{
  const Mesh_index index = index_file("three_peaks.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Inverse_curvature_map<> solver(index, metric, interior_of(index));
  Eigen::VectorXd u;
  ASSERT_TRUE(ICM::free_boundary_optimum(solver, metric, u).converged);
  Eigen::VectorXd k;
  std::vector<double> w;
  solver.curvature_map().evaluate(u, k, &w);
  const std::vector<double> lengths = solver.curvature_map().lengths();

  const std::vector<ICM::Uv> propagated =
    ICM::layout_by_propagation(index, lengths, solver.curvature_map().face_angles());
  const ICM::Layout_check a = ICM::check_layout(index, lengths, propagated);
  EXPECT_EQ(a.flipped_faces, 0);
  EXPECT_LT(a.max_relative_length_error, 1e-8);

  std::vector<ICM::Uv> harmonic;
  std::string message;
  ASSERT_TRUE(ICM::layout_harmonic(index, lengths, k, w, solver.laplacian(), harmonic, message))
    << message;
  const ICM::Layout_check b = ICM::check_layout(index, lengths, harmonic);
  EXPECT_EQ(b.flipped_faces, 0);
  EXPECT_LT(b.max_relative_length_error, 1e-8);

  // That layout refined Newton's last factorization; a fresh factorization of the final
  // Laplacian gives the same coordinates.
  ASSERT_TRUE(solver.laplacian().has_factorization());
  ICM::Dynamic_laplacian<> fresh(index, interior_of(index));
  ASSERT_FALSE(fresh.has_factorization());
  std::vector<ICM::Uv> direct;
  ASSERT_TRUE(ICM::layout_harmonic(index, lengths, k, w, fresh, direct, message)) << message;
  ASSERT_TRUE(fresh.has_factorization());
  double largest_difference = 0, extent = 0;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    for(int c = 0; c < 2; ++c)
    {
      largest_difference = std::max(largest_difference, std::abs(direct[v][c] - harmonic[v][c]));
      extent = std::max(extent, std::abs(direct[v][c]));
    }
  EXPECT_LT(largest_difference, 1e-12 * extent);
}

TEST(Layout, EquilateralGridLaysOutAsItself)
{
  // A planar mesh reproduced exactly by its packing is already flat: the optimum is u0
  // and the layout is the input up to a rigid motion.
  const Mesh_index grid = equilateral_grid(5);
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(grid);
  Eigen::VectorXd u;
  const ICM::Newton_report report =
    ICM::free_boundary_optimum(grid, metric, ICM::boundary_singular_set(grid), u);
  ASSERT_TRUE(report.converged);
  EXPECT_EQ(report.iterations, 0);
  ICM::Curvature_map<> curvature(grid, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(u);
  const std::vector<ICM::Uv> uv = ICM::layout_by_propagation(grid, lengths, curvature.face_angles());
  for(int i = 0; i < grid.number_of_vertices(); ++i)
    for(int j = i + 1; j < grid.number_of_vertices(); j += 5)
    {
      const auto& p = grid.points[i];
      const auto& q = grid.points[j];
      EXPECT_NEAR(std::hypot(uv[i][0] - uv[j][0], uv[i][1] - uv[j][1]),
                  std::hypot(p[0] - q[0], p[1] - q[1]), 1e-12);
    }
}

TEST(Layout, LongStripLaysOutAsItselfInLinearTime)
{
  // 6000 faces in a row: 3000 hops from the central root to either end, where the error
  // estimate has overflowed to infinity long before. The layout is still every face once
  // (a strip of 1 x 550 squares used to offer its faces again without end) and isometric.
  const Mesh_index strip = equilateral_strip(3000);
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(strip);
  ICM::Curvature_map<> curvature(strip, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(metric.u0);
  const std::vector<ICM::Uv> uv = ICM::layout_by_propagation(strip, lengths, curvature.face_angles());
  const ICM::Layout_check check = ICM::check_layout(strip, lengths, uv);
  EXPECT_EQ(check.flipped_faces, 0);
  EXPECT_LT(check.max_relative_length_error, 1e-9);
  const int last = strip.number_of_vertices() - 1;
  EXPECT_NEAR(std::hypot(uv[last][0] - uv[0][0], uv[last][1] - uv[0][1]),
              std::hypot(strip.points[last][0] - strip.points[0][0], strip.points[last][1] - strip.points[0][1]),
              1e-9 * strip.points[last][0]);
}
