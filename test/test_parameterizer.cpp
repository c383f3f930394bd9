// Tests of Inverse_curvature_map_parameterizer_3: the CGAL drop-in path on Surface_mesh,
// Polyhedron_3 and Seam_mesh, analytic cases (planar disks, a spherical cap), the real disk
// meshes of the shared data set, nearly closed surfaces, and every kind of bad input.

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/IO/read_seam_selection.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/io.h>

#include <boost/property_map/property_map.hpp>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <queue>
#include <random>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Surface_mesh = CGAL::Surface_mesh<Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
using SM_vertex = Surface_mesh::Vertex_index;
using SM_halfedge = Surface_mesh::Halfedge_index;
using SM_face = Surface_mesh::Face_index;
namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace fs = std::filesystem;

template <class Mesh>
using Parameterizer = ICM::Inverse_curvature_map_parameterizer_3<Mesh>;

const double nan_value = std::numeric_limits<double>::quiet_NaN();

using icm_test::data_path;
using icm_test::shared_dir_exists;
using icm_test::shared_path;

template <class Mesh>
void read_mesh(const std::string& path, Mesh& mesh)
{
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(path, mesh)) << "cannot read " << path;
  ASSERT_FALSE(faces(mesh).empty()) << path;
}

/// Number of border cycles and Euler characteristic of a (connected) mesh.
template <class Mesh>
std::pair<int, int> topology(const Mesh& mesh)
{
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  const int chi =
    static_cast<int>(num_vertices(mesh)) - static_cast<int>(num_edges(mesh)) + static_cast<int>(num_faces(mesh));
  return {static_cast<int>(cycles.size()), chi};
}

// ---------------------------------------------------------------------------------------------
// Mesh builders

/// A disk of concentric rings: ring i (i = first_ring..rings) has 6 i points at radius
/// radius(i, k) and angle angle(i, k); ring 0 is the centre. Consecutive rings are zipped by
/// angle. Faces are counter-clockwise seen from +z (or from outside for the cap).
/// first_ring = 1 leaves out the centre: an annulus (two boundary loops).
template <class Position>
Surface_mesh ring_disk(int rings, Position position, int first_ring = 0)
{
  Surface_mesh mesh;
  std::vector<std::vector<SM_vertex>> ring(rings + 1);
  std::vector<std::vector<double>> angle(rings + 1);
  for(int i = first_ring; i <= rings; ++i)
  {
    const int n = i == 0 ? 1 : 6 * i;
    for(int k = 0; k < n; ++k)
    {
      double a = 0;
      ring[i].push_back(mesh.add_vertex(position(i, k, n, a)));
      angle[i].push_back(a);
    }
  }
  for(int i = first_ring; i < rings; ++i)
  {
    const std::vector<SM_vertex>&inner = ring[i], &outer = ring[i + 1];
    const int n = static_cast<int>(inner.size()), m = static_cast<int>(outer.size());
    if(n == 1)
    {
      for(int b = 0; b < m; ++b)
        EXPECT_NE(mesh.add_face(inner[0], outer[b], outer[(b + 1) % m]), Surface_mesh::null_face());
      continue;
    }
    auto next_angle = [](const std::vector<double>& a, int j) {
      const int size = static_cast<int>(a.size());
      return a[j % size] + (j >= size ? 2 * CGAL_PI : 0.0);
    };
    int a = 0, b = 0;
    while(a < n || b < m)
    {
      const bool advance_outer = a == n || (b < m && next_angle(angle[i + 1], b + 1) <= next_angle(angle[i], a + 1));
      if(advance_outer)
      {
        EXPECT_NE(mesh.add_face(inner[a % n], outer[b % m], outer[(b + 1) % m]), Surface_mesh::null_face());
        ++b;
      }
      else
      {
        EXPECT_NE(mesh.add_face(inner[a % n], outer[b % m], inner[(a + 1) % n]), Surface_mesh::null_face());
        ++a;
      }
    }
  }
  return mesh;
}

/// A planar disk of radius 1 at z = 0 with jittered interior points: irregular triangles.
Surface_mesh jittered_planar_disk(int rings, unsigned seed, double amplitude = 0.3)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
  return ring_disk(rings, [&](int i, int k, int n, double& a) {
    a = 2 * CGAL_PI * k / n;
    double r = static_cast<double>(i) / rings;
    if(i > 0 && i < rings)
    {
      a += jitter(random) * 2 * CGAL_PI / n;
      r += jitter(random) / rings;
    }
    return Point_3(r * std::cos(a), r * std::sin(a), 0);
  });
}

/// Points on the unit sphere with polar angle below max_polar_angle, the rings evenly spaced
/// in polar angle.
Surface_mesh spherical_cap(int rings, double max_polar_angle)
{
  return ring_disk(rings, [&](int i, int k, int n, double& a) {
    a = 2 * CGAL_PI * k / n;
    const double theta = max_polar_angle * i / rings;
    return Point_3(std::sin(theta) * std::cos(a), std::sin(theta) * std::sin(a), std::cos(theta));
  });
}

/// The hexagon of the regular triangular lattice with `radius` edges per side: every edge has
/// length 1, every triangle is equilateral. With `jitter` > 0, every interior point moves by
/// up to `jitter` (a fraction of the edge length) in x and y: irregular planar triangles.
Surface_mesh lattice_hexagon(int radius, double jitter = 0, unsigned seed = 1)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  Surface_mesh mesh;
  std::map<std::pair<int, int>, SM_vertex> vertex;
  for(int q = -radius; q <= radius; ++q)
    for(int r = -radius; r <= radius; ++r)
      if(std::abs(q + r) <= radius)
      {
        const bool interior = std::abs(q) < radius && std::abs(r) < radius && std::abs(q + r) < radius;
        const double dx = interior && jitter > 0 ? offset(random) : 0.0;
        const double dy = interior && jitter > 0 ? offset(random) : 0.0;
        vertex[{q, r}] = mesh.add_vertex(Point_3(q + 0.5 * r + dx, 0.5 * std::sqrt(3.0) * r + dy, 0));
      }
  auto find = [&](int q, int r) {
    auto it = vertex.find({q, r});
    return it == vertex.end() ? Surface_mesh::null_vertex() : it->second;
  };
  for(int q = -radius; q <= radius; ++q)
  {
    for(int r = -radius; r <= radius; ++r)
    {
      const SM_vertex a = find(q, r), b = find(q + 1, r), c = find(q, r + 1), d = find(q + 1, r + 1);
      if(a != Surface_mesh::null_vertex() && b != Surface_mesh::null_vertex() && c != Surface_mesh::null_vertex())
      {
        EXPECT_NE(mesh.add_face(a, b, c), Surface_mesh::null_face());
      }
      if(b != Surface_mesh::null_vertex() && d != Surface_mesh::null_vertex() && c != Surface_mesh::null_vertex())
      {
        EXPECT_NE(mesh.add_face(b, d, c), Surface_mesh::null_face());
      }
    }
  }
  return mesh;
}

