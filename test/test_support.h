// What several test suites need: the bundled and shared mesh paths, whole-file text I/O, and
// a scratch directory that disappears with its content.

#ifndef ICM_TEST_SUPPORT_H
#define ICM_TEST_SUPPORT_H

#include <ICM/internal/Mesh_index.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/intersections.h>

#include <Eigen/Core>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>
#include <system_error>

#ifndef _WIN32
#include <unistd.h>
#endif

namespace icm_test {

namespace fs = std::filesystem;

/// A mesh of `examples/data`.
inline std::string data_path(const std::string& name)
{
  return std::string(ICM_TEST_DATA_DIR) + "/" + name;
}
/// A mesh of `../shared/data/meshes`; tests that need it skip when it is missing.
inline std::string shared_path(const std::string& name)
{
  return std::string(ICM_SHARED_MESH_DIR) + "/" + name;
}
inline bool shared_dir_exists()
{
  return fs::is_directory(ICM_SHARED_MESH_DIR);
}

/// A typed test's name from its metric's `name` ("intrinsic-delaunay" -> "intrinsic_delaunay"):
/// gtest reads '-' in a filter as "except", so ctest's filter of a name with a '-' would
/// select no test and report it passed.
struct Metric_test_names
{
  template <class T>
  static std::string GetName(int)
  {
    std::string name = T::name;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  }
};

/// A parameterized test's name from a mesh file name: every character that is not a letter
/// or a digit becomes '_' (gtest names allow no other), e.g. "lion-head.off" -> "lion_head_off".
struct Mesh_file_test_name
{
  template <class Param_info>
  std::string operator()(const Param_info& info) const
  {
    std::string name(info.param);
    for(char& c : name)
      if(!std::isalnum(static_cast<unsigned char>(c)))
        c = '_';
    return name;
  }
};

/// The indexed first component of a mesh file.
inline ICM::internal::Mesh_index index_of(const std::string& path)
{
  CGAL::Surface_mesh<CGAL::Simple_cartesian<double>::Point_3> mesh;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(path, mesh)) << path;
  ICM::internal::Mesh_index index;
  std::vector<decltype(mesh)::Vertex_index> vertices;
  const ICM::Status status =
    ICM::internal::index_mesh(mesh, *faces(mesh).begin(), get(CGAL::vertex_point, mesh), index, vertices);
  EXPECT_TRUE(status.ok()) << status.message;
  return index;
}

/// A planar grid of equilateral triangles: every circle packing with tangent circles of
/// radius l/2 reproduces it exactly.
/// The mesh of a bundled data file, indexed.
inline ICM::internal::Mesh_index index_file(const std::string& name)
{
  return index_of(data_path(name));
}

