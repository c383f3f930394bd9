// Tests of the output side: Uv_mesh extraction from Surface_mesh, Polyhedron_3 and Seam_mesh,
// the OBJ, PLY, glTF, SVG and PNG writers, the choice of format by extension, and the atomic file
// replacement they rely on.

#include <ICM/IO/read_polygon_soup.h>
#include <ICM/IO/read_seam_selection.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/IO/write_uv_mesh.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_ply.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/internal/Atomic_file.h>
#ifdef ICM_HAS_STB_IMAGE_WRITE
#include <ICM/IO/write_uv_png.h>
#include <stb_image.h> // reads the pictures back (libstb, which the PNG writer links)
#endif

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/Seam_mesh.h>

#include <boost/property_map/property_map.hpp>

#include <gtest/gtest.h>

#include "test_support.h"
#include "uv_output_readers.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#ifndef _WIN32
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Surface_mesh = CGAL::Surface_mesh<Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
namespace fs = std::filesystem;

using icm_test::read_text;
using icm_test::write_text;
using Temp_dir = icm_test::Scratch_directory;

std::size_t count_occurrences(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for(std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + what.size()))
    ++n;
  return n;
}

// The 3x3 grid of vertices (i, j, 0), i, j in {0, 1, 2}, vertex j*3+i, 8 counterclockwise
// triangles. Works for any mutable FaceGraph. Returns the vertices in creation order.
template <class Mesh>
std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> build_grid(Mesh& mesh)
{
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  auto vpm = get(CGAL::vertex_point, mesh);
  std::vector<vertex_descriptor> v;
  for(int j = 0; j < 3; ++j)
    for(int i = 0; i < 3; ++i)
    {
      v.push_back(add_vertex(mesh));
      put(vpm, v.back(), Point_3(i, j, 0));
    }
  for(int j = 0; j < 2; ++j)
    for(int i = 0; i < 2; ++i)
    {
      const int a = j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
      const std::vector<vertex_descriptor> t1{v[a], v[b], v[c]}, t2{v[a], v[c], v[d]};
      EXPECT_NE(CGAL::Euler::add_face(t1, mesh), boost::graph_traits<Mesh>::null_face());
      EXPECT_NE(CGAL::Euler::add_face(t2, mesh), boost::graph_traits<Mesh>::null_face());
    }
  return v;
}

// A UV map with uv = (x, y) of the vertex, for any FaceGraph.
template <class Mesh>
std::unordered_map<typename boost::graph_traits<Mesh>::vertex_descriptor, Point_2> xy_uvs(const Mesh& mesh)
{
  std::unordered_map<typename boost::graph_traits<Mesh>::vertex_descriptor, Point_2> uv;
  for(auto v : vertices(mesh))
  {
    const Point_3& p = get(CGAL::vertex_point, mesh, v);
    uv[v] = Point_2(p.x(), p.y());
  }
  return uv;
}

// Checks that every corner's position and uv are consistent with uv = xy.
void expect_uv_is_xy(const ICM::IO::Uv_mesh& m)
{
  for(std::size_t f = 0; f < m.number_of_faces(); ++f)
    for(int k = 0; k < 3; ++k)
    {
      const auto& p = m.positions.at(m.face_positions[f][k]);
      const auto& t = m.uvs.at(m.face_uvs[f][k]);
      EXPECT_EQ(p[0], t[0]);
      EXPECT_EQ(p[1], t[1]);
      EXPECT_EQ(p[2], 0.);
    }
}

// Each face's corners, as a set of (x, y) integer positions, for order-independent comparison.
std::multiset<std::vector<std::pair<int, int>>> face_corner_sets(const ICM::IO::Uv_mesh& m)
{
  std::multiset<std::vector<std::pair<int, int>>> out;
  for(const auto& f : m.face_positions)
  {
    std::vector<std::pair<int, int>> c;
    for(int k = 0; k < 3; ++k)
      c.emplace_back(static_cast<int>(m.positions[f[k]][0]), static_cast<int>(m.positions[f[k]][1]));
    // Rotate so the smallest corner comes first: keeps the orientation, drops the start.
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    out.insert(c);
  }
  return out;
}

// The expected faces of build_grid(), in the same normal form as face_corner_sets().
std::multiset<std::vector<std::pair<int, int>>> grid_corner_sets()
{
  std::multiset<std::vector<std::pair<int, int>>> out;
  for(int j = 0; j < 2; ++j)
    for(int i = 0; i < 2; ++i)
    {
      out.insert({{i, j}, {i + 1, j}, {i + 1, j + 1}});
      out.insert({{i, j}, {i + 1, j + 1}, {i, j + 1}});
    }
  return out;
}

// Seam mesh over the grid, as in CGAL's Surface_mesh_parameterization examples.
using SM_vertex_descriptor = boost::graph_traits<Surface_mesh>::vertex_descriptor;
using SM_edge_descriptor = boost::graph_traits<Surface_mesh>::edge_descriptor;
using SM_halfedge_descriptor = boost::graph_traits<Surface_mesh>::halfedge_descriptor;
using Seam_edge_pmap = Surface_mesh::Property_map<SM_edge_descriptor, bool>;
using Seam_vertex_pmap = Surface_mesh::Property_map<SM_vertex_descriptor, bool>;
using Seam_mesh = CGAL::Seam_mesh<Surface_mesh, Seam_edge_pmap, Seam_vertex_pmap>;
using Seam_vertex_descriptor = boost::graph_traits<Seam_mesh>::vertex_descriptor;

// The grid as a seam mesh cut along the given edges (pairs of grid vertex numbers), set up as
// in CGAL's Surface_mesh_parameterization examples. Not copyable: the seam mesh refers to sm.
struct Cut_grid
{
  explicit Cut_grid(std::initializer_list<std::pair<int, int>> seams)
    : v(build_grid(sm)), seam_edges(sm.add_property_map<SM_edge_descriptor, bool>("e:on_seam", false).first),
      seam_vertices(sm.add_property_map<SM_vertex_descriptor, bool>("v:on_seam", false).first),
      mesh(sm, seam_edges, seam_vertices)
  {
    for(const auto& e : seams)
      EXPECT_TRUE(mesh.add_seam(v[e.first], v[e.second]));
  }
  Cut_grid(const Cut_grid&) = delete;
  Cut_grid& operator=(const Cut_grid&) = delete;

  Surface_mesh sm;
  std::vector<SM_vertex_descriptor> v;
  Seam_edge_pmap seam_edges;
  Seam_vertex_pmap seam_vertices;
  Seam_mesh mesh;
};

// UVs that pull the two sides of the vertical line x = 1 apart by 0.2, so that a seam
// vertex's copies have different UVs: a seam mesh vertex is on the left side when the faces
// around it are.
std::map<Seam_vertex_descriptor, Point_2> split_uvs(const Seam_mesh& mesh, const Surface_mesh& sm)
{
  std::map<Seam_vertex_descriptor, Point_2> uv;
  for(Seam_vertex_descriptor v : vertices(mesh))
  {
    const Point_3& p = sm.point(target(SM_halfedge_descriptor(halfedge(v, mesh)), sm));
    double cx = 0.;
    int n = 0;
    for(auto h : CGAL::halfedges_around_target(halfedge(v, mesh), mesh))
    {
      if(is_border(h, mesh))
        continue;
      for(auto g : CGAL::halfedges_around_face(h, mesh))
      {
        cx += sm.point(target(SM_halfedge_descriptor(g), sm)).x();
        ++n;
      }
    }
    const double shift = (cx / n < 1.) ? -0.1 : 0.1;
    uv[v] = Point_2(p.x() + shift, p.y());
  }
  return uv;
}

// How many different UV indices the faces use for each position.
std::vector<std::size_t> uvs_per_position(const ICM::IO::Uv_mesh& m)
{
  std::vector<std::set<int>> s(m.positions.size());
  for(std::size_t f = 0; f < m.number_of_faces(); ++f)
    for(int k = 0; k < 3; ++k)
      s.at(m.face_positions[f][k]).insert(m.face_uvs[f][k]);
  std::vector<std::size_t> n;
  for(const auto& x : s)
    n.push_back(x.size());
  return n;
}

