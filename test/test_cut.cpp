// Tests of ICM/Cut_graph.h: the seams chosen by `cut_graph` cut every surface into one disk
// through its cones, the user's seams are checked, and `cut_mesh` builds that disk with one
// vertex per wedge. Hand-built fixtures (octahedron, torus grid, torus with a hole) pin exact
// counts; the shared meshes cover genus 0 to 3 and up to 7 boundary loops.

#include <ICM/cut/Cut_graph.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ICM::internal::Mesh_index;

const double pi = std::acos(-1.0);

// --- meshes ----------------------------------------------------------------------------------

/// Indexes a shared mesh; false (and nothing asserted) when the file is absent, so the caller
/// can skip.
bool index_shared(const std::string& name, Mesh_index& index)
{
  const std::string path = icm_test::shared_path(name);
  if(!icm_test::fs::exists(path))
    return false;
  Mesh mesh;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(path, mesh)) << path;
  std::vector<Mesh::Vertex_index> vertices;
  const auto status =
    ICM::internal::index_mesh(mesh, *faces(mesh).begin(), get(CGAL::vertex_point, mesh), index, vertices);
  EXPECT_TRUE(status.ok()) << name << ": " << status.message;
  return status.ok();
}

#define ICM_INDEX_SHARED_OR_SKIP(name, index)                                                                          \
  if(!index_shared(name, index))                                                                                       \
  GTEST_SKIP() << icm_test::shared_path(name) << " is missing"

Mesh_index make_index(std::vector<std::array<double, 3>> points, std::vector<std::array<int, 3>> faces)
{
  Mesh_index index;
  index.points = std::move(points);
  index.faces = std::move(faces);
  const auto status = ICM::internal::build_connectivity(index);
  EXPECT_TRUE(status.ok()) << status.message;
  return index;
}

// Vertices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z (north), 5 -z (south); faces oriented outwards.
Mesh_index octahedron()
{
  return make_index({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                    {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {0, 5, 2}, {2, 5, 1}, {1, 5, 3}, {3, 5, 0}});
}

/// An n x m grid wrapped into a torus of radii 3 and 1; when `hole`, the two triangles of
/// square (0, 0) are left out, giving genus 1 with one boundary loop.
Mesh_index torus(int n, int m, bool hole = false)
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 3>> faces;
  const auto id = [n, m](int i, int j) { return (j % m) * n + (i % n); };
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < n; ++i)
    {
      const double phi = 2 * pi * i / n, theta = 2 * pi * j / m, rho = 3 + std::cos(theta);
      points.push_back({rho * std::cos(phi), rho * std::sin(phi), std::sin(theta)});
    }
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < n; ++i)
    {
      if(hole && i == 0 && j == 0)
        continue;
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return make_index(std::move(points), std::move(faces));
}

int edge_between(const Mesh_index& index, int a, int b)
{
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(index.edges[e] == std::array<int, 2>{std::min(a, b), std::max(a, b)})
      return e;
  ADD_FAILURE() << "no edge " << a << "-" << b;
  return -1;
}

std::vector<char> seams_along(const Mesh_index& index, const std::vector<int>& path)
{
  std::vector<char> is_seam(index.number_of_edges(), 0);
  for(std::size_t k = 0; k + 1 < path.size(); ++k)
    is_seam[edge_between(index, path[k], path[k + 1])] = 1;
  return is_seam;
}

std::vector<char> cones_at(const Mesh_index& index, const std::vector<int>& vertices)
{
  std::vector<char> is_cone(index.number_of_vertices(), 0);
  for(int v : vertices)
    is_cone[v] = 1;
  return is_cone;
}

