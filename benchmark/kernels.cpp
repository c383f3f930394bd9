// Google Benchmark micro-benchmarks of the numeric kernels at several mesh sizes: the
// curvature map, Laplacian assembly, numeric factorization, one Newton step, the layouts.
// Meshes: the bundled disks, and three_peaks refined by Loop subdivision for larger sizes.
// BM_flat_strip times the whole ICM::parameterize call on 1 x N strips of unit squares and
// fits its growth in N (Google Benchmark's complexity fit): it must stay linear.
// BM_read_triangle_mesh reads a file as icm_param --triangulate does: lion-head Loop x3
// against a square tube of polygons with long collinear sides, of the same face count.
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>
#include <ICM/IO/read_triangle_mesh.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

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

/// Writes an OFF file of `points` and `faces` (17 digits: the file reads back exactly).
void write_off(const std::string& path, const std::vector<std::array<double, 3>>& points,
               const std::vector<std::vector<std::size_t>>& faces)
{
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << points.size() << ' ' << faces.size() << " 0\n";
  for(const auto& p : points)
    out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for(const auto& f : faces)
  {
    out << f.size();
    for(std::size_t i : f)
      out << ' ' << i;
    out << '\n';
  }
}

std::string temporary_file(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("icm_kernels_" + name)).string();
}

/// lion-head refined three times by Loop (1 067 136 triangles), written once as OFF.
std::string lion_head_loop3_file()
{
  static const std::string path = [] {
    Mesh mesh;
    if(!CGAL::IO::read_polygon_mesh(ICM_BENCHMARK_LION_HEAD, mesh))
      return std::string();
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    std::vector<std::array<double, 3>> points;
    for(auto v : vertices(mesh))
      points.push_back({mesh.point(v).x(), mesh.point(v).y(), mesh.point(v).z()});
    std::vector<std::vector<std::size_t>> faces;
    for(auto f : mesh.faces())
    {
      faces.emplace_back();
      for(auto v : vertices_around_face(mesh.halfedge(f), mesh))
        faces.back().push_back(v.idx());
    }
    const std::string file = temporary_file("lion_head_loop3.off");
    write_off(file, points, faces);
    return file;
  }();
  return path;
}

/// A tall square tube, open at both ends, of 4 x 16 columns and 21 rows of rectangles, each
/// a polygon with 397 sides along each long side (796 corners, 794 triangles once
/// triangulated: 1 067 136 in all, lion-head Loop x3's count). Its faces' normals are
/// along x or y, so the first axis of their best-fit plane is horizontal and each long side
/// is 397 collinear sides of one abscissa: the case a sweep along that abscissa makes
/// quadratic.
std::string tube_of_long_polygons_file()
{
  static const std::string path = [] {
    const int columns = 16, rows = 21, steps = 397, around = 4 * columns, levels = rows * steps + 1;
    // The corners of the square's border, counter-clockwise seen from above, side 1 long.
    auto corner = [&](int c) -> std::array<double, 2> {
      const int side = c / columns;
      const double t = double(c % columns) / columns;
      switch(side)
      {
      case 0:
        return {t, 0};
      case 1:
        return {1, t};
      case 2:
        return {1 - t, 1};
      default:
        return {0, 1 - t};
      }
    };
    std::vector<std::array<double, 3>> points;
    for(int c = 0; c < around; ++c)
      for(int z = 0; z < levels; ++z)
        points.push_back({corner(c)[0], corner(c)[1], 100.0 * z / (levels - 1)});
    auto point = [&](int c, int z) { return std::size_t((c % around) * levels + z); };
    std::vector<std::vector<std::size_t>> faces;
    for(int c = 0; c < around; ++c)
      for(int r = 0; r < rows; ++r)
      {
        std::vector<std::size_t> face;
        for(int z = r * steps; z <= (r + 1) * steps; ++z) // up the column's right side
          face.push_back(point(c + 1, z));
        for(int z = (r + 1) * steps; z >= r * steps; --z) // down its left side
          face.push_back(point(c, z));
        faces.push_back(face);
      }
    const std::string file = temporary_file("tube_of_long_polygons.off");
    write_off(file, points, faces);
    return file;
  }();
  return path;
}

/// Reading a file with triangulation on, as icm_param --triangulate does.
void BM_read_triangle_mesh(benchmark::State& state)
{
  const bool tube = state.range(0) != 0;
  const std::string path = tube ? tube_of_long_polygons_file() : lion_head_loop3_file();
  if(path.empty())
  {
    state.SkipWithError("lion-head.off not found (ICM_BENCHMARK_LION_HEAD)");
    return;
  }
  ICM::IO::Mesh_reading_options options;
  options.triangulate = true;
  ICM::IO::Mesh_reading_report report;
  Mesh mesh;
  for(auto _ : state)
  {
    if(!ICM::IO::read_triangle_mesh(path, mesh, report, options))
    {
      state.SkipWithError(report.message.c_str());
      return;
    }
    benchmark::DoNotOptimize(mesh.number_of_faces());
  }
  state.counters["faces"] = static_cast<double>(mesh.number_of_faces());
  state.counters["file_faces"] = static_cast<double>(report.file_faces);
  state.SetLabel(tube ? "tube of long polygons" : "lion-head Loop x3");
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
BENCHMARK(BM_read_triangle_mesh)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