// A Uv_mesh whose faces are n separate unit right triangles, each with its own 3 positions
// and 3 UVs, uv = xy: lets a test change the UV area of one face alone.
ICM::IO::Uv_mesh separate_triangles(int n)
{
  ICM::IO::Uv_mesh m;
  for(int f = 0; f < n; ++f)
  {
    const double x = 2. * f;
    const int b = static_cast<int>(m.positions.size());
    m.positions.push_back({{x, 0., 0.}});
    m.positions.push_back({{x + 1., 0., 0.}});
    m.positions.push_back({{x, 1., 0.}});
    for(int k = 0; k < 3; ++k)
      m.uvs.push_back({{m.positions[b + k][0], m.positions[b + k][1]}});
    m.face_positions.push_back({{b, b + 1, b + 2}});
    m.face_uvs.push_back({{b, b + 1, b + 2}});
  }
  return m;
}

ICM::IO::Uv_mesh grid_uv_mesh()
{
  Surface_mesh sm;
  build_grid(sm);
  auto uv = xy_uvs(sm);
  return ICM::IO::make_uv_mesh(sm, boost::make_assoc_property_map(uv));
}

// ------------------------------------------------------------------------------------------
// read_seam_selection

TEST(IoSeamSelection, EdgesOnTheThirdLineAndLaterOnesEachOnce)
{
  Surface_mesh sm;
  build_grid(sm); // vertex i at (i % 3, i / 3)
  Temp_dir dir("icm_seams");
  write_text(dir.file("a.selection.txt"), "4\n\n0 1 1 2\n2 1 4 1\r\n");
  std::vector<Surface_mesh::Edge_index> seams;
  std::string error;
  ASSERT_TRUE(ICM::IO::read_seam_selection(dir.file("a.selection.txt"), sm, seams, error)) << error;
  ASSERT_EQ(seams.size(), 3u);
  const std::pair<int, int> expected[] = {{0, 1}, {1, 2}, {1, 4}};
  for(int i = 0; i < 3; ++i)
  {
    const int a = static_cast<int>(source(seams[i], sm)), b = static_cast<int>(target(seams[i], sm));
    EXPECT_EQ(std::make_pair(std::min(a, b), std::max(a, b)), expected[i]);
  }
}