/// `count` vertices spread over the surface: farthest point sampling in space from vertex 0.
std::vector<char> far_apart_cones(const Mesh_index& index, int count)
{
  std::vector<char> is_cone(index.number_of_vertices(), 0);
  std::vector<double> distance(index.number_of_vertices(), std::numeric_limits<double>::max());
  for(int k = 0, next = 0; k < count; ++k)
  {
    is_cone[next] = 1;
    int farthest = 0;
    for(int v = 0; v < index.number_of_vertices(); ++v)
    {
      distance[v] = std::min(distance[v], ICM::internal::squared_distance(index.points[v], index.points[next]));
      if(distance[v] > distance[farthest])
        farthest = v;
    }
    next = farthest;
  }
  return is_cone;
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

// --- the properties every cut must have ---------------------------------------------------

/// The cut graph K = seams + border: no seam on the border, every cone on K, no dangling
/// branch, and K connected with cycle rank 2g + b — exactly what makes the cut a disk
/// (chi(disk) = chi(M) - chi(K) = 1).
void expect_cut_graph(const Mesh_index& index, const std::vector<char>& is_seam, const std::vector<char>& is_cone)
{
  ASSERT_EQ(static_cast<int>(is_seam.size()), index.number_of_edges());
  const int nv = index.number_of_vertices();
  std::vector<int> degree(nv, 0);
  std::vector<char> on_k(nv, 0);
  ICM::internal::cutting::Union_find components(nv);
  int k_edges = 0;
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const bool border = index.edge_faces[e][1] < 0;
    if(is_seam[e])
    {
      EXPECT_FALSE(border) << "seam on border edge " << e;
      ++degree[index.edges[e][0]];
      ++degree[index.edges[e][1]];
    }
    if(is_seam[e] || border)
    {
      ++k_edges;
      on_k[index.edges[e][0]] = on_k[index.edges[e][1]] = 1;
      components.unite(index.edges[e][0], index.edges[e][1]);
    }
  }
  int k_vertices = 0, k_components = 0;
  for(int v = 0; v < nv; ++v)
  {
    const bool cone = !is_cone.empty() && is_cone[v];
    EXPECT_TRUE(on_k[v] || !cone) << "cone " << v << " is off the cut";
    EXPECT_TRUE(degree[v] != 1 || index.is_boundary_vertex[v] || cone) << "dangling seam end at vertex " << v;
    if(on_k[v])
    {
      ++k_vertices;
      if(components.find(v) == v)
        ++k_components;
    }
  }
  EXPECT_EQ(k_components, 1) << "the cut graph is not connected";
  EXPECT_EQ(k_edges - k_vertices + 1, 2 * index.genus() + index.number_of_boundary_loops())
    << "cycle rank of seams + border";
}

/// The cut mesh: a disk on the same faces and corners, one vertex per wedge, a seam edge as
/// two border edges of the disk with the surface edge's length, any other edge as one.
void expect_cut_mesh(const Mesh_index& index, const std::vector<char>& is_seam)
{
  const ICM::Cut_mesh cut = ICM::cut_mesh(index, is_seam);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  const Mesh_index& disk = cut.disk;
  EXPECT_TRUE(disk.is_disk()) << ICM::internal::describe_topology(disk);
  EXPECT_EQ(disk.euler_characteristic(), 1);
  ASSERT_EQ(disk.number_of_boundary_loops(), 1);
  ASSERT_EQ(disk.number_of_faces(), index.number_of_faces());
  ASSERT_EQ(static_cast<int>(cut.surface_vertex.size()), disk.number_of_vertices());
  ASSERT_EQ(static_cast<int>(cut.surface_edge.size()), disk.number_of_edges());
  ASSERT_EQ(static_cast<int>(cut.disk_edges.size()), index.number_of_edges());

  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(cut.surface_vertex[disk.faces[f][c]], index.faces[f][c]) << "face " << f << " corner " << c;
      EXPECT_EQ(cut.surface_edge[disk.face_edges[f][c]], index.face_edges[f][c]);
    }
  for(int w = 0; w < disk.number_of_vertices(); ++w)
    EXPECT_EQ(disk.points[w], index.points[cut.surface_vertex[w]]);
  for(int v = 0; v < index.number_of_vertices(); ++v)
    EXPECT_EQ(cut.surface_vertex[v], v) << "the first wedge of a vertex keeps its id";

  // Wedges per vertex: seam-degree d inside gives max(d, 1), on the border d + 1.
  std::vector<int> degree(index.number_of_vertices(), 0), wedges(index.number_of_vertices(), 0);
  int seams = 0, border_edges = 0;
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    if(is_seam[e])
    {
      ++seams;
      ++degree[index.edges[e][0]];
      ++degree[index.edges[e][1]];
    }
    if(index.edge_faces[e][1] < 0)
      ++border_edges;
  }
  for(int v : cut.surface_vertex)
    ++wedges[v];
  for(int v = 0; v < index.number_of_vertices(); ++v)
    EXPECT_EQ(wedges[v], index.is_boundary_vertex[v] ? degree[v] + 1 : std::max(degree[v], 1)) << "vertex " << v;

  // Edges: a seam edge becomes exactly two border edges of the disk, any other edge one.
  EXPECT_EQ(disk.number_of_edges(), index.number_of_edges() + seams);
  EXPECT_EQ(static_cast<int>(disk.boundary_loops[0].size()), 2 * seams + border_edges);
  std::vector<int> copies(index.number_of_edges(), 0);
  for(int d = 0; d < disk.number_of_edges(); ++d)
  {
    const int e = cut.surface_edge[d];
    ++copies[e];
    EXPECT_EQ(disk.edge_faces[d][1] < 0, is_seam[e] || index.edge_faces[e][1] < 0) << "disk edge " << d;
    const auto& a = disk.points[disk.edges[d][0]];
    const auto& b = disk.points[disk.edges[d][1]];
    EXPECT_EQ(ICM::internal::squared_distance(a, b),
              ICM::internal::squared_distance(index.points[index.edges[e][0]], index.points[index.edges[e][1]]));
  }
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    EXPECT_EQ(copies[e], is_seam[e] ? 2 : 1) << "surface edge " << e;
    const auto sides = cut.disk_edges[e];
    ASSERT_GE(sides[0], 0);
    EXPECT_EQ(cut.surface_edge[sides[0]], e);
    if(is_seam[e])
    {
      ASSERT_GE(sides[1], 0);
      EXPECT_NE(sides[0], sides[1]);
      EXPECT_EQ(cut.surface_edge[sides[1]], e);
      EXPECT_EQ(disk.edge_faces[sides[0]][0], index.edge_faces[e][0]);
      EXPECT_EQ(disk.edge_faces[sides[1]][0], index.edge_faces[e][1]);
    }
    else
      EXPECT_EQ(sides[1], -1);
  }
}