inline ICM::internal::Mesh_index equilateral_grid(int n)
{
  ICM::internal::Mesh_index index;
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
inline ICM::internal::Mesh_index equilateral_strip(int m)
{
  ICM::internal::Mesh_index index;
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

inline std::vector<char> interior_of(const ICM::internal::Mesh_index& index)
{
  std::vector<char> interior(index.number_of_vertices());
  for(int v = 0; v < index.number_of_vertices(); ++v)
    interior[v] = !index.is_boundary_vertex[v];
  return interior;
}

/// `u0` plus uniform noise in [-amplitude, amplitude], reproducible from `seed`.
inline Eigen::VectorXd random_perturbation(const Eigen::VectorXd& u0, double amplitude, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Eigen::VectorXd u = u0;
  for(int i = 0; i < u.size(); ++i)
    u[i] += d(rng);
  return u;
}

/// The dense Delta (nothing pinned) of the per-edge weights.
inline Eigen::MatrixXd dense_laplacian(const ICM::internal::Mesh_index& index, const std::vector<double>& w)
{
  const int n = index.number_of_vertices();
  Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(n, n);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int i = index.edges[e][0], j = index.edges[e][1];
    delta(i, j) -= w[e];
    delta(j, i) -= w[e];
    delta(i, i) += w[e];
    delta(j, j) += w[e];
  }
  return delta;
}

/// Largest relative difference, over every `stride`-th vertex, between column j of `delta`
/// and the central difference of the curvature map K at `u` in u_j.
template <class Curvature>
double jacobian_finite_difference_error(Curvature& curvature, const Eigen::VectorXd& u, const Eigen::MatrixXd& delta,
                                        int stride)
{
  const double h = 1e-6;
  double worst = 0;
  for(int j = 0; j < u.size(); j += stride)
  {
    Eigen::VectorXd up = u, down = u, kp, km;
    up[j] += h;
    down[j] -= h;
    curvature.evaluate(up, kp);
    curvature.evaluate(down, km);
    const Eigen::VectorXd column = (kp - km) / (2 * h);
    worst = std::max(worst, (column - delta.col(j)).cwiseAbs().maxCoeff() / delta.col(j).cwiseAbs().maxCoeff());
  }
  return worst;
}

inline std::string read_text(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

inline void write_text(const fs::path& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << path;
}

/// A fresh directory under GoogleTest's temporary directory, named after the process and
/// the running test, removed with its content.
class Scratch_directory
{
public:
  explicit Scratch_directory(const std::string& prefix)
  {
    static std::atomic<int> counter{0};
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(testing::TempDir()) / (prefix + "_" + std::to_string(static_cast<long>(::getpid())) + "_" +
                                            std::string(info ? info->name() : "x") + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch_directory()
  {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  Scratch_directory(const Scratch_directory&) = delete;
  Scratch_directory& operator=(const Scratch_directory&) = delete;

  const fs::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::size_t number_of_entries() const
  {
    std::size_t n = 0;
    for(auto it = fs::directory_iterator(path_); it != fs::directory_iterator(); ++it)
      ++n;
    return n;
  }

private:
  fs::path path_;
};

/// Newton's quadratic convergence: once in the quadratic regime (full steps, r < 1e-2),
/// r_{k+1} <= C r_k^2 on every step before the residual reaches rounding; at least one such step.
inline void expect_quadratic_convergence(const std::vector<double>& r)
{
  int quadratic_steps = 0;
  for(std::size_t i = 0; i + 1 < r.size(); ++i)
    if(r[i] < 1e-2 && r[i + 1] > 1e-12)
    {
      EXPECT_LT(r[i + 1], 50.0 * r[i] * r[i]) << "step " << i;
      ++quadratic_steps;
    }
  EXPECT_GE(quadratic_steps, 1);
}

/// Pairs of border edges (any loops) of a FaceGraph whose UV segments meet other than at a
/// common vertex, pair by pair: the plain count against which the library's is checked.
template <class Mesh, class UvMap>
int crossing_border_edges(const Mesh& mesh, const UvMap& uv)
{
  using Point = typename boost::property_traits<UvMap>::value_type;
  using Segment = typename CGAL::Kernel_traits<Point>::Kernel::Segment_2;
  using halfedge_descriptor = typename boost::graph_traits<Mesh>::halfedge_descriptor;
  std::vector<halfedge_descriptor> border;
  for(halfedge_descriptor h : halfedges(mesh))
    if(is_border(h, mesh))
      border.push_back(h);
  int crossings = 0;
  for(std::size_t i = 0; i < border.size(); ++i)
    for(std::size_t j = i + 1; j < border.size(); ++j)
    {
      const auto a = source(border[i], mesh), b = target(border[i], mesh), c = source(border[j], mesh),
                 d = target(border[j], mesh);
      if(a == c || a == d || b == c || b == d)
        continue;
      crossings += CGAL::do_intersect(Segment(get(uv, a), get(uv, b)), Segment(get(uv, c), get(uv, d)));
    }
  return crossings;
}

} // namespace icm_test

#endif // ICM_TEST_SUPPORT_H