TEST(IoSeamSelection, EveryMalformedFileIsRefusedWithItsReason)
{
  Surface_mesh sm;
  build_grid(sm);
  Temp_dir dir("icm_seams");
  const std::pair<std::string, std::string> cases[] = {
    {"\n", "no third line"},
    {"\n\n0 x\n", "line 3, value 2: 'x' is not a vertex index"},
    {"\n\n0 1\n-1 0\n", "line 4, value 1: '-1' is not a vertex index"},
    {"\n\n0 1.5\n", "'1.5' is not a vertex index"},
    {"\n\n0 99\n", "vertex 99 out of range (the mesh has 9 vertices)"},
    {"\n\n0 99999999999999999999999\n", "is not a vertex index"},
    {"\n\n0 8\n", "vertices 0 and 8 are not joined by an edge"},
    {"\n\n0 1 2\n", "odd number"},
    {"\n\n\n", "names no edge"},
  };
  int n = 0;
  for(const auto& [text, reason] : cases)
  {
    const std::string path = dir.file("case" + std::to_string(n++) + ".selection.txt");
    write_text(path, text);
    std::vector<Surface_mesh::Edge_index> seams;
    std::string error;
    EXPECT_FALSE(ICM::IO::read_seam_selection(path, sm, seams, error)) << text;
    EXPECT_NE(error.find(reason), std::string::npos) << "got: " << error;
  }
  std::vector<Surface_mesh::Edge_index> seams;
  std::string error;
  EXPECT_FALSE(ICM::IO::read_seam_selection(dir.file("missing.selection.txt"), sm, seams, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
}

TEST(IoSeamSelection, FirstLineVerticesAreConesBesideTheEdges)
{
  // CGAL's orbifold examples give the cones as the first line, often the file's only one.
  Surface_mesh sm;
  build_grid(sm); // vertex 4 is the one interior vertex
  Temp_dir dir("icm_seams");
  std::vector<Surface_mesh::Vertex_index> cones;
  std::vector<Surface_mesh::Edge_index> seams;
  std::string error;
  write_text(dir.file("cones.selection.txt"), "4 4");
  ASSERT_TRUE(ICM::IO::read_selection(dir.file("cones.selection.txt"), sm, cones, seams, error)) << error;
  EXPECT_EQ(cones, (std::vector<Surface_mesh::Vertex_index>{Surface_mesh::Vertex_index(4)})) << "each once";
  EXPECT_TRUE(seams.empty());
  // Vertices and edges: both.
  write_text(dir.file("both.selection.txt"), "4\n\n0 1 1 4\n");
  ASSERT_TRUE(ICM::IO::read_selection(dir.file("both.selection.txt"), sm, cones, seams, error)) << error;
  EXPECT_EQ(cones, (std::vector<Surface_mesh::Vertex_index>{Surface_mesh::Vertex_index(4)}));
  EXPECT_EQ(seams.size(), 2u);
  // Edges only, as CGAL's Seam_mesh examples write them: no cone.
  write_text(dir.file("edges.selection.txt"), "\n\n1 4\n");
  ASSERT_TRUE(ICM::IO::read_selection(dir.file("edges.selection.txt"), sm, cones, seams, error)) << error;
  EXPECT_TRUE(cones.empty());
  EXPECT_EQ(seams.size(), 1u);
  // The seams-only reader keeps to the edges, as CGAL's Seam_mesh::add_seams does.
  ASSERT_TRUE(ICM::IO::read_seam_selection(dir.file("both.selection.txt"), sm, seams, error)) << error;
  EXPECT_EQ(seams.size(), 2u);
}

TEST(IoSeamSelection, EveryMalformedConeOrEdgeIsRefusedWithItsReason)
{
  Surface_mesh sm;
  build_grid(sm);
  Temp_dir dir("icm_seams");
  const std::pair<std::string, std::string> cases[] = {
    {"", "names no vertex (first line: cones) and no edge (third line on: seams)"},
    {"\n\n\n", "names no vertex (first line: cones) and no edge"},
    {"4 x\n", "line 1, value 2: 'x' is not a vertex index"},
    {"4 99\n", "line 1: vertex 99 out of range (the mesh has 9 vertices)"},
    {"0\n", "line 1: vertex 0 is on the border (a cone is an interior vertex)"},
    {"4\n\n0 99\n", "line 3: vertex 99 out of range"},
    {"4\n\n0 8\n", "line 3: vertices 0 and 8 are not joined by an edge"},
    {"4\n\n0 1 2\n", "odd number"},
  };
  int n = 0;
  for(const auto& [text, reason] : cases)
  {
    const std::string path = dir.file("case" + std::to_string(n++) + ".selection.txt");
    write_text(path, text);
    std::vector<Surface_mesh::Vertex_index> cones;
    std::vector<Surface_mesh::Edge_index> seams;
    std::string error;
    EXPECT_FALSE(ICM::IO::read_selection(path, sm, cones, seams, error)) << text;
    EXPECT_NE(error.find(reason), std::string::npos) << "got: " << error;
    EXPECT_NE(error.find(path), std::string::npos) << "the file is named: " << error;
  }
  // A vertex split at a non-manifold point has two copies: which would be the cone?
  const std::vector<std::vector<Surface_mesh::Vertex_index>> by_index = {
    {Surface_mesh::Vertex_index(0)}, {}, {Surface_mesh::Vertex_index(4), Surface_mesh::Vertex_index(5)}};
  write_text(dir.file("split.selection.txt"), "2\n");
  std::vector<Surface_mesh::Vertex_index> cones;
  std::vector<Surface_mesh::Edge_index> seams;
  std::string error;
  EXPECT_FALSE(ICM::IO::read_selection(dir.file("split.selection.txt"), sm, by_index, cones, seams, error));
  EXPECT_NE(error.find("line 1: vertex 2 is non-manifold and was split into 2 vertices"), std::string::npos) << error;
  write_text(dir.file("dropped.selection.txt"), "1\n");
  EXPECT_FALSE(ICM::IO::read_selection(dir.file("dropped.selection.txt"), sm, by_index, cones, seams, error));
  EXPECT_NE(error.find("line 1: vertex 1 is in no face of the mesh"), std::string::npos) << error;
}

// ------------------------------------------------------------------------------------------
// make_uv_mesh

TEST(IoUvMesh, SurfaceMeshFollowsVertexOrder)
{
  Surface_mesh sm;
  build_grid(sm);
  auto uv = xy_uvs(sm);
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(sm, boost::make_assoc_property_map(uv));

  ASSERT_EQ(m.positions.size(), 9u);
  ASSERT_EQ(m.uvs.size(), 9u);
  ASSERT_EQ(m.number_of_faces(), 8u);
  ASSERT_EQ(m.face_uvs.size(), 8u);
  std::string error;
  EXPECT_TRUE(ICM::IO::is_valid_uv_mesh(m, error)) << error;
  // Vertices were created in grid order, so position i is vertex i.
  for(int i = 0; i < 9; ++i)
  {
    EXPECT_EQ(m.positions[i][0], i % 3);
    EXPECT_EQ(m.positions[i][1], i / 3);
  }
  // One UV per vertex: both index arrays agree.
  EXPECT_EQ(m.face_positions, m.face_uvs);
  EXPECT_EQ(face_corner_sets(m), grid_corner_sets());
  expect_uv_is_xy(m);
}

TEST(IoUvMesh, SurfaceMeshWithRemovedVertexDoesNotUseRawIndices)
{
  Surface_mesh sm;
  // An isolated vertex created first and removed without collecting garbage: the grid's
  // vertices keep indices 1..9 while num_vertices() is 9.
  const SM_vertex_descriptor lonely = sm.add_vertex(Point_3(5, 5, 5));
  build_grid(sm);
  sm.remove_vertex(lonely);
  ASSERT_TRUE(sm.has_garbage());
  auto uv = xy_uvs(sm);
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(sm, boost::make_assoc_property_map(uv));
  ASSERT_EQ(m.positions.size(), 9u);
  std::string error;
  EXPECT_TRUE(ICM::IO::is_valid_uv_mesh(m, error)) << error;
  EXPECT_EQ(face_corner_sets(m), grid_corner_sets());
  expect_uv_is_xy(m);
}

TEST(IoUvMesh, Polyhedron)
{
  Polyhedron p;
  build_grid(p);
  auto uv = xy_uvs(p);
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(p, boost::make_assoc_property_map(uv));

  ASSERT_EQ(m.positions.size(), 9u);
  ASSERT_EQ(m.uvs.size(), 9u);
  ASSERT_EQ(m.number_of_faces(), 8u);
  std::string error;
  EXPECT_TRUE(ICM::IO::is_valid_uv_mesh(m, error)) << error;
  EXPECT_EQ(m.face_positions, m.face_uvs);
  EXPECT_EQ(face_corner_sets(m), grid_corner_sets());
  expect_uv_is_xy(m);
  // Every position is used.
  std::set<int> used;
  for(const auto& f : m.face_positions)
    used.insert(f.begin(), f.end());
  EXPECT_EQ(used.size(), 9u);
}

TEST(IoUvMesh, SeamMeshSplitsSeamVertices)
{
  // Cut along x = 1 from the bottom border to the top border: the mesh falls in two halves.
  Cut_grid grid({{1, 4}, {4, 7}});
  const Seam_mesh& mesh = grid.mesh;
  Surface_mesh& sm = grid.sm;
  ASSERT_EQ(num_vertices(mesh), 12u);

  const auto uv = split_uvs(mesh, sm);
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(mesh, boost::make_assoc_property_map(uv));

  ASSERT_EQ(m.positions.size(), 9u); // one per real vertex
  ASSERT_EQ(m.uvs.size(), 12u);      // one per seam mesh vertex
  ASSERT_EQ(m.number_of_faces(), 8u);
  std::string error;
  EXPECT_TRUE(ICM::IO::is_valid_uv_mesh(m, error)) << error;

  // Positions and their face indices are those of the underlying mesh.
  auto xy = xy_uvs(sm);
  const ICM::IO::Uv_mesh plain = ICM::IO::make_uv_mesh(sm, boost::make_assoc_property_map(xy));
  EXPECT_EQ(m.positions, plain.positions);
  EXPECT_EQ(m.face_positions, plain.face_positions);

  // The vertices on the cut (x = 1) have two UVs, the others one.
  const std::vector<std::size_t> n = uvs_per_position(m);
  for(int i = 0; i < 9; ++i)
    EXPECT_EQ(n[i], (i % 3 == 1) ? 2u : 1u) << "vertex " << i;

  // Every corner uses the copy on its face's side of the cut.
  for(std::size_t f = 0; f < m.number_of_faces(); ++f)
  {
    double cx = 0.;
    for(int k = 0; k < 3; ++k)
      cx += m.positions[m.face_positions[f][k]][0] / 3.;
    const double shift = cx < 1. ? -0.1 : 0.1;
    for(int k = 0; k < 3; ++k)
    {
      const auto& p = m.positions[m.face_positions[f][k]];
      const auto& t = m.uvs[m.face_uvs[f][k]];
      EXPECT_DOUBLE_EQ(t[0], p[0] + shift) << "face " << f << " corner " << k;
      EXPECT_DOUBLE_EQ(t[1], p[1]);
    }
  }

  // A UV map keyed by the underlying halfedges, as CGAL's parameterization examples use,
  // gives the same result.
  auto uv_pm = sm.add_property_map<SM_halfedge_descriptor, Point_2>("h:uv").first;
  for(const auto& e : uv)
    put(uv_pm, e.first, e.second);
  const ICM::IO::Uv_mesh m2 = ICM::IO::make_uv_mesh(mesh, uv_pm);
  EXPECT_EQ(m2.uvs, m.uvs);
  EXPECT_EQ(m2.face_uvs, m.face_uvs);
  EXPECT_EQ(m2.face_positions, m.face_positions);
}

TEST(IoUvMesh, SeamMeshSlitTipHasOneUv)
{
  // A slit from the border to the centre: the border end splits, the inner tip does not.
  Cut_grid grid({{1, 4}});
  const Seam_mesh& mesh = grid.mesh;
  std::map<Seam_vertex_descriptor, Point_2> uv;
  for(Seam_vertex_descriptor sv : vertices(mesh))
    uv[sv] = Point_2(0, 0);
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(mesh, boost::make_assoc_property_map(uv));
  EXPECT_EQ(m.positions.size(), 9u);
  EXPECT_EQ(m.uvs.size(), 10u);
  const std::vector<std::size_t> n = uvs_per_position(m);
  for(int i = 0; i < 9; ++i)
    EXPECT_EQ(n[i], i == 1 ? 2u : 1u) << "vertex " << i;
}

// ------------------------------------------------------------------------------------------
// write_uv_obj

struct Parsed_obj
{
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<double, 2>> vt;
  std::vector<std::array<int, 3>> fv, ft;
};

// A small parser for what write_uv_obj emits (CGAL's OBJ reader drops `vt`).
Parsed_obj parse_obj(const std::string& path)
{
  Parsed_obj obj;
  std::ifstream in(path);
  in.imbue(std::locale::classic());
  std::string line;
  while(std::getline(in, line))
  {
    std::istringstream s(line);
    s.imbue(std::locale::classic());
    std::string tag;
    s >> tag;
    if(tag == "v")
    {
      std::array<double, 3> p;
      s >> p[0] >> p[1] >> p[2];
      EXPECT_TRUE(static_cast<bool>(s)) << line;
      obj.v.push_back(p);
    }
    else if(tag == "vt")
    {
      std::array<double, 2> t;
      s >> t[0] >> t[1];
      EXPECT_TRUE(static_cast<bool>(s)) << line;
      obj.vt.push_back(t);
    }
    else if(tag == "f")
    {
      std::array<int, 3> a, b;
      for(int k = 0; k < 3; ++k)
      {
        char slash = 0;
        s >> a[k] >> slash >> b[k];
        EXPECT_EQ(slash, '/') << line;
        --a[k]; // back to 0-based
        --b[k];
      }
      EXPECT_TRUE(static_cast<bool>(s)) << line;
      std::string rest;
      EXPECT_FALSE(s >> rest) << "more than 3 corners: " << line;
      obj.fv.push_back(a);
      obj.ft.push_back(b);
    }
    else
    {
      EXPECT_TRUE(tag.empty() || tag[0] == '#') << "unexpected line: " << line;
    }
  }
  return obj;
}

void expect_close(double expected, double actual)
{
  EXPECT_LE(std::abs(expected - actual), 1e-15 * std::abs(expected)) << expected << " vs " << actual;
}

TEST(IoObj, RoundTripKeepsEveryDigitAndSeams)
{
  Cut_grid grid({{1, 4}, {4, 7}});
  auto uv = split_uvs(grid.mesh, grid.sm);
  ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(grid.mesh, boost::make_assoc_property_map(uv));

  // Numbers that a short format would round.
  const double awkward[] = {
    0.1, 1. / 3., -2.5e17, 1e-300, 3.141592653589793, -7.0000000000000009, 6.02214076e23, 4.9406564584124654e-314};
  int k = 0;
  for(auto& p : m.positions)
    for(double& x : p)
    {
      x = awkward[k % 8] * (1 + k);
      ++k;
    }
  for(auto& t : m.uvs)
    for(double& x : t)
    {
      x = -awkward[k % 8] / (1 + k);
      ++k;
    }

  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("grid.obj");
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_obj(path, m, error)) << error;
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(dir.number_of_entries(), 1u); // no temporary file left

  const Parsed_obj obj = parse_obj(path);
  ASSERT_EQ(obj.v.size(), m.positions.size());
  ASSERT_EQ(obj.vt.size(), m.uvs.size());
  ASSERT_EQ(obj.fv.size(), m.number_of_faces());
  for(std::size_t i = 0; i < obj.v.size(); ++i)
    for(int c = 0; c < 3; ++c)
      expect_close(m.positions[i][c], obj.v[i][c]);
  for(std::size_t i = 0; i < obj.vt.size(); ++i)
    for(int c = 0; c < 2; ++c)
      expect_close(m.uvs[i][c], obj.vt[i][c]);
  EXPECT_EQ(obj.fv, m.face_positions);
  EXPECT_EQ(obj.ft, m.face_uvs);
}

TEST(IoObj, StreamOverloadText)
{
  // The exact text for a tiny mesh: shortest form for short numbers, 1-based indices.
  ICM::IO::Uv_mesh m = separate_triangles(1);
  m.uvs[1] = {{0.5, 0.25}};
  std::ostringstream s;
  s.imbue(std::locale::classic());
  ASSERT_TRUE(ICM::IO::write_uv_obj(s, m));
  const std::string text = s.str();
  EXPECT_NE(text.find("\nv 1 0 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nvt 0.5 0.25\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nf 1/1 2/2 3/3\n"), std::string::npos) << text;
  EXPECT_EQ(s.precision(), 6); // the stream is left as it was
}

TEST(IoObj, MissingDirectoryFailsAndCreatesNothing)
{
  Temp_dir dir("icm_test_io");
  const fs::path missing = dir.path() / "no_such_dir";
  const std::string path = (missing / "out.obj").string();
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_obj(path, grid_uv_mesh(), error));
  EXPECT_NE(error.find("cannot write '" + path + "'"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_EQ(dir.number_of_entries(), 0u);
}

TEST(IoObj, InvalidMeshIsRefusedAndExistingFileKept)
{
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("keep.obj");
  write_text(path, "original\n");

  ICM::IO::Uv_mesh bad = grid_uv_mesh();
  bad.face_uvs[3][1] = 99;
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_obj(path, bad, error));
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;

  ICM::IO::Uv_mesh nan_uv = grid_uv_mesh();
  nan_uv.uvs[2][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ICM::IO::write_uv_obj(path, nan_uv, error));
  EXPECT_NE(error.find("cannot write '" + path + "': UV 2 is not finite"), std::string::npos) << error;
  EXPECT_EQ(error.find("extent"), std::string::npos) << error;

  // A layout scaled back to a mesh near the largest double overflows: the message says so.
  ICM::IO::Uv_mesh huge = grid_uv_mesh();
  for(auto& p : huge.positions)
    for(double& x : p)
      x *= 1.5e308 / 2;
  huge.uvs[2][1] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ICM::IO::write_uv_obj(path, huge, error));
  EXPECT_NE(error.find("UV 2 is not finite: the layout, scaled back to the mesh's extent (1.5e+308), is beyond the "
                       "range of a double (scale the mesh down)"),
            std::string::npos)
    << error;

  EXPECT_EQ(read_text(path), "original\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

// ------------------------------------------------------------------------------------------
// write_uv_ply, write_uv_gltf, write_uv_mesh and write_uv_files: the format by extension

// The cut grid of RoundTripKeepsEveryDigitAndSeams with coordinates that floats round, so
// that reading back checks the rounding to the nearest float and not only small integers.
ICM::IO::Uv_mesh seam_uv_mesh()
{
  Cut_grid grid({{1, 4}, {4, 7}});
  auto uv = split_uvs(grid.mesh, grid.sm);
  ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(grid.mesh, boost::make_assoc_property_map(uv));
  for(auto& p : m.positions)
    for(double& x : p)
      x = x / 3 + 1e-9;
  for(auto& t : m.uvs)
    for(double& x : t)
      x = -x / 7 + 0.1;
  return m;
}

TEST(IoPly, AsciiAndBinaryReadBackWithTheSameCorners)
{
  const ICM::IO::Uv_mesh m = seam_uv_mesh();
  ASSERT_GT(m.uvs.size(), m.positions.size()); // the seam splits UVs
  Temp_dir dir("icm_test_io");
  for(const bool binary : {false, true})
  {
    const std::string path = dir.file(binary ? "grid_binary.ply" : "grid_ascii.ply");
    ICM::IO::Mesh_writing_options options;
    options.binary_ply = binary;
    std::string error;
    ASSERT_TRUE(ICM::IO::write_uv_mesh(path, m, error, options)) << error;

    const icm_test::Corner_mesh ply = icm_test::read_ply_corners(path);
    EXPECT_EQ(ply.format, binary ? "format binary_little_endian 1.0" : "format ascii 1.0");
    // Vertices are the positions, shared across the seam: the faces index them as m does.
    ASSERT_EQ(ply.positions.size(), m.positions.size());
    EXPECT_EQ(ply.faces, m.face_positions);
    icm_test::expect_same_corners(m, ply);

    // ICM's own PLY reader (the input side) takes it too: same points, same faces.
    ICM::IO::Polygon_soup soup;
    ASSERT_TRUE(ICM::IO::read_polygon_soup(path, soup, error)) << error;
    ASSERT_EQ(soup.points.size(), m.positions.size());
    ASSERT_EQ(soup.polygons.size(), m.number_of_faces());
    for(std::size_t i = 0; i < soup.points.size(); ++i)
      for(int c = 0; c < 3; ++c)
        EXPECT_EQ(static_cast<float>(soup.points[i][c]), static_cast<float>(m.positions[i][c]));
    for(std::size_t f = 0; f < soup.polygons.size(); ++f)
      for(int k = 0; k < 3; ++k)
        EXPECT_EQ(soup.polygons[f].at(k), static_cast<std::size_t>(m.face_positions[f][k]));
  }
  EXPECT_EQ(dir.number_of_entries(), 2u); // no temporary left
}

TEST(IoPly, HeaderNamesTheTexcoordListAsMeshLabWritesIt)
{
  const ICM::IO::Uv_mesh m = separate_triangles(2);
  std::ostringstream s;
  s.imbue(std::locale::classic());
  ASSERT_TRUE(ICM::IO::write_uv_ply(s, m));
  EXPECT_EQ(s.str(), "ply\nformat ascii 1.0\ncomment written by ICM\nelement vertex 6\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                     "property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 0\n2 1 0\n"
                     "3 0 1 2 6 0 0 1 0 0 1\n3 3 4 5 6 2 0 3 0 2 1\n");
  std::ostringstream b;
  ASSERT_TRUE(ICM::IO::write_uv_ply(b, m, true));
  const std::string header_end = "end_header\n";
  const std::size_t body = b.str().find(header_end) + header_end.size();
  // 6 vertices of 3 floats, 2 faces of a count, 3 ints, a count and 6 floats.
  EXPECT_EQ(b.str().size() - body, 6u * 12 + 2u * (1 + 12 + 1 + 24));
}

#ifdef ICM_HAS_TINYGLTF
TEST(IoGltf, GltfAndGlbReadBackByTinygltfWithTheSameCorners)
{
  const ICM::IO::Uv_mesh m = seam_uv_mesh();
  Temp_dir dir("icm_test_io");
  for(const bool binary : {false, true})
  {
    const std::string path = dir.file(binary ? "grid.glb" : "grid.gltf");
    std::string error;
    ASSERT_TRUE(ICM::IO::write_uv_mesh(path, m, error)) << error;
    const std::string text = read_text(path);
    EXPECT_EQ(text.rfind(binary ? "glTF" : "{", 0), 0u) << "not a " << (binary ? "GLB" : "glTF JSON") << " file";

    const icm_test::Corner_mesh gltf = icm_test::read_gltf_corners(path, binary);
    icm_test::expect_same_corners(m, gltf);
    // One glTF vertex per (position, UV) pair: each seam vertex once per side, so here
    // (every UV belongs to one position) exactly one per UV.
    EXPECT_EQ(gltf.positions.size(), m.uvs.size());
    std::set<std::array<int, 2>> pairs;
    for(std::size_t f = 0; f < m.number_of_faces(); ++f)
      for(int k = 0; k < 3; ++k)
        pairs.insert({{m.face_positions[f][k], m.face_uvs[f][k]}});
    EXPECT_EQ(gltf.positions.size(), pairs.size());
  }
  EXPECT_EQ(dir.number_of_entries(), 2u);
}

TEST(IoGltf, MeshWithoutFacesIsRefused)
{
  Temp_dir dir("icm_test_io");
  ICM::IO::Uv_mesh empty;
  empty.positions.push_back({{0., 0., 0.}});
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_mesh(dir.file("empty.glb"), empty, error));
  EXPECT_NE(error.find("no faces"), std::string::npos) << error;
  EXPECT_EQ(dir.number_of_entries(), 0u);
}
#else
TEST(IoGltf, RefusedWithoutTinygltf)
{
  Temp_dir dir("icm_test_io");
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_mesh(dir.file("grid.gltf"), grid_uv_mesh(), error));
  EXPECT_NE(error.find("needs tinygltf"), std::string::npos) << error;
  EXPECT_EQ(dir.number_of_entries(), 0u);
}
#endif