/// Runs `cut_graph` and checks the result end to end.
ICM::Cut_graph_result expect_disk_cut(const Mesh_index& index, const std::vector<char>& is_cone,
                                      const ICM::Cut_graph_options& options = ICM::Cut_graph_options())
{
  const ICM::Cut_graph_result result = ICM::cut_graph(index, is_cone, options);
  EXPECT_TRUE(result.ok()) << result.status.message;
  if(!result.ok())
    return result;
  EXPECT_EQ(result.number_of_generators, 2 * index.genus());
  EXPECT_EQ(static_cast<int>(std::count(result.is_seam.begin(), result.is_seam.end(), char(1))),
            result.number_of_seam_edges);
  expect_cut_graph(index, result.is_seam, is_cone);
  expect_cut_mesh(index, result.is_seam);
  // What the automatic cut chose passes the user-seam check unchanged.
  EXPECT_TRUE(ICM::cut_graph_from_seams(index, result.is_seam, is_cone).ok());
  return result;
}

/// Graph (edge path) distances from `source` to every vertex.
std::vector<double> graph_distances(const Mesh_index& index, int source)
{
  std::vector<double> distance;
  std::vector<int> parent_edge, label;
  ICM::internal::cutting::shortest_path_forest(ICM::internal::cutting::make_surface_graph(index),
                                               {static_cast<std::size_t>(source)}, distance, parent_edge, label);
  return distance;
}

// --- octahedron: exact cuts --------------------------------------------------------------

TEST(CutGraph, OctahedronOppositeConesAreJoinedByATwoEdgePath)
{
  const Mesh_index index = octahedron();
  const auto is_cone = cones_at(index, {4, 5});
  const auto result = expect_disk_cut(index, is_cone);
  EXPECT_EQ(result.number_of_terminals, 2);
  EXPECT_EQ(result.number_of_seam_edges, 2);
  EXPECT_EQ(result.number_of_generators, 0);
  EXPECT_NEAR(result.seam_length, 2 * std::sqrt(2.0), 1e-12);
  // The path runs north -> one equator vertex -> south.
  const auto degree = ICM::internal::seam_degrees(index, result.is_seam);
  EXPECT_EQ(degree[4], 1);
  EXPECT_EQ(degree[5], 1);
  EXPECT_EQ(degree[0] + degree[1] + degree[2] + degree[3], 2);
  EXPECT_EQ(ICM::cut_mesh(index, result.is_seam).disk.number_of_vertices(), 7);
}

