// Google Benchmark micro-benchmarks of the numeric kernels at several mesh sizes: the
// curvature map, Laplacian assembly, numeric factorization, one Newton step, the layouts.
// Meshes: the bundled disks, and three_peaks refined by Loop subdivision for larger sizes.
// BM_flat_strip times the whole ICM::parameterize call on 1 x N strips of unit squares and
// fits its growth in N (Google Benchmark's complexity fit): it must stay linear.
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

/// three_peaks refined `levels` times (3.7k faces x 4^levels), indexed once and cached.
struct Fixture
{
  ICM::internal::Mesh_index index;
  ICM::Circle_packing_metric metric;
  std::vector<char> interior;
  std::vector<double> initial_weights; ///< Laplacian weights at u0
};

const Fixture& fixture(int levels)
{
  static std::map<int, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[levels];
  if(!slot)
  {
    Mesh mesh;
    CGAL::IO::read_polygon_mesh(ICM_BENCHMARK_MESH, mesh);
    if(levels > 0)
      CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(levels));
    slot = std::make_unique<Fixture>();
    std::vector<Mesh::Vertex_index> vertices;
    ICM::internal::index_mesh(mesh, *faces(mesh).begin(), get(CGAL::vertex_point, mesh), slot->index, vertices);
    slot->metric = ICM::initial_circle_packing_metric(slot->index);
    for(char b : slot->index.is_boundary_vertex)
      slot->interior.push_back(!b);
    ICM::Curvature_map<> curvature(slot->index, slot->metric);
    Eigen::VectorXd k;
    curvature.evaluate(slot->metric.u0, k, &slot->initial_weights);
  }
  return *slot;
}

void set_faces(benchmark::State& state, const Fixture& f)
{
  state.counters["faces"] = f.index.number_of_faces();
}

void BM_curvature_map(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  ICM::Curvature_map<> curvature(f.index, f.metric);
  Eigen::VectorXd k;
  std::vector<double> w;
  for(auto _ : state)
  {
    curvature.evaluate(f.metric.u0, k, &w);
    benchmark::DoNotOptimize(k.data());
  }
  set_faces(state, f);
}

void BM_laplacian_assembly(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  const std::vector<double>& w = f.initial_weights;
  ICM::Dynamic_laplacian<> laplacian(f.index, f.interior);
  for(auto _ : state)
  {
    laplacian.assemble(w);
    benchmark::ClobberMemory();
  }
  set_faces(state, f);
}

template <class Solver>
void BM_numeric_factorization(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  const std::vector<double>& w = f.initial_weights;
  ICM::Dynamic_laplacian<Solver> laplacian(f.index, f.interior);
  laplacian.assemble(w);
  for(auto _ : state)
    benchmark::DoNotOptimize(laplacian.factorize());
  set_faces(state, f);
}

void BM_newton_step(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  ICM::Inverse_curvature_map<> solver(f.index, f.metric, f.interior);
  ICM::Newton_options one_step;
  one_step.max_iterations = 1;
  const Eigen::VectorXd flat = Eigen::VectorXd::Zero(f.index.number_of_vertices());
  for(auto _ : state)
  {
    Eigen::VectorXd u = f.metric.u0;
    benchmark::DoNotOptimize(solver.solve(flat, u, one_step).iterations);
  }
  set_faces(state, f);
}

void BM_free_boundary_optimum(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  for(auto _ : state)
  {
    Eigen::VectorXd u;
    benchmark::DoNotOptimize(
      ICM::free_boundary_optimum(f.index, f.metric, ICM::boundary_singular_set(f.index), u).iterations);
  }
  set_faces(state, f);
}

/// The one nested dissection of a mesh (below the threshold: nothing to do).
void BM_elimination_order(benchmark::State& state)
{
  ICM::internal::Mesh_index index = fixture(static_cast<int>(state.range(0))).index;
  for(auto _ : state)
  {
    ICM::internal::order_vertices_for_elimination(index);
    benchmark::DoNotOptimize(index.elimination_rank.data());
  }
  state.counters["faces"] = index.number_of_faces();
}

void BM_layout(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  const bool harmonic = state.range(1) != 0;
  ICM::Inverse_curvature_map<> solver(f.index, f.metric, f.interior);
  Eigen::VectorXd u, k;
  std::vector<double> w;
  ICM::free_boundary_optimum(solver, f.metric, u);
  solver.curvature_map().evaluate(u, k, &w);
  const std::vector<double> lengths = solver.curvature_map().lengths();
  std::vector<ICM::Uv> uv;
  std::string message;
  for(auto _ : state)
  {
    if(harmonic)
      ICM::layout_harmonic(f.index, lengths, k, w, solver.laplacian(), uv, message);
    else
      uv = ICM::layout_by_propagation(f.index, lengths, solver.curvature_map().face_angles());
    benchmark::DoNotOptimize(uv.data());
  }
  set_faces(state, f);
  state.SetLabel(harmonic ? "harmonic" : "propagation");
}

/// The whole call on a 1 x N rectangle of unit squares (flat: the map is the strip itself).
void BM_flat_strip(benchmark::State& state)
{
  const int n = static_cast<int>(state.range(0));
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for(int i = 0; i <= n; ++i)
  {
    v.push_back(mesh.add_vertex(Kernel::Point_3(i, 0, 0)));
    v.push_back(mesh.add_vertex(Kernel::Point_3(i, 1, 0)));
  }
  for(int i = 0; i < n; ++i)
  {
    mesh.add_face(v[2 * i], v[2 * i + 2], v[2 * i + 3]);
    mesh.add_face(v[2 * i], v[2 * i + 3], v[2 * i + 1]);
  }
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  ICM::Surface_parameterization_report report;
  for(auto _ : state)
    report = ICM::parameterize(mesh, uv);
  if(report.status != CGAL::Surface_mesh_parameterization::OK)
    state.SkipWithError(report.message.c_str());
  state.SetComplexityN(n);
  state.counters["faces"] = 2 * n;
  state.counters["log_area"] = ICM::measure_distortion_corner_uv(mesh, uv).log_area_distortion;
}

} // namespace

BENCHMARK(BM_flat_strip)
  ->RangeMultiplier(10)
  ->Range(1000, 100000)
  ->Complexity(benchmark::oN)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_curvature_map)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_laplacian_assembly)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_numeric_factorization, ICM::Simplicial_solver)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
#ifdef ICM_HAS_CHOLMOD
BENCHMARK_TEMPLATE(BM_numeric_factorization, ICM::Cholmod_solver)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_numeric_factorization, ICM::Nested_dissection_solver)
  ->DenseRange(0, 4)
  ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_numeric_factorization, ICM::Preordered_cholmod_solver)
  ->DenseRange(0, 4)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_elimination_order)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
#endif
BENCHMARK(BM_newton_step)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_free_boundary_optimum)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_layout)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