TEST(IoUvMeshFormat, ByExtensionInAnyCase)
{
  using ICM::IO::Uv_mesh_format;
  EXPECT_EQ(ICM::IO::uv_mesh_format("a/b.obj"), Uv_mesh_format::Obj);
  EXPECT_EQ(ICM::IO::uv_mesh_format("b.PLY"), Uv_mesh_format::Ply);
  EXPECT_EQ(ICM::IO::uv_mesh_format("c.d.gltf"), Uv_mesh_format::Gltf);
  EXPECT_EQ(ICM::IO::uv_mesh_format("e.Glb"), Uv_mesh_format::Glb);
  EXPECT_FALSE(ICM::IO::uv_mesh_format("f.off"));
  EXPECT_FALSE(ICM::IO::uv_mesh_format("obj"));
  EXPECT_EQ(ICM::IO::why_uv_mesh_path_is_refused("x.obj"), "");
  EXPECT_EQ(ICM::IO::why_uv_mesh_path_is_refused("x.off"),
            "cannot write 'x.off': unknown extension '.off' (writes .obj, .ply, .gltf and .glb)");
  EXPECT_EQ(ICM::IO::why_uv_mesh_path_is_refused("dir.d/x"),
            "cannot write 'dir.d/x': no extension (writes .obj, .ply, .gltf and .glb)");
}