TEST(CutGraph, OctahedronThreeAndSixConesGiveTrees)
{
  const Mesh_index index = octahedron();
  const auto three = expect_disk_cut(index, cones_at(index, {0, 2, 4}));
  EXPECT_EQ(three.number_of_seam_edges, 2);
  const auto six = expect_disk_cut(index, cones_at(index, {0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(six.number_of_seam_edges, 5); // a spanning tree
  EXPECT_NEAR(six.seam_length, 5 * std::sqrt(2.0), 1e-12);
}

TEST(CutGraph, AdjacentConesAreCutAlongTwoEdgesNotOne)
{
  // One seam edge would give a disk bordered by two edges between the same two vertices,
  // which a triangle mesh cannot hold: the cut detours through a third vertex.
  const Mesh_index index = octahedron();
  const auto is_cone = cones_at(index, {0, 4});
  const auto result = expect_disk_cut(index, is_cone);
  EXPECT_EQ(result.number_of_seam_edges, 2);
  EXPECT_FALSE(result.is_seam[edge_between(index, 0, 4)]);
}

TEST(CutGraph, ClosedGenusZeroNeedsTwoCones)
{
  const Mesh_index index = octahedron();
  for(const auto& cones : {std::vector<int>{}, std::vector<int>{4}})
  {
    const auto result = ICM::cut_graph(index, cones_at(index, cones));
    EXPECT_FALSE(result.ok());
    EXPECT_TRUE(contains(result.status.message, "needs at least 2 cones")) << result.status.message;
    EXPECT_TRUE(contains(result.status.message, "got " + std::to_string(cones.size()))) << result.status.message;
  }
  const auto no_flags = ICM::cut_graph(index, {});
  EXPECT_FALSE(no_flags.ok());
  EXPECT_TRUE(contains(no_flags.status.message, "got 0")) << no_flags.status.message;
}

TEST(CutGraph, ConeFlagsOfTheWrongSizeAreRefused)
{
  const Mesh_index index = octahedron();
  const auto result = ICM::cut_graph(index, std::vector<char>(5, 1));
  EXPECT_FALSE(result.ok());
  EXPECT_TRUE(contains(result.status.message, "5 entries")) << result.status.message;
}

TEST(CutGraph, PruningRemovesADanglingBranch)
{
  // Seams north -> +x -> south plus a slit +x -> +y: with cones at the poles the slit leads
  // nowhere and goes; the poles' ends stay.
  const Mesh_index index = octahedron();
  auto is_seam = seams_along(index, {4, 0, 5});
  is_seam[edge_between(index, 0, 2)] = 1;
  const auto graph = ICM::internal::cutting::make_surface_graph(index);
  EXPECT_EQ(ICM::internal::cutting::prune_dangling_seams(index, graph, cones_at(index, {4, 5}), is_seam), 1);
  EXPECT_EQ(is_seam, seams_along(index, {4, 0, 5}));
  // Without cones the whole path dangles.
  EXPECT_EQ(ICM::internal::cutting::prune_dangling_seams(index, graph, {}, is_seam), 2);
  EXPECT_EQ(std::count(is_seam.begin(), is_seam.end(), char(1)), 0);
}

// --- torus fixtures --------------------------------------------------------------------------

TEST(CutGraph, TorusGridNeedsTwoGeneratorsAndNoCone)
{
  const Mesh_index index = torus(8, 6);
  ASSERT_EQ(index.genus(), 1);
  const auto result = expect_disk_cut(index, {});
  EXPECT_EQ(result.number_of_generators, 2);
  EXPECT_EQ(result.number_of_terminals, 0);
  EXPECT_EQ(result.number_of_tree_edges, 0);
  // Unpruned, the generator loops are still a valid cut; pruning never adds an edge.
  ICM::Cut_graph_options unpruned;
  unpruned.prune = false;
  const auto raw = ICM::cut_graph(index, {}, unpruned);
  ASSERT_TRUE(raw.ok()) << raw.status.message;
  EXPECT_EQ(raw.number_of_pruned_edges, 0);
  EXPECT_EQ(raw.number_of_seam_edges, result.number_of_seam_edges + result.number_of_pruned_edges);
}

TEST(CutGraph, TorusGridWithConesJoinsThemToTheGenerators)
{
  const Mesh_index index = torus(10, 7);
  const auto is_cone = cones_at(index, {0, 25, 47});
  const auto result = expect_disk_cut(index, is_cone);
  EXPECT_EQ(result.number_of_generators, 2);
  EXPECT_EQ(result.number_of_terminals, 3);
  EXPECT_GE(result.number_of_tree_edges, 2);
}

TEST(CutGraph, TorusWithAHoleGetsGeneratorsFromItsBorder)
{
  const Mesh_index index = torus(8, 6, true);
  ASSERT_EQ(index.genus(), 1);
  ASSERT_EQ(index.number_of_boundary_loops(), 1);
  const auto result = expect_disk_cut(index, {});
  EXPECT_EQ(result.number_of_generators, 2);
  EXPECT_EQ(result.number_of_terminals, 1);
  // With one interior cone too.
  expect_disk_cut(index, cones_at(index, {27}));
}

// --- shared meshes -----------------------------------------------------------------------

TEST(CutGraph, Sphere966FourConesAreJoinedByAShortTree)
{
  Mesh_index index;
  ICM_INDEX_SHARED_OR_SKIP("sphere966.off", index);
  ASSERT_EQ(index.genus(), 0);
  ASSERT_EQ(index.number_of_boundary_loops(), 0);
  const auto is_cone = far_apart_cones(index, 4);
  const auto result = expect_disk_cut(index, is_cone);
  EXPECT_EQ(result.number_of_terminals, 4);
  EXPECT_EQ(result.number_of_tree_edges, result.number_of_seam_edges);

  // A tree: its ends are cones only (checked above) and it has one edge fewer than vertices.
  const auto degree = ICM::internal::seam_degrees(index, result.is_seam);
  EXPECT_EQ(result.number_of_seam_edges + 1,
            static_cast<int>(std::count_if(degree.begin(), degree.end(), [](int d) { return d > 0; })));

  // Its length lies between the farthest pair of cones and the minimum spanning tree of
  // the cones' pairwise shortest-path distances (Mehlhorn's bound).
  std::vector<int> cones;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(is_cone[v])
      cones.push_back(v);
  std::vector<std::vector<double>> pair(cones.size());
  double farthest = 0;
  for(std::size_t i = 0; i < cones.size(); ++i)
  {
    const auto distance = graph_distances(index, cones[i]);
    for(int w : cones)
    {
      pair[i].push_back(distance[w]);
      farthest = std::max(farthest, distance[w]);
    }
  }
  double mst = 0; // Prim on 4 points
  std::vector<char> in(cones.size(), 0);
  std::vector<double> best(cones.size(), std::numeric_limits<double>::max());
  best[0] = 0;
  for(std::size_t step = 0; step < cones.size(); ++step)
  {
    std::size_t next = 0;
    while(in[next])
      ++next;
    for(std::size_t i = 0; i < cones.size(); ++i)
      if(!in[i] && best[i] < best[next])
        next = i;
    in[next] = 1;
    mst += best[next];
    for(std::size_t i = 0; i < cones.size(); ++i)
      best[i] = std::min(best[i], pair[next][i]);
  }
  EXPECT_GE(result.seam_length, farthest - 1e-9);
  EXPECT_LE(result.seam_length, mst + 1e-9);
}

TEST(CutGraph, Sphere966WithoutConesIsRefused)
{
  Mesh_index index;
  ICM_INDEX_SHARED_OR_SKIP("sphere966.off", index);
  const auto result = ICM::cut_graph(index, std::vector<char>(index.number_of_vertices(), 0));
  EXPECT_FALSE(result.ok());
  EXPECT_TRUE(contains(result.status.message, "closed genus-0 surface needs at least 2 cones"))
    << result.status.message;
}

/// A shared mesh of known topology, cut without cones.
void expect_shared_disk_cut(const std::string& name, int genus, int loops)
{
  Mesh_index index;
  if(!index_shared(name, index))
    GTEST_SKIP() << icm_test::shared_path(name) << " is missing";
  ASSERT_EQ(index.genus(), genus) << name;
  ASSERT_EQ(index.number_of_boundary_loops(), loops) << name;
  const auto result = expect_disk_cut(index, {});
  EXPECT_EQ(result.number_of_generators, 2 * genus) << name;
  EXPECT_EQ(result.number_of_terminals, loops) << name;
  if(genus == 0)
  {
    EXPECT_EQ(result.number_of_tree_edges, result.number_of_seam_edges) << name;
  }
}

TEST(CutGraph, RotorTorusGetsTwoGenerators)
{
  expect_shared_disk_cut("rotor.off", 1, 0);
}
TEST(CutGraph, ElkTorusGetsTwoGenerators)
{
  expect_shared_disk_cut("elk.off", 1, 0);
}
TEST(CutGraph, KnottedTorusGetsTwoGenerators)
{
  expect_shared_disk_cut("knot1.off", 1, 0);
}
TEST(CutGraph, EightGenusTwoGetsFourGenerators)
{
  expect_shared_disk_cut("eight.off", 2, 0);
}
TEST(CutGraph, FemurGenusTwoGetsFourGenerators)
{
  expect_shared_disk_cut("femur.off", 2, 0);
}
TEST(CutGraph, ElephantGenusThreeGetsSixGenerators)
{
  expect_shared_disk_cut("elephant.off", 3, 0);
}
TEST(CutGraph, PigSevenBoundaryLoopsAreJoined)
{
  expect_shared_disk_cut("pig.off", 0, 7);
}
TEST(CutGraph, HeadThreeBoundaryLoopsAreJoined)
{
  expect_shared_disk_cut("head.off", 0, 3);
}
TEST(CutGraph, SharkFourBoundaryLoopsAreJoined)
{
  expect_shared_disk_cut("mech-holes-shark.off", 0, 4);
}

TEST(CutGraph, EightWithConesAddsATreeToTheGenerators)
{
  Mesh_index index;
  ICM_INDEX_SHARED_OR_SKIP("eight.off", index);
  const auto result = expect_disk_cut(index, far_apart_cones(index, 5));
  EXPECT_EQ(result.number_of_generators, 4);
  EXPECT_EQ(result.number_of_terminals, 5);
}

TEST(CutGraph, PigWithConesJoinsConesAndLoops)
{
  Mesh_index index;
  ICM_INDEX_SHARED_OR_SKIP("pig.off", index);
  auto is_cone = far_apart_cones(index, 6);
  const auto result = expect_disk_cut(index, is_cone);
  int interior = 0;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    interior += is_cone[v] && !index.is_boundary_vertex[v];
  EXPECT_EQ(result.number_of_terminals, 7 + interior);
}

// --- cones of angle above 2 pi --------------------------------------------------------------

/// The 3D angle of each wedge of surface vertex `v` in the cut: the corner angles at its
/// copies in the disk, summed per copy.
std::vector<double> wedge_angles(const Mesh_index& index, const std::vector<char>& is_seam, int v)
{
  const ICM::Cut_mesh cut = ICM::cut_mesh(index, is_seam);
  EXPECT_TRUE(cut.ok()) << cut.status.message;
  std::vector<double> angle(cut.disk.number_of_vertices(), 0.0);
  for(const auto& f : cut.disk.faces)
    for(int c = 0; c < 3; ++c)
      if(cut.surface_vertex[f[c]] == v)
      {
        const auto a = ICM::internal::difference(cut.disk.points[f[(c + 1) % 3]], cut.disk.points[f[c]]);
        const auto b = ICM::internal::difference(cut.disk.points[f[(c + 2) % 3]], cut.disk.points[f[c]]);
        angle[f[c]] += std::atan2(ICM::internal::cross_norm(a, b), ICM::internal::dot(a, b));
      }
  std::vector<double> wedges;
  for(int w = 0; w < cut.disk.number_of_vertices(); ++w)
    if(cut.surface_vertex[w] == v)
      wedges.push_back(angle[w]);
  return wedges;
}

/// A cone whose layout angle is expected above 2 pi gets seams through it until no wedge
/// scaled to that angle (angle / 3D angle sum) is wider than 0.9 of 2 pi; the cut stays one
/// disk. Two such cones on sphere966 (angles 3.5 pi and 5.2 pi, needing 2 and 3 seams) and
/// one on the genus-2 eight.
void expect_wedges_below_a_full_turn(const std::string& name, int cones, const std::vector<double>& wide_curvatures)
{
  Mesh_index index;
  ICM_INDEX_SHARED_OR_SKIP(name, index);
  const auto is_cone = far_apart_cones(index, cones);
  ICM::Cut_graph_options options;
  options.cone_curvatures.assign(index.number_of_vertices(), std::nan(""));
  std::vector<int> wide;
  for(int v = 0; v < index.number_of_vertices() && wide.size() < wide_curvatures.size(); ++v)
    if(is_cone[v])
    {
      options.cone_curvatures[v] = wide_curvatures[wide.size()];
      wide.push_back(v);
    }
  const auto plain = expect_disk_cut(index, is_cone);
  const auto result = expect_disk_cut(index, is_cone, options);
  EXPECT_EQ(result.wide_cones_left_wide, 0);
  EXPECT_GE(result.seam_length, plain.seam_length);
  for(int w : wide)
  {
    const std::vector<double> wedges = wedge_angles(index, result.is_seam, w);
    double total = 0;
    for(double a : wedges)
      total += a;
    const double angle = 2 * pi - options.cone_curvatures[w];
    EXPECT_GE(static_cast<int>(wedges.size()), static_cast<int>(std::ceil(angle / (2 * pi)))) << name << " cone " << w;
    for(double a : wedges)
      EXPECT_LE(a * angle / total, 0.9 * 2 * pi + 1e-9) << name << " cone " << w << ", " << wedges.size() << " wedges";
  }
  if(index.genus() == 0) // still a tree
  {
    const auto degree = ICM::internal::seam_degrees(index, result.is_seam);
    EXPECT_EQ(result.number_of_seam_edges + 1,
              static_cast<int>(std::count_if(degree.begin(), degree.end(), [](int d) { return d > 0; })));
  }
}

TEST(CutGraph, ConesWiderThanAFullTurnGetSeamsThroughThem)
{
  expect_wedges_below_a_full_turn("sphere966.off", 6, {-1.5 * pi, -3.2 * pi});
  expect_wedges_below_a_full_turn("eight.off", 6, {-2.5 * pi});
}

TEST(CutGraph, SeamCountsForAConeAngle)
{
  using ICM::internal::cutting::least_seam_degree;
  EXPECT_EQ(least_seam_degree(std::nan("")), 1);
  EXPECT_EQ(least_seam_degree(1.0), 1);
  EXPECT_EQ(least_seam_degree(0.0), 1);
  EXPECT_EQ(least_seam_degree(-0.1), 2);      // just above 2 pi
  EXPECT_EQ(least_seam_degree(-2 * pi), 2);   // 4 pi: two wedges of 2 pi
  EXPECT_EQ(least_seam_degree(-2.1 * pi), 3); // above 4 pi
}

// --- user seams ------------------------------------------------------------------------

TEST(CutGraph, UserSeamsThatCutADiskAreTakenAsGiven)
{
  const Mesh_index index = octahedron();
  // North -> +x -> south with a slit +x -> +y that no cone needs: a disk, kept as is.
  auto is_seam = seams_along(index, {4, 0, 5});
  is_seam[edge_between(index, 0, 2)] = 1;
  const auto result = ICM::cut_graph_from_seams(index, is_seam, cones_at(index, {4, 5}));
  ASSERT_TRUE(result.ok()) << result.status.message;
  EXPECT_EQ(result.is_seam, is_seam);
  EXPECT_EQ(result.number_of_seam_edges, 3);
  expect_cut_mesh(index, is_seam);
}

TEST(CutGraph, UserSeamsAroundTheEquatorMakeTwoPieces)
{
  const Mesh_index index = octahedron();
  const auto result = ICM::cut_graph_from_seams(index, seams_along(index, {0, 2, 1, 3, 0}));
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.status.message, "the seams cut the surface into 2 pieces");
  EXPECT_FALSE(ICM::cut_mesh(index, seams_along(index, {0, 2, 1, 3, 0})).ok());
}

TEST(CutGraph, UserSeamsThatLeaveGenusOrLoopsAreRefused)
{
  // A torus cut along one meridian is a cylinder: two boundary loops.
  const Mesh_index closed = torus(8, 6);
  std::vector<int> meridian;
  for(int j = 0; j <= 6; ++j)
    meridian.push_back((j % 6) * 8);
  const auto cylinder = ICM::cut_graph_from_seams(closed, seams_along(closed, meridian));
  EXPECT_FALSE(cylinder.ok());
  EXPECT_TRUE(contains(cylinder.status.message, "leave 2 boundary loops")) << cylinder.status.message;

  // Meridian and longitude together through vertex 0: a disk.
  auto both = seams_along(closed, meridian);
  for(int i = 0; i < 8; ++i)
    both[edge_between(closed, i, (i + 1) % 8)] = 1;
  EXPECT_TRUE(ICM::cut_graph_from_seams(closed, both).ok());
  expect_cut_mesh(closed, both);

  // A torus with a hole and no seam keeps its handle.
  const Mesh_index holed = torus(8, 6, true);
  const auto handle = ICM::cut_graph_from_seams(holed, std::vector<char>(holed.number_of_edges(), 0));
  EXPECT_FALSE(handle.ok());
  EXPECT_TRUE(contains(handle.status.message, "leave genus 1")) << handle.status.message;

  // A closed surface without seams cuts nothing.
  const auto nothing = ICM::cut_graph_from_seams(closed, std::vector<char>(closed.number_of_edges(), 0));
  EXPECT_FALSE(nothing.ok());
  EXPECT_TRUE(contains(nothing.status.message, "no seams")) << nothing.status.message;
}

TEST(CutGraph, MalformedUserSeamsAreRefused)
{
  const Mesh_index holed = torus(8, 6, true);
  std::vector<char> border_seam(holed.number_of_edges(), 0);
  for(int e = 0; e < holed.number_of_edges(); ++e)
    if(holed.edge_faces[e][1] < 0)
    {
      border_seam[e] = 1;
      break;
    }
  const auto border = ICM::cut_graph_from_seams(holed, border_seam);
  EXPECT_FALSE(border.ok());
  EXPECT_TRUE(contains(border.status.message, "a seam edge is a border edge")) << border.status.message;

  const Mesh_index index = octahedron();
  const auto size = ICM::cut_graph_from_seams(index, std::vector<char>(3, 0));
  EXPECT_FALSE(size.ok());
  EXPECT_TRUE(contains(size.status.message, "3 entries")) << size.status.message;

  const auto lone = ICM::cut_graph_from_seams(index, seams_along(index, {0, 4}));
  EXPECT_FALSE(lone.ok());
  EXPECT_TRUE(contains(lone.status.message, "touches no other seam")) << lone.status.message;

  const auto cone_off = ICM::cut_graph_from_seams(index, seams_along(index, {4, 0, 5}), cones_at(index, {4, 2}));
  EXPECT_FALSE(cone_off.ok());
  EXPECT_EQ(cone_off.status.message, "cone vertex 2 is neither on a seam nor on the border");
}

// --- cut mesh ------------------------------------------------------------------------------

TEST(CutMesh, ADiskWithoutSeamsIsItself)
{
  const Mesh_index plane = make_index({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}},
                                      {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  const std::vector<char> no_seam(plane.number_of_edges(), 0);
  const ICM::Cut_mesh cut = ICM::cut_mesh(plane, no_seam);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  EXPECT_EQ(cut.disk.faces, plane.faces);
  EXPECT_EQ(cut.disk.edges, plane.edges);
  EXPECT_EQ(cut.disk.boundary_loops, plane.boundary_loops);
  expect_cut_mesh(plane, no_seam);
}

TEST(CutMesh, SlitThroughTheMiddleOfADiskIsRefusedButAPathToTheBorderIsNot)
{
  // Square fan around its centre 4: a seam from the border corner 0 to the centre is a slit
  // (still a disk; the centre gets one wedge, corner 0 two).
  const Mesh_index plane = make_index({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}},
                                      {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  const auto slit = seams_along(plane, {0, 4});
  const ICM::Cut_mesh cut = ICM::cut_mesh(plane, slit);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  EXPECT_EQ(cut.disk.number_of_vertices(), 6);
  expect_cut_mesh(plane, slit);
  // Border to border through the centre splits the square in two.
  const ICM::Cut_mesh halves = ICM::cut_mesh(plane, seams_along(plane, {0, 4, 2}));
  EXPECT_FALSE(halves.ok());
  EXPECT_EQ(halves.status.message, "the seams cut the surface into 2 pieces");
}

TEST(CutMesh, OctahedronCutHasTheWedgesOfItsSeams)
{
  const Mesh_index index = octahedron();
  const auto is_seam = seams_along(index, {4, 0, 5, 1}); // ends 4 and 1 interior, 0 and 5 inner
  const ICM::Cut_mesh cut = ICM::cut_mesh(index, is_seam);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  // Ends keep one wedge, the two inner path vertices get two: 6 + 2.
  EXPECT_EQ(cut.disk.number_of_vertices(), 8);
  EXPECT_EQ(cut.disk.number_of_edges(), index.number_of_edges() + 3);
  expect_cut_mesh(index, is_seam);
}

} // namespace