/// Removes the faces around `v` (in rotational order, so the hole grows as one disk).
void punch_hole(Surface_mesh& mesh, SM_vertex v)
{
  std::vector<SM_face> around;
  for(SM_face f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
    if(f != Surface_mesh::null_face())
      around.push_back(f);
  for(SM_face f : around)
    CGAL::Euler::remove_face(mesh.halfedge(f), mesh);
  mesh.collect_garbage();
}

// ---------------------------------------------------------------------------------------------
// Running and checking

/// UV property of a Surface_mesh, every value NaN before the run.
Surface_mesh::Property_map<SM_vertex, Point_2> nan_uv_map(Surface_mesh& mesh)
{
  auto uv = mesh.add_property_map<SM_vertex, Point_2>("v:test_uv", Point_2(nan_value, nan_value)).first;
  for(SM_vertex v : vertices(mesh))
    put(uv, v, Point_2(nan_value, nan_value));
  return uv;
}

struct Outcome
{
  SMP::Error_code status = SMP::ERROR_EMPTY_MESH;
  ICM::Parameterization_report report;
};

/// The drop-in path: CGAL's parameterize() from the border halfedge `bhd`.
template <class Metric = CGAL::Default, class Mesh, class Halfedge, class UvMap>
Outcome run_cgal_from(Mesh& mesh, Halfedge bhd, UvMap uvmap, const ICM::Parameterization_options& options = {})
{
  ICM::Inverse_curvature_map_parameterizer_3<Mesh, Metric> parameterizer(options);
  Outcome run;
  run.status = SMP::parameterize(mesh, parameterizer, bhd, uvmap);
  run.report = parameterizer.report();
  return run;
}

/// The drop-in path: CGAL's parameterize() with the longest border.
template <class Metric = CGAL::Default, class Mesh, class UvMap>
Outcome run_cgal(Mesh& mesh, UvMap uvmap, const ICM::Parameterization_options& options = {})
{
  return run_cgal_from<Metric>(mesh, PMP::longest_border(mesh).first, uvmap, options);
}

/// The member function directly, with any halfedge (null, interior...).
Outcome run_direct(Surface_mesh& mesh, SM_halfedge bhd)
{
  auto uv = nan_uv_map(mesh);
  auto parameterized = mesh.add_property_map<SM_vertex, bool>("v:test_parameterized", false).first;
  Parameterizer<Surface_mesh> parameterizer;
  Outcome run;
  run.status = parameterizer.parameterize(mesh, bhd, uv, get(CGAL::vertex_index, mesh), parameterized);
  run.report = parameterizer.report();
  return run;
}

/// The checks every successful run must pass, with the distortion measured independently.
template <class Mesh, class UvMap>
void expect_good_run(const Outcome& run, const Mesh& mesh, UvMap uvmap, const std::string& what,
                     int max_newton_iterations = 10, bool allow_degenerate_uv_faces = false,
                     double max_layout_length_error = 1e-8)
{
  ASSERT_EQ(run.status, SMP::OK) << what << ": " << run.report.message;
  EXPECT_EQ(run.report.status, SMP::OK) << what;
  EXPECT_TRUE(run.report.message.empty()) << what << ": " << run.report.message;
  EXPECT_LE(run.report.newton_iterations, max_newton_iterations) << what;
  EXPECT_LT(run.report.max_curvature_error, 1e-9) << what;
  EXPECT_EQ(run.report.flipped_faces, 0) << what;
  EXPECT_LT(run.report.max_layout_length_error, max_layout_length_error) << what;
  EXPECT_EQ(run.report.boundary_loops, 1) << what;
  EXPECT_EQ(run.report.genus, 0) << what;
  EXPECT_EQ(run.report.euler_characteristic, 1) << what;
  EXPECT_EQ(run.report.vertices, static_cast<int>(num_vertices(mesh))) << what;
  EXPECT_EQ(run.report.faces, static_cast<int>(num_faces(mesh))) << what;

  int non_finite = 0;
  for(auto v : vertices(mesh))
  {
    const auto p = get(uvmap, v);
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()))
      ++non_finite;
  }
  EXPECT_EQ(non_finite, 0) << what << ": vertices without a finite UV";
  if(non_finite == 0)
  {
    EXPECT_EQ(run.report.overlapping_border_edges, icm_test::crossing_border_edges(mesh, uvmap)) << what;
  }

  const ICM::Distortion_measures measures = ICM::measure_distortion(mesh, uvmap);
  EXPECT_EQ(measures.flipped_faces, 0u) << what;
  if(!allow_degenerate_uv_faces)
  {
    EXPECT_EQ(measures.degenerate_uv_faces, 0u) << what;
  }
  EXPECT_EQ(measures.faces, num_faces(mesh)) << what;
}

/// UV length of every edge of a Surface_mesh, keyed by the (sorted) vertex indices.
template <class UvMap>
std::map<std::pair<std::size_t, std::size_t>, double> uv_edge_lengths(const Surface_mesh& mesh, UvMap uv)
{
  std::map<std::pair<std::size_t, std::size_t>, double> lengths;
  for(auto e : edges(mesh))
  {
    const SM_vertex a = source(e, mesh), b = target(e, mesh);
    const Point_2 p = get(uv, a), q = get(uv, b);
    lengths[std::minmax(std::size_t(a), std::size_t(b))] = std::sqrt(CGAL::squared_distance(p, q));
  }
  return lengths;
}

/// Max relative difference of two edge length tables over the same edges.
double max_relative_difference(const std::map<std::pair<std::size_t, std::size_t>, double>& a,
                               const std::map<std::pair<std::size_t, std::size_t>, double>& b)
{
  EXPECT_EQ(a.size(), b.size());
  double worst = 0;
  for(const auto& [key, length] : a)
  {
    const auto it = b.find(key);
    if(it == b.end())
      return HUGE_VAL;
    worst = std::max(worst, std::abs(it->second / length - 1.0));
  }
  return worst;
}