TEST(IoUvMeshFormat, UnknownExtensionWritesNothingAndKeepsTheFile)
{
  Temp_dir dir("icm_test_io");
  const std::string off = dir.file("mesh.off");
  write_text(off, "previous\n");
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_mesh(off, grid_uv_mesh(), error));
  EXPECT_NE(error.find("unknown extension '.off'"), std::string::npos) << error;
  // Not even the SVG of a pair: the refusal comes before anything is written.
  EXPECT_FALSE(ICM::IO::write_uv_files(off, dir.file("layout.svg"), grid_uv_mesh(), error));
  EXPECT_NE(error.find("unknown extension '.off'"), std::string::npos) << error;
  EXPECT_EQ(read_text(off), "previous\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

TEST(IoUvMeshFormat, CoordinatesBeyondAFloatAreRefusedForPlyAndGltf)
{
  Temp_dir dir("icm_test_io");
  ICM::IO::Uv_mesh big = grid_uv_mesh();
  big.positions[4][2] = 1e39;
  std::string error;
  EXPECT_FALSE(ICM::IO::write_uv_mesh(dir.file("big.ply"), big, error));
  EXPECT_NE(error.find("position 4 has a coordinate (1e+39) beyond the range of the 32-bit floats PLY stores"),
            std::string::npos)
    << error;
  EXPECT_FALSE(ICM::IO::write_uv_ply(dir.file("big.ply"), big, error));
  EXPECT_NE(error.find("beyond the range"), std::string::npos) << error;
  big = grid_uv_mesh();
  big.uvs[2][0] = -1e300;
#ifdef ICM_HAS_TINYGLTF
  EXPECT_FALSE(ICM::IO::write_uv_mesh(dir.file("big.glb"), big, error));
  EXPECT_NE(error.find("UV 2 has a coordinate (-1e+300) beyond the range of the 32-bit floats glTF stores"),
            std::string::npos)
    << error;
#endif
  EXPECT_EQ(dir.number_of_entries(), 0u);
  // OBJ keeps doubles: the same mesh is written.
  EXPECT_TRUE(ICM::IO::write_uv_mesh(dir.file("big.obj"), big, error)) << error;
}

TEST(IoUvFiles, MeshOfAnyFormatAndSvgAllOrNothing)
{
  const ICM::IO::Uv_mesh m = seam_uv_mesh();
  Temp_dir dir("icm_test_io");
  const std::string ply = dir.file("pair.ply"), svg = dir.file("pair.svg");
  ICM::IO::Mesh_writing_options binary;
  binary.binary_ply = true;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_files(ply, svg, m, error, ICM::IO::Svg_options(), binary)) << error;
  icm_test::expect_same_corners(m, icm_test::read_ply_corners(ply));
  EXPECT_NE(read_text(svg).find("<svg"), std::string::npos);

  // A failing SVG: the new mesh is not written either.
  const std::string glb = dir.file("new.glb");
  EXPECT_FALSE(ICM::IO::write_uv_files(glb, (dir.path() / "nope" / "x.svg").string(), m, error));
  EXPECT_NE(error.find("x.svg"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(glb));
  EXPECT_EQ(dir.number_of_entries(), 2u);
}

#ifdef ICM_HAS_STB_IMAGE_WRITE
// ------------------------------------------------------------------------------------------
// write_uv_png, write_uv_preview_png

/// A PNG read back: its size and RGB pixels.
struct Png_picture
{
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  std::array<int, 3> at(int x, int y) const
  {
    const std::size_t i = 3 * (std::size_t(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

Png_picture read_png(const std::string& path)
{
  const std::string bytes = read_text(path);
  Png_picture picture;
  int channels = 0;
  unsigned char* pixels =
    stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()),
                          &picture.width, &picture.height, &channels, 3);
  if(pixels == nullptr)
    throw std::runtime_error("not a PNG: " + path);
  picture.rgb.assign(pixels, pixels + 3 * std::size_t(picture.width) * picture.height);
  stbi_image_free(pixels);
  return picture;
}

TEST(IoPng, LayoutFacesTakeTheColourOfTheirAreaRatioAndFlippedOnesAreBlack)
{
  // Four unit right triangles side by side (UV = xy): face 1's UV triangle enlarged 4x in area,
  // face 2's shrunk 4x, face 3's mirrored (clockwise: flipped).
  ICM::IO::Uv_mesh m = separate_triangles(4);
  const auto scale_face = [&m](int f, double s) {
    for(int k = 1; k < 3; ++k)
      for(int c = 0; c < 2; ++c)
        m.uvs[3 * f + k][c] = m.uvs[3 * f][c] + s * (m.uvs[3 * f + k][c] - m.uvs[3 * f][c]);
  };
  scale_face(1, 2.);
  scale_face(2, 0.5);
  std::swap(m.uvs[10], m.uvs[11]);
  Temp_dir dir("icm_test_io");
  ICM::IO::Png_options opt;
  opt.size = 400;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_png(dir.file("layout.png"), m, error, opt)) << error;
  const Png_picture png = read_png(dir.file("layout.png"));
  ASSERT_EQ(png.width, 400);
  EXPECT_EQ(png.height, 400 + 64); // the colour bar's band

  // Where each face's centroid lands: the same fit as the SVG's.
  const ICM::IO::Uv_mesh unit = ICM::internal::at_unit_size(m);
  const ICM::internal::Layout_fit fit = ICM::internal::fit_layout(m, unit, 0., 0., opt.size, opt.margin);
  const auto centroid_pixel = [&](int f) {
    std::array<double, 2> c = {0., 0.};
    for(int k = 0; k < 3; ++k)
      for(int i = 0; i < 2; ++i)
        c[i] += m.uvs[m.face_uvs[f][k]][i] / 3;
    const std::array<double, 2> p = fit(c);
    return png.at(static_cast<int>(p[0]), static_cast<int>(p[1]));
  };
  const std::vector<double> ratios = ICM::IO::log_area_ratios(m);
  for(int f = 0; f < 3; ++f)
  {
    const std::array<int, 3> expected = ICM::internal::diverging_colour(ratios[f] / opt.log_ratio_range);
    const std::array<int, 3> seen = centroid_pixel(f);
    for(int k = 0; k < 3; ++k)
      EXPECT_NEAR(seen[k], expected[k], 2) << "face " << f << " channel " << k;
  }
  EXPECT_GT(centroid_pixel(1)[0], centroid_pixel(1)[2] + 60); // enlarged: red
  EXPECT_GT(centroid_pixel(2)[2], centroid_pixel(2)[0] + 60); // shrunk: blue
  EXPECT_EQ(centroid_pixel(3), (std::array<int, 3>{0, 0, 0}));
  const auto count_green = [](const Png_picture& picture) {
    std::size_t green = 0;
    for(int y = 0; y < picture.height; ++y)
      for(int x = 0; x < picture.width; ++x)
      {
        const std::array<int, 3> c = picture.at(x, y);
        green += c[1] > 200 && c[0] < 60 && c[2] < 60;
      }
    return green;
  };
  EXPECT_GT(count_green(png), 100u); // the flipped face's outline and the legend's key
  EXPECT_EQ(png.at(2, 2), (std::array<int, 3>{255, 255, 255}));

  // A layout mirrored as a whole is drawn mirrored back: nothing is flipped.
  ICM::IO::Uv_mesh mirrored = separate_triangles(4);
  for(auto& t : mirrored.uvs)
    t[0] = -t[0];
  ASSERT_TRUE(ICM::IO::write_uv_png(dir.file("mirrored.png"), mirrored, error, opt)) << error;
  EXPECT_EQ(count_green(read_png(dir.file("mirrored.png"))), 0u);
}

TEST(IoPng, PreviewOfAFlatSquareIsItsCheckerboard)
{
  // The unit square in the xy plane with UV = xy, seen head on (yaw 0, pitch 0: the camera on
  // +z, x right, y up): 4 x 4 checks, lit fully, so each check's centre has its exact colour
  // and the colours alternate.
  ICM::IO::Uv_mesh m;
  m.positions = {{{0., 0., 0.}}, {{1., 0., 0.}}, {{1., 1., 0.}}, {{0., 1., 0.}}};
  m.uvs = {{{0., 0.}}, {{1., 0.}}, {{1., 1.}}, {{0., 1.}}};
  m.face_positions = m.face_uvs = {{{0, 1, 2}}, {{0, 2, 3}}};
  ICM::IO::Preview_options opt;
  opt.size = 200;
  opt.checks = 4;
  opt.yaw = 0;
  opt.pitch = 0;
  Temp_dir dir("icm_test_io");
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_preview_png(dir.file("preview.png"), m, error, opt)) << error;
  const Png_picture png = read_png(dir.file("preview.png"));
  ASSERT_EQ(png.width, 200);
  ASSERT_EQ(png.height, 200);
  const double side = 0.92 * 200, low = 0.5 * (200 - side); // the square fills 92 % of the picture
  std::set<std::array<int, 3>> colours[2];
  for(int i = 0; i < 4; ++i)
    for(int j = 0; j < 4; ++j)
    {
      const int x = static_cast<int>(low + (i + 0.5) * side / 4), y = static_cast<int>(low + (3.5 - j) * side / 4);
      colours[(i + j) % 2].insert(png.at(x, y));
    }
  EXPECT_EQ(colours[0], (std::set<std::array<int, 3>>{{242, 242, 242}}));
  EXPECT_EQ(colours[1], (std::set<std::array<int, 3>>{{214, 96, 77}}));
  EXPECT_EQ(png.at(1, 1), (std::array<int, 3>{255, 255, 255})); // the background

  // Seen from behind, lit the same (both sides alike); the nearer of two overlapping squares hides
  // the farther one.
  ICM::IO::Uv_mesh two = m;
  for(const auto& p : m.positions)
    two.positions.push_back({p[0], p[1], -1.});
  for(const auto& t : m.uvs)
    two.uvs.push_back({t[0] + 0.25, t[1]}); // shifted by a check: the colours swap
  two.face_positions.push_back({{4, 5, 6}});
  two.face_positions.push_back({{4, 6, 7}});
  two.face_uvs.push_back({{4, 5, 6}});
  two.face_uvs.push_back({{4, 6, 7}});
  ASSERT_TRUE(ICM::IO::write_uv_preview_png(dir.file("two.png"), two, error, opt)) << error;
  const Png_picture front = read_png(dir.file("two.png"));
  const int cx = static_cast<int>(low + 0.5 * side / 4), cy = static_cast<int>(low + 3.5 * side / 4);
  EXPECT_EQ(front.at(cx, cy), png.at(cx, cy)); // the square at z = 0 is in front
  opt.yaw = 180;
  ASSERT_TRUE(ICM::IO::write_uv_preview_png(dir.file("back.png"), two, error, opt)) << error;
  const Png_picture back = read_png(dir.file("back.png"));
  EXPECT_NE(back.at(200 - 1 - cx, cy), png.at(cx, cy)); // from behind, the shifted square is in front
}

TEST(IoPng, BadOptionsAndMeshesAreRefusedByNameAndNothingIsWritten)
{
  Temp_dir dir("icm_test_io");
  const ICM::IO::Uv_mesh m = grid_uv_mesh();
  std::string error;
  ICM::IO::Png_options small;
  small.size = 8;
  EXPECT_FALSE(ICM::IO::write_uv_png(dir.file("a.png"), m, error, small));
  EXPECT_NE(error.find("picture size"), std::string::npos) << error;
  ICM::IO::Png_options range;
  range.log_ratio_range = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ICM::IO::write_uv_png(dir.file("a.png"), m, error, range));
  EXPECT_NE(error.find("log ratio range"), std::string::npos) << error;
  ICM::IO::Preview_options checks;
  checks.checks = 0;
  EXPECT_FALSE(ICM::IO::write_uv_preview_png(dir.file("a.png"), m, error, checks));
  EXPECT_NE(error.find("checkerboard"), std::string::npos) << error;
  ICM::IO::Preview_options pitch;
  pitch.pitch = 100;
  EXPECT_FALSE(ICM::IO::write_uv_preview_png(dir.file("a.png"), m, error, pitch));
  EXPECT_NE(error.find("pitch"), std::string::npos) << error;
  ICM::IO::Uv_mesh bad = m;
  bad.uvs[0][0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ICM::IO::write_uv_preview_png(dir.file("a.png"), bad, error));
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
  EXPECT_EQ(dir.number_of_entries(), 0u);
}

