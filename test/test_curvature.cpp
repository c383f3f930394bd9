// The curvature stage (curvature/) on flat arrays: the mesh index it reads, the curvature map
// and its Jacobian (the dynamic Laplacian), Newton on it (Algorithm 1).

#include <ICM/cones/Linearized_cones.h>
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

Mesh_index index_file(const std::string& name)
{
  return icm_test::index_of(icm_test::data_path(name));
}

using icm_test::equilateral_grid;
using icm_test::interior_of;
using icm_test::random_perturbation;

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

TEST(DynamicLaplacian, ConjugateGradientsOnAnEarlierFactorizationSolveTheCurrentMatrix)
{
  // Factorized at the weights w, assembled again at w times 1 +- 5%: conjugate gradients
  // preconditioned by the old factorization solve the new matrix to 1e-12 in a few solves,
  // as a fresh factorization does; lent by another Laplacian on the same unknowns, the same.
  // Weights moved by factors of 1/5 to 5 are not solved in 3 solves, and the call says so.
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Curvature_map<> curvature(index, metric);
  Eigen::VectorXd k;
  std::vector<double> w;
  curvature.evaluate(metric.u0, k, &w);
  auto scaled = [&w](double spread, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> factor(-spread, spread);
    std::vector<double> moved = w;
    for(double& x : moved)
      x *= std::exp(factor(random));
    return moved;
  };
  using Laplacian = ICM::Dynamic_laplacian<ICM::Simplicial_solver>;
  Laplacian laplacian(index, interior_of(index)), lender(index, interior_of(index)), fresh(index, interior_of(index));
  laplacian.assemble(w);
  lender.assemble(w);
  ASSERT_TRUE(laplacian.factorize());
  ASSERT_TRUE(lender.factorize());
  ASSERT_TRUE(laplacian.numbers_unknowns_as(lender));
  const std::vector<double> near = scaled(0.05, 3);
  laplacian.assemble(near);
  fresh.assemble(near);
  ASSERT_TRUE(fresh.factorize());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(laplacian.size(), -1.0, 2.0);
  const Eigen::VectorXd exact = fresh.solve(b);
  Eigen::VectorXd x, lent;
  int solves = 0, lent_solves = 0;
  ASSERT_TRUE(laplacian.solve_preconditioned(b, x, 1e-12, 20, solves));
  EXPECT_LE(solves, 10);
  EXPECT_LT((x - exact).norm(), 1e-9 * exact.norm());
  ASSERT_TRUE(laplacian.solve_preconditioned(b, lent, 1e-12, 20, lent_solves, &lender));
  EXPECT_EQ(lent_solves, solves);
  EXPECT_LT((lent - x).norm(), 1e-12 * exact.norm());

  // Columns are separate runs sharing each triangular solve (the harmonic layout's two
  // coordinates): the first column is the run above, a zero column stays zero, and a third
  // column needs as many solves as the slowest.
  Eigen::MatrixXd columns(laplacian.size(), 3), xs;
  columns << b, Eigen::VectorXd::Zero(laplacian.size()), Eigen::VectorXd::LinSpaced(laplacian.size(), 3.0, -1.0);
  int block_solves = 0, third_solves = 0;
  ASSERT_TRUE(laplacian.solve_preconditioned(columns, xs, 1e-12, 20, block_solves));
  Eigen::VectorXd third;
  ASSERT_TRUE(laplacian.solve_preconditioned(Eigen::VectorXd(columns.col(2)), third, 1e-12, 20, third_solves));
  EXPECT_EQ(block_solves, std::max(solves, third_solves));
  EXPECT_LT((xs.col(0) - x).norm(), 1e-12 * exact.norm());
  EXPECT_EQ(xs.col(1).norm(), 0.0);
  EXPECT_LT((xs.col(2) - third).norm(), 1e-12 * third.norm());
  EXPECT_LT((xs.col(2) - fresh.solve(Eigen::VectorXd(columns.col(2)))).norm(), 1e-9 * third.norm());

  laplacian.assemble(scaled(std::log(5.0), 4));
  EXPECT_FALSE(laplacian.solve_preconditioned(b, x, 1e-12, 3, solves));
  EXPECT_EQ(solves, 3);
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

namespace {

std::vector<char> interior_vertices(const Mesh_index& index)
{
  std::vector<char> is_interior(index.number_of_vertices());
  for(int v = 0; v < index.number_of_vertices(); ++v)
    is_interior[v] = !index.is_boundary_vertex[v];
  return is_interior;
}

} // namespace

TEST(InverseCurvatureMap, TheLinearizedOptimumGivesNewtonItsFirstStepAndItsFactorization)
{
  // The free-boundary optimum of a disk from u0: Newton's own, then with the linearized
  // optimum (cones/Linearized_cones.h, no cone) as the first step and its factorization at
  // u0 lent to precondition the rest: the same first step, the same metric, and not one
  // factorization. A first step Newton's line search rejects (every interior u raised by 50)
  // leaves Newton's own run as it was.
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  const std::vector<char> is_free = interior_vertices(index);
  const Eigen::VectorXd flat = Eigen::VectorXd::Zero(index.number_of_vertices());
  const std::vector<char> border(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  ICM::internal::Linearized_cone_problem<ICM::Default_sparse_solver, ICM::Circle_packing_metric> linearized(
    index, metric, border);
  ASSERT_TRUE(linearized.ok()) << linearized.message();
  auto run = [&](const Eigen::VectorXd* first_step, bool borrow, Eigen::VectorXd& u) {
    ICM::Inverse_curvature_map<> solver(index, metric, is_free);
    if(borrow)
      solver.borrow_factorization(linearized.laplacian());
    u = metric.u0;
    return solver.solve(flat, u, ICM::Newton_options(), first_step);
  };
  Eigen::VectorXd u_own, u_given, u_rejected;
  const ICM::Newton_report own = run(nullptr, false, u_own);
  const Eigen::VectorXd first_step = linearized.solve();
  const ICM::Newton_report given = run(&first_step, true, u_given);
  Eigen::VectorXd raised = Eigen::VectorXd::Zero(index.number_of_vertices());
  for(int v = 0; v < index.number_of_vertices(); ++v)
    raised[v] = is_free[v] ? 50.0 : 0.0;
  const ICM::Newton_report rejected = run(&raised, false, u_rejected);
  ASSERT_TRUE(own.converged) << own.message;
  ASSERT_TRUE(given.converged) << given.message;
  ASSERT_TRUE(rejected.converged) << rejected.message;
  ASSERT_GE(own.residual_history.size(), 3u);
  EXPECT_GT(own.residual_history[0], 1e-2);
  EXPECT_GE(own.factorizations, 1);
  EXPECT_NEAR(given.residual_history[1], own.residual_history[1], 1e-9);
  EXPECT_EQ(given.factorizations, 0);
  EXPECT_EQ(given.refined_steps, given.iterations - 1);
  EXPECT_LE(given.iterations, own.iterations + 1);
  EXPECT_LT((u_given - u_own).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(rejected.residual_history, own.residual_history);
  EXPECT_EQ(rejected.factorizations, own.factorizations);
  EXPECT_LT((u_rejected - u_own).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(LinearizedCones, OptimumIsFlatOffTheConesWithinAndPastTheKeptColumns)
{
  // u = x + G lambda from the kept single-precision columns of G (up to 64 cones), then by a
  // solve past them: either way the linearized curvature K0 + Delta u vanishes at every free
  // vertex that is no cone, and u = 0 on the border and at the cones.
  const Mesh_index index = index_file("nefertiti.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  std::vector<char> is_fixed(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  ICM::internal::Linearized_cone_problem<ICM::Default_sparse_solver, ICM::Circle_packing_metric> problem(index, metric,
                                                                                                         is_fixed);
  ASSERT_TRUE(problem.ok()) << problem.message();
  ICM::Curvature_map<> curvature(index, metric);
  Eigen::VectorXd k0;
  std::vector<double> w;
  curvature.evaluate(metric.u0, k0, &w);
  auto expect_flat_off_the_cones = [&](double tolerance, int cones) {
    const Eigen::VectorXd u = problem.solve();
    Eigen::VectorXd linearized = k0;
    for(int e = 0; e < index.number_of_edges(); ++e)
    {
      const int a = index.edges[e][0], b = index.edges[e][1];
      linearized[a] += w[e] * (u[a] - u[b]);
      linearized[b] += w[e] * (u[b] - u[a]);
    }
    double worst = 0;
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(is_fixed[v])
        EXPECT_EQ(u[v], 0.0) << "vertex " << v << " with " << cones << " cones";
      else
        worst = std::max(worst, std::abs(linearized[v]));
    EXPECT_LT(worst, tolerance) << cones << " cones";
  };
  std::vector<int> cones;
  for(int v = 0; v < index.number_of_vertices() && cones.size() < 70; v += 3)
    if(!is_fixed[v])
    {
      problem.add_cone(v);
      is_fixed[v] = 1;
      cones.push_back(v);
      if(cones.size() == 5)
      {
        expect_flat_off_the_cones(1e-5, 5);
        problem.remove_cone(problem.position_of(cones[1])); // its column goes with it
        is_fixed[cones[1]] = 0;
        expect_flat_off_the_cones(1e-5, 4);
        problem.add_cone(cones[1]);
        is_fixed[cones[1]] = 1;
      }
    }
  ASSERT_EQ(cones.size(), 70u);
  expect_flat_off_the_cones(1e-10, 70);
}

TEST(InverseCurvatureMap, RefusesCurvatureThatViolatesGaussBonnet)
{
  const Mesh_index index = index_file("sphere966.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  Eigen::VectorXd u;
  const ICM::Newton_report report =
    ICM::inverse_curvature_map(index, metric, Eigen::VectorXd::Zero(index.number_of_vertices()), u);
  EXPECT_FALSE(report.converged);
  EXPECT_NE(report.message.find("Gauss-Bonnet"), std::string::npos) << report.message;
}