/// Per face: UV area / 3D area (raw, not normalised).
template <class UvMap>
double face_area_ratio(const Surface_mesh& mesh, UvMap uv, SM_face f)
{
  std::array<Point_3, 3> p;
  std::array<Point_2, 3> q;
  int c = 0;
  for(SM_vertex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
  {
    p[c] = mesh.point(v);
    q[c] = get(uv, v);
    ++c;
  }
  return CGAL::area(q[0], q[1], q[2]) / std::sqrt(CGAL::squared_area(p[0], p[1], p[2]));
}

// =============================================================================================
// 1. The CGAL drop-in path

TEST(ParameterizerDropIn, SurfaceMeshAndPolyhedronAgree)
{
  Surface_mesh sm;
  read_mesh(data_path("nefertiti.off"), sm);
  auto sm_uv = nan_uv_map(sm);
  const Outcome sm_run = run_cgal(sm, sm_uv);
  expect_good_run(sm_run, sm, sm_uv, "Surface_mesh nefertiti");
  EXPECT_EQ(sm_run.report.vertices, 299);
  EXPECT_EQ(sm_run.report.faces, 562);

  Polyhedron poly;
  read_mesh(data_path("nefertiti.off"), poly);
  using P_vertex = boost::graph_traits<Polyhedron>::vertex_descriptor;
  std::unordered_map<P_vertex, Point_2> poly_uv_storage;
  for(P_vertex v : vertices(poly))
    poly_uv_storage[v] = Point_2(nan_value, nan_value);
  boost::associative_property_map<std::unordered_map<P_vertex, Point_2>> poly_uv(poly_uv_storage);
  const Outcome poly_run = run_cgal(poly, poly_uv);
  expect_good_run(poly_run, poly, poly_uv, "Polyhedron_3 nefertiti");

  // Same file, same vertex order: compare the UV length of every edge.
  ASSERT_EQ(num_vertices(poly), num_vertices(sm));
  std::vector<Point_2> poly_uv_by_index;
  for(P_vertex v : vertices(poly))
    poly_uv_by_index.push_back(get(poly_uv, v));
  for(SM_vertex v : vertices(sm))
    ASSERT_EQ(sm.point(v), (*std::next(vertices(poly).begin(), std::size_t(v)))->point());
  auto sm_lengths = uv_edge_lengths(sm, sm_uv);
  auto poly_uv_as_sm = sm.add_property_map<SM_vertex, Point_2>("v:poly_uv").first;
  for(SM_vertex v : vertices(sm))
    put(poly_uv_as_sm, v, poly_uv_by_index[std::size_t(v)]);
  EXPECT_LT(max_relative_difference(sm_lengths, uv_edge_lengths(sm, poly_uv_as_sm)), 1e-8)
    << "Surface_mesh and Polyhedron_3 layouts differ by more than a rigid motion";
  EXPECT_EQ(sm_run.report.newton_iterations, poly_run.report.newton_iterations);
  EXPECT_NEAR(sm_run.report.max_curvature_error, poly_run.report.max_curvature_error, 1e-9);
}

using SM_edge = Surface_mesh::Edge_index;
using Seam_edge_pmap = Surface_mesh::Property_map<SM_edge, bool>;
using Seam_vertex_pmap = Surface_mesh::Property_map<SM_vertex, bool>;
using Seam_mesh = CGAL::Seam_mesh<Surface_mesh, Seam_edge_pmap, Seam_vertex_pmap>;

/// Breadth-first shortest path (in edges) from `from` to the first vertex `hops` edges away.
std::vector<SM_vertex> bfs_path(const Surface_mesh& mesh, SM_vertex from, int hops)
{
  std::vector<int> depth(num_vertices(mesh), -1);
  std::vector<SM_vertex> parent(num_vertices(mesh));
  std::queue<SM_vertex> queue;
  depth[std::size_t(from)] = 0;
  queue.push(from);
  SM_vertex end = from;
  while(!queue.empty() && end == from)
  {
    const SM_vertex v = queue.front();
    queue.pop();
    for(SM_vertex w : CGAL::vertices_around_target(mesh.halfedge(v), mesh))
      if(depth[std::size_t(w)] < 0)
      {
        depth[std::size_t(w)] = depth[std::size_t(v)] + 1;
        parent[std::size_t(w)] = v;
        if(depth[std::size_t(w)] == hops)
        {
          end = w;
          break;
        }
        queue.push(w);
      }
  }
  std::vector<SM_vertex> path;
  if(end == from)
    return path;
  for(SM_vertex v = end; v != from; v = parent[std::size_t(v)])
    path.push_back(v);
  path.push_back(from);
  return path;
}

TEST(ParameterizerDropIn, SeamMeshOfClosedSphere)
{
  Surface_mesh sm;
  read_mesh(data_path("sphere966.off"), sm);
  ASSERT_EQ(topology(sm), std::make_pair(0, 2)) << "sphere966 should be a closed sphere";

  Seam_edge_pmap seam_edges = sm.add_property_map<SM_edge, bool>("e:on_seam", false).first;
  Seam_vertex_pmap seam_vertices = sm.add_property_map<SM_vertex, bool>("v:on_seam", false).first;
  Seam_mesh mesh(sm, seam_edges, seam_vertices);

  const std::vector<SM_vertex> path = bfs_path(sm, *vertices(sm).begin(), 10);
  ASSERT_EQ(path.size(), 11u);
  for(std::size_t i = 0; i + 1 < path.size(); ++i)
    ASSERT_TRUE(mesh.add_seam(path[i], path[i + 1]));
  EXPECT_EQ(mesh.number_of_seam_edges(), 10u);

  // The cut sphere: a disk whose border runs both ways along the path; the 9 inner path
  // vertices have two copies each.
  ASSERT_EQ(num_vertices(mesh), num_vertices(sm) + 9u);
  boost::graph_traits<Seam_mesh>::halfedge_descriptor bhd;
  int border_halfedges = 0;
  for(auto h : halfedges(mesh))
    if(is_border(h, mesh))
    {
      bhd = h;
      ++border_halfedges;
    }
  ASSERT_EQ(border_halfedges, 20);

  // UVs on the canonical halfedges of the seam mesh vertices, as in CGAL's seam examples.
  auto uv_pm = sm.add_property_map<SM_halfedge, Point_2>("h:uv", Point_2(nan_value, nan_value)).first;
  const Outcome run = run_cgal_from(mesh, bhd, uv_pm);
  expect_good_run(run, mesh, uv_pm, "Seam_mesh of sphere966");
  EXPECT_EQ(run.report.vertices, static_cast<int>(num_vertices(sm)) + 9);
  EXPECT_EQ(run.report.faces, static_cast<int>(num_faces(sm)));

  // Both copies of an inner path vertex got a UV, and they differ: the seam really opened.
  std::map<SM_vertex, std::vector<Point_2>> copies;
  for(auto v : vertices(mesh))
    copies[target(v.hd.tmhd, sm)].push_back(get(uv_pm, v));
  for(std::size_t i = 1; i + 1 < path.size(); ++i)
  {
    ASSERT_EQ(copies[path[i]].size(), 2u) << "path vertex " << i;
    EXPECT_GT(std::sqrt(CGAL::squared_distance(copies[path[i]][0], copies[path[i]][1])), 1e-6) << "path vertex " << i;
  }
  EXPECT_EQ(copies[path.front()].size(), 1u);
  EXPECT_EQ(copies[path.back()].size(), 1u);
}

/// max over the seam edges of the relative difference between the UV lengths of their two
/// sides in a Seam_mesh parameterized into `uv_pm` (one UV per seam-mesh vertex), and max
/// over the seam vertices passed by exactly two seam edges of |2 pi - their UV angle sum over
/// both sides|: zero when the sides are one flat surface cut open.
template <class UvMap>
std::pair<double, double> seam_mismatch(const Seam_mesh& mesh, const Surface_mesh& sm, UvMap uv_pm)
{
  using Seam_halfedge = boost::graph_traits<Seam_mesh>::halfedge_descriptor;
  auto uv_length = [&](SM_halfedge h) {
    const Seam_halfedge sh(h);
    return std::sqrt(CGAL::squared_distance(get(uv_pm, target(sh, mesh)), get(uv_pm, source(sh, mesh))));
  };
  double worst_length = 0;
  std::map<SM_vertex, int> seam_degree;
  for(SM_edge e : edges(sm))
    if(mesh.has_on_seam(e))
    {
      const double a = uv_length(halfedge(e, sm)), b = uv_length(opposite(halfedge(e, sm), sm));
      worst_length = std::max(worst_length, std::abs(a - b) / std::max(a, b));
      ++seam_degree[source(e, sm)];
      ++seam_degree[target(e, sm)];
    }
  std::map<SM_vertex, double> angle_sum;
  for(SM_halfedge h : halfedges(sm))
    if(!is_border(h, sm))
    {
      const Seam_halfedge sh(h);
      const Point_2 p = get(uv_pm, target(sh, mesh)), a = get(uv_pm, source(sh, mesh)),
                    b = get(uv_pm, target(next(sh, mesh), mesh));
      const Kernel::Vector_2 to_a = a - p, to_b = b - p;
      angle_sum[target(h, sm)] += std::atan2(std::abs(CGAL::determinant(to_a, to_b)), to_a * to_b);
    }
  double worst_angle = 0;
  for(const auto& [v, degree] : seam_degree)
    if(degree == 2)
      worst_angle = std::max(worst_angle, std::abs(angle_sum[v] - 2 * M_PI));
  return {worst_length, worst_angle};
}

TEST(ParameterizerDropIn, SeamMeshSeamsReadAsBorderOrAsCuts)
{
  // The bundled star of 44 seam edges on sphere966. Read as border (CGAL's reading), the two
  // sides of a seam are free border: one length (u - u0 is one constant on the border), but
  // each side turns its own way. Read as cuts of the sphere, every vertex inside a seam is
  // flat across both sides, and the star's 4 ends and its centre are the only cones.
  Surface_mesh sm;
  read_mesh(data_path("sphere966.off"), sm);
  std::vector<SM_edge> star;
  std::string error;
  ASSERT_TRUE(ICM::IO::read_seam_selection(data_path("sphere966.selection.txt"), sm, star, error)) << error;
  Seam_edge_pmap seam_edges = sm.add_property_map<SM_edge, bool>("e:on_seam", false).first;
  Seam_vertex_pmap seam_vertices = sm.add_property_map<SM_vertex, bool>("v:on_seam", false).first;
  Seam_mesh mesh(sm, seam_edges, seam_vertices);
  for(SM_edge e : star)
    ASSERT_TRUE(mesh.add_seam(source(e, sm), target(e, sm)));
  boost::graph_traits<Seam_mesh>::halfedge_descriptor bhd;
  for(auto h : halfedges(mesh))
    if(is_border(h, mesh))
      bhd = h;

  // As border: CGAL's parameterize() with the disk parameterizer.
  auto border_uv = sm.add_property_map<SM_halfedge, Point_2>("h:uv_border", Point_2(nan_value, nan_value)).first;
  expect_good_run(run_cgal_from(mesh, bhd, border_uv), mesh, border_uv, "seams as border");
  const auto [border_length_mismatch, border_angle_defect] = seam_mismatch(mesh, sm, border_uv);
  EXPECT_LT(border_length_mismatch, 1e-7);
  EXPECT_GT(border_angle_defect, 1e-2);

  // As cuts: ICM::parameterize on the seam mesh, the seams' ends and centre its only cones.
  auto cut_uv = sm.add_property_map<SM_halfedge, Point_2>("h:uv_cut", Point_2(nan_value, nan_value)).first;
  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, cut_uv);
  ASSERT_EQ(report.status, SMP::OK) << report.message;
  ASSERT_EQ(report.charts.size(), 1u);
  EXPECT_EQ(report.charts[0].flipped_faces, 0);
  EXPECT_EQ(report.charts[0].seam_edges, static_cast<int>(star.size()));
  EXPECT_EQ(report.charts[0].cones.size(), 5u);
  for(auto v : vertices(mesh))
    EXPECT_TRUE(std::isfinite(get(cut_uv, v).x()) && std::isfinite(get(cut_uv, v).y()));
  EXPECT_EQ(ICM::measure_distortion(mesh, cut_uv).flipped_faces, 0u);
  const auto [cut_length_mismatch, cut_angle_defect] = seam_mismatch(mesh, sm, cut_uv);
  EXPECT_LT(cut_length_mismatch, 1e-9);
  EXPECT_LT(cut_angle_defect, 1e-8);
}