TEST(IoUvFiles, MeshAndEveryPictureAllOrNothing)
{
  const ICM::IO::Uv_mesh m = seam_uv_mesh();
  Temp_dir dir("icm_test_io");
  ICM::IO::Uv_pictures pictures;
  pictures.svg = dir.file("a.svg");
  pictures.png = dir.file("a.png");
  pictures.preview = dir.file("a_preview.png");
  pictures.png_options.size = pictures.preview_options.size = 64;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_files(dir.file("a.obj"), pictures, m, error)) << error;
  EXPECT_EQ(read_png(pictures.png).width, 64);
  EXPECT_EQ(read_png(pictures.preview).height, 64);
  EXPECT_EQ(dir.number_of_entries(), 4u);

  // A preview that cannot be written: neither the mesh nor the other pictures are.
  pictures.svg = dir.file("b.svg");
  pictures.png = dir.file("b.png");
  pictures.preview = (dir.path() / "nope" / "b_preview.png").string();
  EXPECT_FALSE(ICM::IO::write_uv_files(dir.file("b.obj"), pictures, m, error));
  EXPECT_NE(error.find("b_preview.png"), std::string::npos) << error;
  pictures.preview = dir.file("b_preview.png");
  pictures.preview_options.size = 1;
  EXPECT_FALSE(ICM::IO::write_uv_files(dir.file("b.obj"), pictures, m, error));
  EXPECT_NE(error.find("picture size"), std::string::npos) << error;
  EXPECT_EQ(dir.number_of_entries(), 4u);
}
#endif // ICM_HAS_STB_IMAGE_WRITE