// =============================================================================================
// 2. The report is shared by the copies CGAL's parameterize() makes

TEST(ParameterizerReport, SharedWithCopies)
{
  Surface_mesh mesh;
  read_mesh(data_path("nefertiti.off"), mesh);
  auto uv = nan_uv_map(mesh);
  Parameterizer<Surface_mesh> parameterizer;
  const Parameterizer<Surface_mesh> copy = parameterizer;
  EXPECT_EQ(&copy.report(), &parameterizer.report());
  EXPECT_EQ(parameterizer.report().vertices, 0);

  std::vector<std::string> stages;
  parameterizer.options().progress = [&](const std::string& s) { stages.push_back(s); };
  const SMP::Error_code status =
    SMP::parameterize(mesh, parameterizer, PMP::longest_border(mesh).first, uv); // by value
  ASSERT_EQ(status, SMP::OK);
  const ICM::Parameterization_report& report = parameterizer.report();
  EXPECT_EQ(report.status, SMP::OK);
  EXPECT_EQ(report.vertices, 299);
  EXPECT_EQ(report.faces, 562);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_GE(report.newton_iterations, 1);
  EXPECT_EQ(report.residual_history.size(), static_cast<std::size_t>(report.newton_iterations) + 1);
  EXPECT_EQ(report.layout, "propagation");
  EXPECT_GT(report.seconds_total, 0.0);
  EXPECT_GE(report.seconds_total,
            report.seconds_index + report.seconds_metric + report.seconds_optimum + report.seconds_layout - 1e-9);
  EXPECT_EQ(copy.report().vertices, 299) << "a copy made before the run sees it too";
  EXPECT_EQ(stages, (std::vector<std::string>{"index", "metric", "optimum", "layout"}));

  // A failing run through another copy replaces the report everyone sees.
  Parameterizer<Surface_mesh> second = parameterizer;
  auto parameterized = mesh.add_property_map<SM_vertex, bool>("v:p", false).first;
  const SM_halfedge interior = mesh.halfedge(*faces(mesh).begin());
  EXPECT_EQ(second.parameterize(mesh, interior, uv, get(CGAL::vertex_index, mesh), parameterized),
            SMP::ERROR_WRONG_PARAMETER);
  EXPECT_EQ(parameterizer.report().status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_FALSE(parameterizer.report().message.empty());
  EXPECT_EQ(parameterizer.report().vertices, 0);
}

// =============================================================================================
// 3. Analytic cases

/// Every metric length of the layout equals the 3D length times one common scale, and the
/// map has no distortion at all: what a planar or developable mesh must get.
template <class UvMap>
void expect_isometric(const Surface_mesh& mesh, UvMap uv, const std::string& what)
{
  double ratio_min = HUGE_VAL, ratio_max = 0;
  for(auto e : edges(mesh))
  {
    const SM_vertex a = source(e, mesh), b = target(e, mesh);
    const double ratio =
      std::sqrt(CGAL::squared_distance(get(uv, a), get(uv, b)) / CGAL::squared_distance(mesh.point(a), mesh.point(b)));
    ratio_min = std::min(ratio_min, ratio);
    ratio_max = std::max(ratio_max, ratio);
  }
  EXPECT_LT(ratio_max / ratio_min - 1.0, 1e-9) << what << ": not a similarity of the input";
  const ICM::Distortion_measures m = ICM::measure_distortion(mesh, uv);
  EXPECT_NEAR(m.qc_mean, 1.0, 1e-9) << what;
  EXPECT_NEAR(m.qc_max, 1.0, 1e-9) << what;
  EXPECT_LT(m.log_area_distortion, 1e-12) << what;
}

TEST(ParameterizerAnalytic, EquilateralGridIsASimilarity)
{
  // All edges equal: tangent circles of radius l/2 (phi = 0) reproduce every edge exactly,
  // every interior vertex is already flat, so the optimum is the input metric itself.
  Surface_mesh mesh = lattice_hexagon(5);
  ASSERT_EQ(num_vertices(mesh), 91u);
  ASSERT_EQ(num_faces(mesh), 150u);
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  expect_good_run(run, mesh, uv, "equilateral hexagon");
  if(HasFatalFailure())
    return;
  EXPECT_EQ(run.report.metric, ICM::Default_metric::name);
  EXPECT_TRUE(run.report.fallback_reason.empty()) << run.report.fallback_reason;

  expect_isometric(mesh, uv, "equilateral hexagon");
  // And the similarity preserves orientation: no face is mirrored.
  for(SM_face f : faces(mesh))
    EXPECT_GT(face_area_ratio(mesh, uv, f), 0.0);
}

TEST(ParameterizerAnalytic, JitteredPlanarLatticeMapsToItself)
{
  // Irregular planar triangles: the default metric is the mesh's own, already flat, so the
  // optimum is the input up to a similarity, exactly.
  for(double jitter : {0.05, 0.1})
  {
    Surface_mesh mesh = lattice_hexagon(8, jitter, 3);
    ASSERT_EQ(topology(mesh), std::make_pair(1, 1));
    auto uv = nan_uv_map(mesh);
    const Outcome run = run_cgal(mesh, uv);
    expect_good_run(run, mesh, uv, "jittered lattice " + std::to_string(jitter), 1);
    EXPECT_EQ(run.report.newton_iterations, 0); // flat already: nothing to solve
    expect_isometric(mesh, uv, "jittered lattice " + std::to_string(jitter));
  }
}

TEST(ParameterizerAnalytic, CirclePackingOfAJitteredLatticeIsOnlyNearlyIsometric)
{
  // The paper's metric: one circle per vertex cannot reproduce every edge length (disjoint
  // circles are made tangent, heavily overlapping ones orthogonal), so the result is close
  // to, not equal to, a similarity; the distortion vanishes with the irregularity.
  double conformality[2];
  const double jitter[2] = {0.05, 0.1};
  for(int j = 0; j < 2; ++j)
  {
    Surface_mesh mesh = lattice_hexagon(8, jitter[j], 3);
    auto uv = nan_uv_map(mesh);
    const Outcome run = run_cgal<ICM::Circle_packing_metric>(mesh, uv);
    expect_good_run(run, mesh, uv, "jittered lattice " + std::to_string(jitter[j]));
    if(HasFatalFailure())
      return;
    EXPECT_EQ(run.report.metric, "circle-packing");
    const ICM::Distortion_measures m = ICM::measure_distortion(mesh, uv);
    conformality[j] = m.conformality;
    // Measured at jitter 0.1: conformality 0.0033, log area 0.0034, qc mean 1.073.
    EXPECT_LT(m.conformality, 0.01) << jitter[j];
    EXPECT_LT(m.log_area_distortion, 0.05) << jitter[j];
    EXPECT_LT(m.qc_mean, 1.1) << jitter[j];
    EXPECT_GT(m.qc_mean, 1.01) << jitter[j]; // visibly not the mesh's own conformal class
  }
  // Roughly quadratic in the jitter (measured ratio 3.9).
  EXPECT_LT(conformality[0], 0.5 * conformality[1]);
}

TEST(ParameterizerAnalytic, RegularPolygonDiskMapsToItself)
{
  // A regular 48-gon filled with 8 rings (6 i points on ring i): planar, not equilateral.
  // The circle packing made it a moderate conformal distortion (qc mean 1.267); the mesh's
  // own metric keeps it.
  Surface_mesh mesh = jittered_planar_disk(8, 7, 0.0);
  ASSERT_EQ(num_vertices(mesh), 217u);
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  expect_good_run(run, mesh, uv, "regular polygon disk", 1);
  expect_isometric(mesh, uv, "regular polygon disk");
}

TEST(ParameterizerAnalytic, DevelopableDisksFlattenIsometrically)
{
  // A strip rolled into 3/4 of a cylinder and an annular sector of a cone (apex cut away)
  // are flat surfaces: with the default options their map must be an isometry.
  const int n = 24, m = 6;
  auto grid = [&](auto position) {
    Surface_mesh mesh;
    std::vector<SM_vertex> v;
    for(int j = 0; j <= m; ++j)
      for(int i = 0; i <= n; ++i)
        v.push_back(mesh.add_vertex(position(double(i) / n, double(j) / m)));
    auto id = [&](int i, int j) { return v[j * (n + 1) + i]; };
    for(int j = 0; j < m; ++j)
      for(int i = 0; i < n; ++i)
      {
        mesh.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        mesh.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      }
    return mesh;
  };
  const double turn = 1.5 * CGAL_PI;
  Surface_mesh cylinder =
    grid([&](double s, double t) { return Point_3(std::cos(turn * s), std::sin(turn * s), 2.0 * t); });
  // Cone of half-angle 30 deg: radius grows with slant distance r as r sin 30.
  Surface_mesh cone = grid([&](double s, double t) {
    const double r = 1.0 + 2.0 * t;
    return Point_3(0.5 * r * std::cos(turn * s), 0.5 * r * std::sin(turn * s), r * std::sqrt(0.75));
  });
  for(auto* mesh : {&cylinder, &cone})
  {
    const std::string what = mesh == &cylinder ? "rolled strip" : "cone without apex";
    ASSERT_EQ(topology(*mesh), std::make_pair(1, 1)) << what;
    auto uv = nan_uv_map(*mesh);
    const Outcome run = run_cgal(*mesh, uv);
    expect_good_run(run, *mesh, uv, what, 1);
    expect_isometric(*mesh, uv, what);
  }
}

TEST(ParameterizerAnalytic, SphericalCapMatchesStereographicScale)
{
  // The free-boundary optimum keeps the original scale on the border (u_S = u0_S) and is
  // conformal and flat inside, so its log scale u solves the flattening equation with u = 0
  // on the rim. Stereographic projection of the unit sphere is conformal with linear scale
  // 1/cos^2(theta/2); as the solution is unique, the optimum is that map rescaled to scale 1
  // at the rim theta = 60 deg: its area ratio at polar angle theta is
  // (cos^2(30 deg) / cos^2(theta/2))^2, 0.5625 at the centre and 1 at the rim. Positive
  // curvature leaves through the border: centre faces shrink more than rim faces.
  const double max_polar = CGAL_PI / 3;
  const int rings = 12;
  Surface_mesh mesh = spherical_cap(rings, max_polar);
  ASSERT_EQ(topology(mesh), std::make_pair(1, 1));
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  expect_good_run(run, mesh, uv, "spherical cap");
  if(HasFatalFailure())
    return;

  auto stereographic_ratio = [&](double theta) {
    const double c = std::cos(max_polar / 2), d = std::cos(theta / 2);
    return std::pow(c * c / (d * d), 2);
  };
  // Per band of faces between ring i and ring i + 1: mean of measured / predicted ratio.
  std::vector<double> band_sum(rings, 0.0);
  std::vector<int> band_count(rings, 0);
  double center_sum = 0, rim_sum = 0;
  int center_count = 0, rim_count = 0;
  for(SM_face f : faces(mesh))
  {
    Point_3 centroid(0, 0, 0);
    double max_z = -1, min_z = 2;
    for(SM_vertex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
    {
      centroid = centroid + (mesh.point(v) - CGAL::ORIGIN) / 3.0;
      max_z = std::max(max_z, mesh.point(v).z());
      min_z = std::min(min_z, mesh.point(v).z());
    }
    const double theta = std::atan2(std::hypot(centroid.x(), centroid.y()), centroid.z());
    const double ratio = face_area_ratio(mesh, uv, f);
    // The band is the inner ring of the face: the polar angle of its highest vertex.
    const int band = static_cast<int>(std::lround(std::acos(std::min(1.0, max_z)) / max_polar * rings));
    ASSERT_GE(band, 0);
    ASSERT_LT(band, rings);
    band_sum[band] += ratio / stereographic_ratio(theta);
    ++band_count[band];
    if(band == 0)
    {
      center_sum += ratio;
      ++center_count;
    }
    if(std::abs(min_z - std::cos(max_polar)) < 1e-12)
    {
      rim_sum += ratio;
      ++rim_count;
    }
  }
  ASSERT_EQ(center_count, 6);
  ASSERT_EQ(rim_count, 6 * rings + 6 * (rings - 1));
  for(int b = 0; b < rings; ++b)
  {
    ASSERT_GT(band_count[b], 0);
    const double mean = band_sum[b] / band_count[b];
    RecordProperty("band_" + std::to_string(b), std::to_string(mean));
    // Measured 0.92..1.02 with 12 rings (the rim band lowest).
    EXPECT_NEAR(mean, 1.0, 0.1) << "band " << b << ": area ratio vs stereographic prediction";
  }
  const double center = center_sum / center_count, rim = rim_sum / rim_count;
  RecordProperty("center_area_ratio", std::to_string(center));
  RecordProperty("rim_area_ratio", std::to_string(rim));
  EXPECT_LT(center, rim);
  // Face centroids: polar angle ~ 1/3 ring at the centre, ~ 11 2/3 rings at the rim.
  EXPECT_NEAR(center / rim, stereographic_ratio(max_polar / 36) / stereographic_ratio(max_polar * (1 - 1.0 / 36)),
              0.05);
}

// =============================================================================================
// 4. The disk meshes of the shared data set

class SharedDisk : public testing::TestWithParam<const char*>
{};

TEST_P(SharedDisk, Parameterizes)
{
  if(!shared_dir_exists())
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  Surface_mesh mesh;
  read_mesh(shared_path(GetParam()), mesh);
  ASSERT_EQ(topology(mesh).first, 1) << GetParam() << " should have one boundary loop";
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  expect_good_run(run, mesh, uv, GetParam());
  RecordProperty("newton_iterations", run.report.newton_iterations);
  RecordProperty("seconds_total", std::to_string(run.report.seconds_total));
}

INSTANTIATE_TEST_SUITE_P(Meshes, SharedDisk,
                         testing::Values("nefertiti.off", "mesh_with_border.off", "three_peaks.off", "mushroom.off",
                                         "cylinder_locally_refined.off", "lion-head.off", "camelhead.off",
                                         "mannequin-devil.off", "horse.obj"),
                         icm_test::Mesh_file_test_name());

TEST(ParameterizerMetric, FallsBackToTheCirclePackingWhenTheMeshsOwnClassCannotGetThere)
{
  // The horse's free-boundary optimum in plain vertex scaling (the mesh's edges kept) would
  // need faces that are no longer triangles: the parameterizer says so and uses the circle
  // packing. With the default, intrinsic Delaunay flips, it reaches the optimum and BFF's
  // conformality (BFF: qc mean 1.03; measured 1.033).
  if(!shared_dir_exists())
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  Surface_mesh mesh;
  read_mesh(shared_path("horse.obj"), mesh);
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal<ICM::Vertex_scaling_metric>(mesh, uv);
  expect_good_run(run, mesh, uv, "horse");
  EXPECT_EQ(run.report.metric, "circle-packing");
  EXPECT_NE(run.report.fallback_reason.find("vertex-scaling"), std::string::npos) << run.report.fallback_reason;
  EXPECT_NE(run.report.fallback_reason.find("valid region"), std::string::npos) << run.report.fallback_reason;

  // Without the fallback the same failure is the result, with the same reason.
  ICM::Parameterization_options strict;
  strict.fall_back_to_circle_packing = false;
  auto uv_strict = nan_uv_map(mesh);
  const Outcome refused = run_cgal<ICM::Vertex_scaling_metric>(mesh, uv_strict, strict);
  EXPECT_EQ(refused.status, SMP::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM);
  EXPECT_NE(refused.report.message.find("valid region"), std::string::npos) << refused.report.message;

  auto uv_default = nan_uv_map(mesh);
  const Outcome flipped = run_cgal(mesh, uv_default, strict);
  expect_good_run(flipped, mesh, uv_default, "horse, intrinsic Delaunay");
  EXPECT_EQ(flipped.report.metric, "intrinsic-delaunay");
  EXPECT_LE(flipped.report.moved_vertices, 2);
  // Without cones the free border swings a leg over another: said, not cut (one UV per vertex).
  EXPECT_EQ(flipped.report.overlapping_border_edges, 16);
  EXPECT_LT(ICM::measure_distortion(mesh, uv_default).qc_mean, 1.04);
}

TEST(ParameterizerMetric, OrdinaryDisksKeepTheirOwnConformalStructure)
{
  // Where the optimum is reachable in the mesh's own class, it is used, and the map is far
  // more conformal than the circle packing's (measured: qc mean 1.050 / 1.279 / 1.036 against
  // 1.343 / 2.208 / 1.455).
  const std::pair<const char*, double> cases[] = {
    {"nefertiti.off", 1.06}, {"three_peaks.off", 1.31}, {"mushroom.off", 1.05}};
  for(const auto& [name, max_qc] : cases)
  {
    Surface_mesh mesh;
    read_mesh(data_path(name), mesh);
    auto uv = nan_uv_map(mesh);
    const Outcome run = run_cgal(mesh, uv);
    expect_good_run(run, mesh, uv, name);
    EXPECT_EQ(run.report.metric, "intrinsic-delaunay") << name;
    EXPECT_TRUE(run.report.fallback_reason.empty()) << name << ": " << run.report.fallback_reason;
    const ICM::Distortion_measures m = ICM::measure_distortion(mesh, uv);
    EXPECT_LT(m.qc_mean, max_qc) << name;

    auto uv_packing = nan_uv_map(mesh);
    run_cgal<ICM::Circle_packing_metric>(mesh, uv_packing);
    EXPECT_LT(m.qc_mean, ICM::measure_distortion(mesh, uv_packing).qc_mean) << name;
  }
}

TEST(ParameterizerLayout, PropagationAndHarmonicAgree)
{
  if(!shared_dir_exists())
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  std::map<std::pair<std::size_t, std::size_t>, double> lengths[2];
  const ICM::Layout_method methods[2] = {ICM::Layout_method::Propagation, ICM::Layout_method::Harmonic};
  const char* names[2] = {"propagation", "harmonic"};
  for(int m = 0; m < 2; ++m)
  {
    Surface_mesh mesh;
    read_mesh(shared_path("three_peaks.off"), mesh);
    auto uv = nan_uv_map(mesh);
    ICM::Parameterization_options options;
    options.layout = methods[m];
    const Outcome run = run_cgal(mesh, uv, options);
    expect_good_run(run, mesh, uv, std::string("three_peaks ") + names[m]);
    EXPECT_EQ(run.report.layout, names[m]);
    lengths[m] = uv_edge_lengths(mesh, uv);
  }
  EXPECT_LT(max_relative_difference(lengths[0], lengths[1]), 1e-8);
}

// =============================================================================================
// 5. Nearly closed surfaces: a closed mesh with the star of one vertex removed

struct Nearly_closed
{
  const char* name;
  bool shared;
  double min_area_ratio_span; // area_ratio_max / area_ratio_min must exceed this
};

void PrintTo(const Nearly_closed& c, std::ostream* os)
{
  *os << c.name;
}

class NearlyClosed : public testing::TestWithParam<Nearly_closed>
{};

TEST_P(NearlyClosed, Parameterizes)
{
  const Nearly_closed c = GetParam();
  if(c.shared && !shared_dir_exists())
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  Surface_mesh mesh;
  read_mesh(c.shared ? shared_path(c.name) : data_path(c.name), mesh);
  ASSERT_EQ(topology(mesh), std::make_pair(0, 2)) << c.name << " should be a closed sphere";
  const std::size_t vertices_before = num_vertices(mesh), faces_before = num_faces(mesh);
  const SM_vertex v = *vertices(mesh).begin();
  const std::size_t degree = CGAL::halfedges_around_target(mesh.halfedge(v), mesh).size();
  punch_hole(mesh, v);
  ASSERT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  ASSERT_EQ(num_vertices(mesh), vertices_before - 1);
  ASSERT_EQ(num_faces(mesh), faces_before - degree);
  ASSERT_EQ(topology(mesh), std::make_pair(1, 1)) << "not a disk after removing one vertex star";

  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  RecordProperty("newton_iterations", run.report.newton_iterations);
  RecordProperty("metric", run.report.metric);
  // Far from the small hole the optimum has to move u by tens of units, and each Newton step
  // is capped (max_step): more iterations than on ordinary disks.
  // Protrusions (legs, horns) are compressed by factors below 1e-14 in area, so some UV
  // faces count as degenerate for measure_distortion; none is flipped. Edges there span a
  // few million representable steps of their coordinates: the layout reproduces the metric
  // to the library's default tolerance, not to the 1e-8 of ordinary disks.
  expect_good_run(run, mesh, uv, std::string(c.name) + " minus one vertex star", 12, true,
                  ICM::Parameterization_options().max_layout_length_error);
  if(HasFatalFailure())
    return;
  const ICM::Distortion_measures m = ICM::measure_distortion(mesh, uv);
  const double span = m.area_ratio_max / m.area_ratio_min;
  RecordProperty("area_ratio_span", std::to_string(span));
  RecordProperty("degenerate_uv_faces", std::to_string(m.degenerate_uv_faces));
  // The whole closed surface is squeezed inside its tiny hole's border: this area ratio span
  // is what makes linear methods such as LSCM collapse on these inputs.
  EXPECT_GT(span, c.min_area_ratio_span) << c.name;

  // The one call for any mesh sees the extreme free-boundary optimum and adds interior cones
  // (cut to the border): at least 10 times less log area distortion, still no flip.
  auto corner_uv = mesh.add_property_map<SM_halfedge, Point_2>("h:test_corner_uv").first;
  const ICM::Surface_parameterization_report with_cones = ICM::parameterize(mesh, corner_uv);
  ASSERT_EQ(with_cones.status, SMP::OK) << c.name << ": " << with_cones.message;
  ASSERT_EQ(with_cones.charts.size(), 1u);
  EXPECT_GT(with_cones.charts[0].cones.size(), 0u) << c.name;
  EXPECT_EQ(with_cones.charts[0].overlapping_border_edges, 0) << c.name;
  const ICM::Distortion_measures coned = ICM::measure_distortion_corner_uv(mesh, corner_uv);
  EXPECT_EQ(coned.flipped_faces, 0u) << c.name;
  RecordProperty("log_area_free_boundary", std::to_string(m.log_area_distortion));
  RecordProperty("log_area_with_cones", std::to_string(coned.log_area_distortion));
  EXPECT_LT(10 * coned.log_area_distortion, m.log_area_distortion) << c.name;
  std::cout << c.name << ": log area " << m.log_area_distortion << " free boundary, " << coned.log_area_distortion
            << " with " << with_cones.charts[0].cones.size() << " cones\n";
}

INSTANTIATE_TEST_SUITE_P(Meshes, NearlyClosed,
                         testing::Values(Nearly_closed{"sphere966.off", false, 1e5},
                                         Nearly_closed{"cow.off", true, 1e4}, Nearly_closed{"bull.off", true, 1e8},
                                         Nearly_closed{"camel.off", true, 1e8}, Nearly_closed{"bear.off", true, 1e4},
                                         Nearly_closed{"armadillo.off", true, 1e8},
                                         Nearly_closed{"bunny00.off", true, 1e4}),
                         [](const testing::TestParamInfo<Nearly_closed>& info) {
                           std::string name = info.param.name;
                           return name.substr(0, name.find('.'));
                         });

// =============================================================================================
// 6. Bad input: a clear error code and a human reason, never a crash

TEST(ParameterizerBadInput, EmptyMeshWithNullHalfedge)
{
  // An empty mesh is an empty mesh, whatever halfedge comes with it.
  Surface_mesh mesh;
  const Outcome run = run_direct(mesh, Surface_mesh::null_halfedge());
  EXPECT_EQ(run.status, SMP::ERROR_EMPTY_MESH);
  EXPECT_EQ(run.report.status, run.status);
  EXPECT_NE(run.report.message.find("no faces"), std::string::npos) << run.report.message;
  EXPECT_EQ(run.report.vertices, 0);
}

TEST(ParameterizerBadInput, NullHalfedgeOnAMeshWithFaces)
{
  // What longest_border() gives on a closed mesh: refused by name (CGAL's own wrapper would
  // crash on it before the parameterizer runs, which is why closed meshes go to
  // ICM::parameterize).
  Surface_mesh mesh;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("sphere966.off"), mesh));
  const Outcome run = run_direct(mesh, Surface_mesh::null_halfedge());
  EXPECT_EQ(run.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(run.report.message.find("no border halfedge"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, EdgeWithoutFaces)
{
  // The only way to pass a border halfedge of a mesh with no face: a lone edge.
  Surface_mesh mesh;
  const SM_vertex a = mesh.add_vertex(Point_3(0, 0, 0)), b = mesh.add_vertex(Point_3(1, 0, 0));
  const SM_halfedge h = mesh.add_edge(a, b);
  mesh.set_target(h, b);
  mesh.set_target(mesh.opposite(h), a);
  mesh.set_next(h, mesh.opposite(h));
  mesh.set_next(mesh.opposite(h), h);
  mesh.set_halfedge(a, mesh.opposite(h));
  mesh.set_halfedge(b, h);
  ASSERT_TRUE(is_border(h, mesh));
  const Outcome run = run_direct(mesh, h);
  EXPECT_EQ(run.status, SMP::ERROR_EMPTY_MESH);
  EXPECT_NE(run.report.message.find("no faces"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, QuadFace)
{
  Surface_mesh mesh;
  const SM_vertex v0 = mesh.add_vertex(Point_3(0, 0, 0)), v1 = mesh.add_vertex(Point_3(1, 0, 0)),
                  v2 = mesh.add_vertex(Point_3(1, 1, 0)), v3 = mesh.add_vertex(Point_3(0, 1, 0));
  const SM_face f = mesh.add_face(v0, v1, v2, v3);
  ASSERT_NE(f, Surface_mesh::null_face());
  const Outcome run = run_direct(mesh, mesh.opposite(mesh.halfedge(f)));
  EXPECT_EQ(run.status, SMP::ERROR_NON_TRIANGULAR_MESH);
  EXPECT_NE(run.report.message.find("more than 3 sides"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, AnnulusIsNotADisk)
{
  Surface_mesh mesh = ring_disk(
    4,
    [](int i, int k, int n, double& a) {
      a = 2 * CGAL_PI * k / n;
      return Point_3(i * std::cos(a), i * std::sin(a), 0);
    },
    1);
  ASSERT_EQ(topology(mesh), std::make_pair(2, 0));
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  EXPECT_EQ(run.status, SMP::ERROR_NO_TOPOLOGICAL_DISC);
  EXPECT_NE(run.report.message.find("2 boundary loops"), std::string::npos) << run.report.message;
  EXPECT_NE(run.report.message.find("not a disk"), std::string::npos) << run.report.message;
  EXPECT_EQ(run.report.boundary_loops, 2);
  for(SM_vertex v : vertices(mesh))
    EXPECT_TRUE(std::isnan(get(uv, v).x())) << "a failed run wrote UVs";
}

TEST(ParameterizerBadInput, ZeroAreaFace)
{
  // a, b, c collinear; face (a, c, b) has no area; faces (a, b, d), (b, c, d) are fine.
  Surface_mesh mesh;
  const SM_vertex a = mesh.add_vertex(Point_3(0, 0, 0)), b = mesh.add_vertex(Point_3(1, 0, 0)),
                  c = mesh.add_vertex(Point_3(2, 0, 0)), d = mesh.add_vertex(Point_3(1, 1, 0));
  ASSERT_NE(mesh.add_face(a, b, d), Surface_mesh::null_face());
  ASSERT_NE(mesh.add_face(b, c, d), Surface_mesh::null_face());
  ASSERT_NE(mesh.add_face(a, c, b), Surface_mesh::null_face());
  ASSERT_EQ(topology(mesh), std::make_pair(1, 1));
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  EXPECT_NE(run.status, SMP::OK);
  EXPECT_EQ(run.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(run.report.message.find("degenerate"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, NanCoordinate)
{
  Surface_mesh mesh = jittered_planar_disk(3, 1);
  mesh.point(*std::next(vertices(mesh).begin(), 5)) = Point_3(0.1, nan_value, 0);
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  EXPECT_EQ(run.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(run.report.message.find("non-finite"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, InfiniteCoordinate)
{
  Surface_mesh mesh = jittered_planar_disk(3, 1);
  mesh.point(*vertices(mesh).begin()) = Point_3(std::numeric_limits<double>::infinity(), 0, 0);
  auto uv = nan_uv_map(mesh);
  const Outcome run = run_cgal(mesh, uv);
  EXPECT_EQ(run.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(run.report.message.find("non-finite"), std::string::npos) << run.report.message;
}

TEST(ParameterizerBadInput, HalfedgeNotOnBorder)
{
  Surface_mesh mesh = jittered_planar_disk(3, 1);
  SM_halfedge interior = Surface_mesh::null_halfedge();
  for(SM_halfedge h : halfedges(mesh))
    if(!is_border(h, mesh) && !is_border(opposite(h, mesh), mesh))
      interior = h;
  ASSERT_NE(interior, Surface_mesh::null_halfedge());
  const Outcome run = run_direct(mesh, interior);
  EXPECT_EQ(run.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(run.report.message.find("not on a border"), std::string::npos) << run.report.message;

  // The face side of a border edge is not a border halfedge either.
  SM_halfedge face_side = Surface_mesh::null_halfedge();
  for(SM_halfedge h : halfedges(mesh))
    if(is_border(opposite(h, mesh), mesh))
      face_side = h;
  EXPECT_EQ(run_direct(mesh, face_side).status, SMP::ERROR_WRONG_PARAMETER);
}

} // namespace