// ------------------------------------------------------------------------------------------
// write_file_atomically

TEST(IoAtomicFile, FailingBodyKeepsOriginalAndLeavesNoTemporary)
{
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("data.txt");
  write_text(path, "precious content\n");

  std::string error;
  EXPECT_FALSE(ICM::internal::write_file_atomically(
    path,
    [](std::ostream& os) {
      os << "half written garbage";
      return false;
    },
    error));
  EXPECT_NE(error.find("cannot write '" + path + "'"), std::string::npos) << error;
  EXPECT_EQ(read_text(path), "precious content\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);

  error.clear();
  EXPECT_FALSE(ICM::internal::write_file_atomically(
    path,
    [](std::ostream& os) -> bool {
      os << "garbage";
      throw std::runtime_error("boom");
    },
    error));
  EXPECT_NE(error.find("boom"), std::string::npos) << error;
  EXPECT_EQ(read_text(path), "precious content\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);

  // A body that breaks its stream but claims success is caught by the stream check.
  error.clear();
  EXPECT_FALSE(ICM::internal::write_file_atomically(
    path,
    [](std::ostream& os) {
      os << "garbage";
      os.setstate(std::ios::badbit);
      return true;
    },
    error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(read_text(path), "precious content\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

TEST(IoAtomicFile, SuccessReplacesTheFile)
{
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("data.txt");
  write_text(path, "old\n");
  std::string error = "stale";
  EXPECT_TRUE(ICM::internal::write_file_atomically(
    path,
    [](std::ostream& os) {
      os << "new " << 1.5 << '\n';
      return true;
    },
    error));
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(read_text(path), "new 1.5\n");
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

TEST(IoAtomicFile, TargetIsADirectory)
{
  Temp_dir dir("icm_test_io");
  fs::create_directory(dir.path() / "sub");
  std::string error;
  EXPECT_FALSE(ICM::internal::write_file_atomically(
    dir.file("sub"), [](std::ostream& os) { return static_cast<bool>(os << "x"); }, error));
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(fs::is_directory(dir.path() / "sub"));
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

#ifndef _WIN32
/// Runs `child` in a forked process, which ends with exit code 0 if `child` returns, and
/// returns its wait status.
int wait_status_of_child(const std::function<void()>& child)
{
  const pid_t pid = ::fork();
  if(pid == 0)
  {
    child();
    ::_exit(0);
  }
  int status = 0;
  EXPECT_EQ(::waitpid(pid, &status, 0), pid);
  return status;
}

/// Writes `obj` and `svg` atomically, with signal `sig` raised in the middle of the second
/// content: both temporaries exist then. Exits 0 if the writing succeeded, 1 if it failed.
void write_interrupted_by(int sig, const std::string& obj, const std::string& svg)
{
  std::string error;
  const bool written =
    ICM::internal::write_files_atomically({{obj, [](std::ostream& os) { return static_cast<bool>(os << "v 0 0 0\n"); }},
                                           {svg,
                                            [sig](std::ostream& os) {
                                              os << "<svg>" << std::flush;
                                              ::raise(sig);
                                              return static_cast<bool>(os << "</svg>\n");
                                            }}},
                                          error);
  ::_exit(written ? 0 : 1);
}

void exit_42(int)
{
  ::_exit(42);
}

TEST(IoAtomicFile, SignalWhileWritingLeavesNoTemporaryAndKillsBySignal)
{
  for(int sig : {SIGTERM, SIGINT})
  {
    Temp_dir dir("icm_test_io");
    const std::string obj = dir.file("out.obj"), svg = dir.file("out.svg");
    write_text(obj, "previous\n");
    const int status = wait_status_of_child([&] { write_interrupted_by(sig, obj, svg); });
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "signal " << sig << ", wait status " << status;
    EXPECT_EQ(read_text(obj), "previous\n");
    EXPECT_EQ(dir.number_of_entries(), 1u) << "signal " << sig; // out.obj only: no temporary
  }
}

TEST(IoAtomicFile, SignalHandlerCallsThePreviousOneAndLeavesAnIgnoredSignalIgnored)
{
  Temp_dir dir("icm_test_io");
  const std::string obj = dir.file("out.obj"), svg = dir.file("out.svg");
  // A handler of the program's own, installed before the writing: called after the cleanup.
  int status = wait_status_of_child([&] {
    ::signal(SIGTERM, exit_42);
    write_interrupted_by(SIGTERM, obj, svg);
  });
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 42) << "wait status " << status;
  EXPECT_EQ(dir.number_of_entries(), 0u);
  // An ignored signal stays ignored: the files are written.
  status = wait_status_of_child([&] {
    ::signal(SIGTERM, SIG_IGN);
    write_interrupted_by(SIGTERM, obj, svg);
  });
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "wait status " << status;
  EXPECT_EQ(read_text(svg), "<svg></svg>\n");
  EXPECT_EQ(dir.number_of_entries(), 2u);
}
#endif

// ------------------------------------------------------------------------------------------
// log_area_ratios

TEST(IoLogAreaRatios, SimilarityGivesZero)
{
  Surface_mesh sm;
  build_grid(sm);
  // Distort the 3D positions so faces have different areas, and tilt them out of z = 0.
  auto vpm = get(CGAL::vertex_point, sm);
  for(auto v : vertices(sm))
  {
    const Point_3 p = get(vpm, v);
    put(vpm, v, Point_3(p.x() + 0.3 * p.y() * p.y(), p.y() + 0.1 * p.x(), 0.));
  }
  // UV = the distorted plane points scaled, rotated, translated and mirrored; 3D = the same
  // points tilted out of z = 0 by a rotation about the x axis (an isometry).
  const double c = std::cos(0.7), s = std::sin(0.7), scale = 123.456;
  std::unordered_map<SM_vertex_descriptor, Point_2> uv;
  for(auto v : vertices(sm))
  {
    const Point_3 p = get(vpm, v);
    uv[v] = Point_2(scale * (c * p.x() - s * p.y()) + 1e3, -scale * (s * p.x() + c * p.y()) - 7.);
    put(vpm, v, Point_3(p.x(), c * p.y(), s * p.y()));
  }
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(sm, boost::make_assoc_property_map(uv));
  const std::vector<double> r = ICM::IO::log_area_ratios(m);
  ASSERT_EQ(r.size(), 8u);
  for(double x : r)
    EXPECT_NEAR(x, 0., 1e-12);
}

TEST(IoLogAreaRatios, OneFaceDoubled)
{
  const int n = 5;
  ICM::IO::Uv_mesh m = separate_triangles(n);
  // Scale face 0's UVs by sqrt(2) about its first corner: its UV area doubles.
  for(int k = 1; k < 3; ++k)
  {
    auto& t = m.uvs[k];
    const auto& o = m.uvs[0];
    t = {{o[0] + std::sqrt(2.) * (t[0] - o[0]), o[1] + std::sqrt(2.) * (t[1] - o[1])}};
  }
  // Total UV area (n + 1) a is normalised to n a: face 0 has 2n/(n+1), the others n/(n+1).
  const std::vector<double> r = ICM::IO::log_area_ratios(m);
  ASSERT_EQ(r.size(), static_cast<std::size_t>(n));
  EXPECT_NEAR(r[0], std::log(2. * n / (n + 1.)), 1e-12);
  for(int f = 1; f < n; ++f)
    EXPECT_NEAR(r[f], std::log(n / (n + 1.)), 1e-12);
  // Scale invariance: the same layout 1000 times larger gives the same ratios.
  for(auto& t : m.uvs)
    t = {{1e3 * t[0], 1e3 * t[1]}};
  const std::vector<double> r2 = ICM::IO::log_area_ratios(m);
  for(int f = 0; f < n; ++f)
    EXPECT_NEAR(r2[f], r[f], 1e-12);
}

TEST(IoLogAreaRatios, DegenerateFacesAreClamped)
{
  ICM::IO::Uv_mesh m = separate_triangles(3);
  m.uvs[2] = m.uvs[1];             // face 0: zero UV area
  m.positions[5] = m.positions[4]; // face 1: zero 3D area
  const std::vector<double> r = ICM::IO::log_area_ratios(m);
  EXPECT_EQ(r[0], -ICM::IO::log_area_ratio_clamp);
  EXPECT_EQ(r[1], ICM::IO::log_area_ratio_clamp);
  EXPECT_TRUE(std::isfinite(r[2]));

  // A layout with no area at all: every face is shrunk to nothing.
  ICM::IO::Uv_mesh flat = separate_triangles(2);
  for(auto& t : flat.uvs)
    t = {{1., 2.}};
  for(double x : ICM::IO::log_area_ratios(flat))
    EXPECT_EQ(x, -ICM::IO::log_area_ratio_clamp);
}

// ------------------------------------------------------------------------------------------
// write_uv_svg

TEST(IoSvg, OnePolygonPerFaceAndEscapedTitle)
{
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("layout.svg");
  const ICM::IO::Uv_mesh m = grid_uv_mesh();
  ICM::IO::Svg_options opt;
  opt.title = "ICM <grid> & co";
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_svg(path, m, error, opt)) << error;
  const std::string svg = read_text(path);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(count_occurrences(svg, "<polygon"), m.number_of_faces());
  EXPECT_NE(svg.find("ICM &lt;grid&gt; &amp; co"), std::string::npos);
  EXPECT_EQ(count_occurrences(svg, "<linearGradient"), 1u); // the colour bar
  EXPECT_NE(svg.find(">-2<"), std::string::npos);           // its range
  EXPECT_NE(svg.find(">+2<"), std::string::npos);
  // An area preserving layout is white everywhere, and nothing is flipped.
  EXPECT_EQ(count_occurrences(svg, "fill=\"#ffffff\"/>"), m.number_of_faces());
  EXPECT_EQ(svg.find("#00ff00"), std::string::npos);
  EXPECT_EQ(dir.number_of_entries(), 1u);
}

TEST(IoSvg, CoordinatesFitTheSquareWithYUp)
{
  ICM::IO::Uv_mesh m = separate_triangles(1); // uv (0,0), (1,0), (0,1)
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("t.svg");
  ICM::IO::Svg_options opt;
  opt.size = 100.;
  opt.margin = 10.;
  opt.legend = false;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_svg(path, m, error, opt)) << error;
  // UV (0,0) is the bottom left corner of the 80 px square, (0,1) its top left.
  EXPECT_NE(read_text(path).find("points=\"10,90 90,90 10,10\""), std::string::npos) << read_text(path);
}

TEST(IoSvg, FlippedFacesAreHighlighted)
{
  ICM::IO::Uv_mesh m = separate_triangles(4);
  // Mirror face 2's UV triangle: it is now clockwise.
  for(int k = 0; k < 3; ++k)
    m.uvs[6 + k][1] = -m.uvs[6 + k][1];
  Temp_dir dir("icm_test_io");
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_svg(dir.file("a.svg"), m, error)) << error;
  std::string svg = read_text(dir.file("a.svg"));
  EXPECT_EQ(count_occurrences(svg, "<polygon"), 4u);
  EXPECT_EQ(count_occurrences(svg, "stroke=\"#00ff00\""), 2u); // the face group + legend swatch
  EXPECT_NE(svg.find("1 flipped face<"), std::string::npos);

  // Mirroring the whole layout flips nothing: it is mirrored back before drawing.
  ICM::IO::Uv_mesh mirrored = separate_triangles(4);
  for(auto& t : mirrored.uvs)
    t[0] = -t[0];
  ASSERT_TRUE(ICM::IO::write_uv_svg(dir.file("b.svg"), mirrored, error)) << error;
  svg = read_text(dir.file("b.svg"));
  EXPECT_EQ(count_occurrences(svg, "<polygon"), 4u);
  EXPECT_EQ(svg.find("#00ff00"), std::string::npos);
}

TEST(IoSvg, EdgesOmittedBeyondTheLimit)
{
  Temp_dir dir("icm_test_io");
  ICM::IO::Svg_options opt;
  opt.max_faces_with_edges = 4;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_svg(dir.file("e.svg"), grid_uv_mesh(), error, opt)) << error;
  const std::string svg = read_text(dir.file("e.svg"));
  EXPECT_EQ(count_occurrences(svg, "<polygon"), 8u);
  EXPECT_NE(svg.find("<g stroke=\"none\">"), std::string::npos);
}

TEST(IoSvg, PanelsSideBySideWithOneColourBar)
{
  ICM::IO::Uv_mesh doubled = separate_triangles(3);
  for(auto& t : doubled.uvs)
    t = {{2. * t[0], 2. * t[1]}};
  doubled.uvs[1][0] += 1.; // face 0 enlarged
  const std::vector<std::pair<std::string, ICM::IO::Uv_mesh>> panels = {
    {"ICM", grid_uv_mesh()}, {"LSCM", doubled}, {"ARAP", separate_triangles(2)}};
  Temp_dir dir("icm_test_io");
  const std::string path = dir.file("cmp.svg");
  ICM::IO::Svg_options opt;
  opt.title = "three_peaks";
  opt.log_ratio_range = 1.5;
  std::string error;
  ASSERT_TRUE(ICM::IO::write_uv_svg_panels(path, panels, error, opt)) << error;
  const std::string svg = read_text(path);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(count_occurrences(svg, "<polygon"), 8u + 3u + 2u);
  for(const char* t : {">ICM<", ">LSCM<", ">ARAP<", ">three_peaks<", ">-1.5<", ">+1.5<"})
    EXPECT_NE(svg.find(t), std::string::npos) << t;
  EXPECT_EQ(count_occurrences(svg, "<linearGradient"), 1u);
  EXPECT_NE(svg.find("viewBox=\"0 0 2400 "), std::string::npos);
  // The enlarged face is reddish, the others bluish: not everything is white any more.
  EXPECT_LT(count_occurrences(svg, "fill=\"#ffffff\"/>"), 13u);
}

TEST(IoSvg, FailuresLeaveNothing)
{
  Temp_dir dir("icm_test_io");
  std::string error;
  const std::string missing = (dir.path() / "nope" / "x.svg").string();
  EXPECT_FALSE(ICM::IO::write_uv_svg(missing, grid_uv_mesh(), error));
  EXPECT_NE(error.find("cannot write '" + missing + "'"), std::string::npos) << error;

  ICM::IO::Svg_options bad;
  bad.log_ratio_range = 0.;
  EXPECT_FALSE(ICM::IO::write_uv_svg(dir.file("x.svg"), grid_uv_mesh(), error, bad));
  EXPECT_FALSE(error.empty());

  ICM::IO::Uv_mesh invalid = grid_uv_mesh();
  invalid.face_positions.pop_back();
  EXPECT_FALSE(ICM::IO::write_uv_svg_panels(dir.file("x.svg"), {{"broken", invalid}}, error));
  EXPECT_NE(error.find("'broken'"), std::string::npos) << error;
  EXPECT_EQ(dir.number_of_entries(), 0u);
}

} // namespace
