// Step 6: cut a surface into one topological disk.
//
// Curvature and the metric live on the surface as given; the layout needs a disk. This header
// chooses the cut (the seam edges) and builds the cut surface as its own Mesh_index:
// - `cut_graph` joins the terminals (cone vertices and boundary loops) by a tree of short edge
//   paths, adds 2g homology generators by tree–cotree (Erickson & Whittlesey 2005) on a
//   surface of genus g, and prunes the branches that lead nowhere;
// - `cut_graph_from_seams` takes a user's seams as given and only checks them;
// - `check_cut_graph` is the check both use: the cut must leave one disk and touch every cone;
// - `cut_mesh` splits every vertex on the cut into its wedges (one copy per side) and indexes
//   the disk, keeping face ids and corner order, so corner (f, c) of the disk is corner (f, c)
//   of the surface.
// Everything works on the flat arrays of `internal::Mesh_index`; edge lengths are 3D
// Euclidean lengths. No exceptions: each result carries a status with the human reason.

#ifndef ICM_CUT_GRAPH_H
#define ICM_CUT_GRAPH_H

#include <ICM/Status.h>
#include <ICM/internal/Mesh_index.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/visitors.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace ICM {

struct Cut_graph_options
{
  /// Remove seam branches that end at a vertex which is neither a cone nor on the border:
  /// they cut nothing the disk needs and only lengthen its border.
  bool prune = true;
};

/// The seam edges of a cut and what went into them.
struct Cut_graph_result
{
  std::vector<char> is_seam;          ///< per surface edge; never a border edge
  int number_of_seam_edges = 0;
  int number_of_terminals = 0;        ///< interior cones + boundary loops
  int number_of_tree_edges = 0;       ///< edges of the tree joining the terminals
  int number_of_generators = 0;       ///< homology generators added, 2g on genus g
  int number_of_pruned_edges = 0;     ///< dangling seam edges removed
  double seam_length = 0;             ///< total 3D length of the seam edges
  Status status;
  bool ok() const { return status.ok(); }
};

/// The surface cut open along its seams, as a mesh of its own.
/// Faces are the surface's faces with the same ids and corner order; a disk vertex is a
/// wedge, one side of a surface vertex: the corner (f, c) lies on wedge `disk.faces[f][c]`.
/// A vertex off the cut keeps its id (wedges `0 .. n-1` are the surface vertices' first
/// wedges), the extra sides of vertices on the cut are numbered from n on.
struct Cut_mesh
{
  internal::Mesh_index disk;
  std::vector<int> surface_vertex;            ///< disk vertex (wedge) -> surface vertex
  std::vector<int> surface_edge;              ///< disk edge -> surface edge
  /// surface edge -> its disk edges: the side in `edge_faces[e][0]`, then the side in
  /// `edge_faces[e][1]` on a seam edge (-1 off the cut, where one disk edge serves both faces)
  std::vector<std::array<int, 2>> disk_edges;
  Status status;
  bool ok() const { return status.ok(); }
};

namespace internal {
/// The helpers of this header, in their own namespace: names such as `Union_find` are common
/// enough to meet another header's.
namespace cutting {

/// A cut that does not leave one disk, and why.
inline Status not_a_disk(std::string why)
{
  return Status::failure(CGAL::Surface_mesh_parameterization::ERROR_NO_TOPOLOGICAL_DISC, std::move(why));
}

/// Union–find by size with path halving, for pieces, wedges and terminal trees.
class Union_find
{
public:
  explicit Union_find(int n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }

  int find(int x)
  {
    while(parent_[x] != x)
    {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Joins the sets of `a` and `b`; false when they were already one.
  bool unite(int a, int b)
  {
    a = find(a);
    b = find(b);
    if(a == b)
      return false;
    if(size_[a] < size_[b])
      std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

private:
  std::vector<int> parent_;
  std::vector<int> size_;
};

/// An arc of the surface graph: the mesh edge it runs along and its 3D length.
struct Surface_arc
{
  int edge = -1;
  double length = 0;
};

/// The edge graph of the surface, both directions of every edge, in Boost.Graph's compressed
/// form: built once per cut, then shared by every shortest-path search.
using Surface_graph =
  boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, Surface_arc>;

inline Surface_graph make_surface_graph(const Mesh_index& index)
{
  std::vector<std::pair<std::size_t, std::size_t>> arcs;
  std::vector<Surface_arc> properties;
  arcs.reserve(2 * index.edges.size());
  properties.reserve(2 * index.edges.size());
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const std::size_t a = index.edges[e][0], b = index.edges[e][1];
    const Surface_arc arc{e, edge_length(index, e)};
    arcs.emplace_back(a, b);
    properties.push_back(arc);
    arcs.emplace_back(b, a);
    properties.push_back(arc);
  }
  return Surface_graph(boost::edges_are_unsorted_multi_pass, arcs.begin(), arcs.end(),
                       properties.begin(), static_cast<std::size_t>(index.number_of_vertices()));
}

/// Records, when Dijkstra relaxes an arc, the mesh edge to the parent and the label of the
/// source the vertex now hangs from. The last relaxation wins, and it is made from a settled
/// vertex, so both are final when the search ends.
struct Forest_recorder
{
  using event_filter = boost::on_edge_relaxed;
  std::vector<int>* parent_edge;
  std::vector<int>* label;

  template <class Arc, class Graph>
  void operator()(Arc arc, const Graph& graph) const
  {
    const auto from = source(arc, graph), to = target(arc, graph);
    (*parent_edge)[to] = graph[arc].edge;
    (*label)[to] = (*label)[from];
  }
};

/// Multi-source shortest-path forest: `distance` to the nearest source, `parent_edge` towards
/// it (-1 at the sources) and the source's `label` (preset at the sources, copied down).
inline void shortest_path_forest(const Surface_graph& graph, const std::vector<std::size_t>& sources,
                                 std::vector<double>& distance, std::vector<int>& parent_edge,
                                 std::vector<int>& label)
{
  const std::size_t n = num_vertices(graph);
  distance.assign(n, std::numeric_limits<double>::max());
  parent_edge.assign(n, -1);
  label.resize(n, -1);
  const auto vertex_index = get(boost::vertex_index, graph);
  boost::dijkstra_shortest_paths(
    graph, sources.begin(), sources.end(), boost::dummy_property_map(),
    boost::make_iterator_property_map(distance.begin(), vertex_index),
    get(&Surface_arc::length, graph), vertex_index, std::less<double>(),
    boost::closed_plus<double>(), std::numeric_limits<double>::max(), 0.0,
    boost::make_dijkstra_visitor(Forest_recorder{&parent_edge, &label}));
}

inline int opposite_end(const Mesh_index& index, int e, int v)
{
  return index.edges[e][0] == v ? index.edges[e][1] : index.edges[e][0];
}

inline bool is_surface_border_edge(const Mesh_index& index, int e) { return index.edge_faces[e][1] < 0; }

/// Marks the forest path from `v` up to its source. A marked parent edge means the rest of
/// the path was marked before, so each edge is walked once however many paths share it.
inline void mark_path_to_source(const Mesh_index& index, const std::vector<int>& parent_edge, int v,
                                std::vector<char>& is_seam)
{
  while(parent_edge[v] >= 0 && !is_seam[parent_edge[v]])
  {
    is_seam[parent_edge[v]] = 1;
    v = opposite_end(index, parent_edge[v], v);
  }
}

/// Joins the terminals (each boundary loop as one, each interior cone) by a tree of shortest
/// paths, Mehlhorn's Steiner tree approximation: one multi-source Dijkstra from every terminal
/// splits the surface into nearest-terminal regions; an edge between two regions is a path
/// terminal -> edge -> terminal; Kruskal keeps the shortest paths that join new terminals.
/// One search instead of one per terminal, and the same factor-2 bound as growing the tree
/// terminal by terminal. Paths never cross a border vertex (each is the source of its loop's
/// region), so no path closes a loop with a border. Returns the number of seam edges added.
inline int join_terminals(const Mesh_index& index, const Surface_graph& graph,
                          const std::vector<int>& interior_cones, std::vector<char>& is_seam)
{
  const int loops = index.number_of_boundary_loops();
  const int terminals = loops + static_cast<int>(interior_cones.size());
  if(terminals < 2)
    return 0;

  std::vector<int> label(index.number_of_vertices(), -1);
  std::vector<std::size_t> sources;
  for(int l = 0; l < loops; ++l)
    for(int v : index.boundary_loops[l])
    {
      label[v] = l;
      sources.push_back(static_cast<std::size_t>(v));
    }
  for(std::size_t k = 0; k < interior_cones.size(); ++k)
  {
    label[interior_cones[k]] = loops + static_cast<int>(k);
    sources.push_back(static_cast<std::size_t>(interior_cones[k]));
  }
  std::vector<double> distance;
  std::vector<int> parent_edge;
  shortest_path_forest(graph, sources, distance, parent_edge, label);

  std::vector<std::pair<double, int>> bridges;  // (terminal-to-terminal length, edge)
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    if(label[a] != label[b] && label[a] >= 0 && label[b] >= 0)  // -1: unreachable, a second component
      bridges.emplace_back(distance[a] + edge_length(index, e) + distance[b], e);
  }
  std::sort(bridges.begin(), bridges.end());

  Union_find joined(terminals);
  int joins = 0;
  for(const auto& bridge : bridges)
  {
    const int e = bridge.second, a = index.edges[e][0], b = index.edges[e][1];
    if(!joined.unite(label[a], label[b]))
      continue;
    is_seam[e] = 1;
    mark_path_to_source(index, parent_edge, a, is_seam);
    mark_path_to_source(index, parent_edge, b, is_seam);
    if(++joins == terminals - 1)
      break;
  }
  return static_cast<int>(std::count(is_seam.begin(), is_seam.end(), char(1)));
}

/// Tree–cotree (Erickson & Whittlesey 2005) on the surface already cut along `is_seam` and its
/// border (together the connected set K: the terminal tree, or one root vertex when there is
/// none). T is the shortest-path forest from all of K, so every generator loop is as short as
/// the tree allows and ends on K; C is a spanning tree of the faces across edges in neither T
/// nor K. Each remaining edge closes one generator: its endpoints' paths to K plus itself.
/// Counting, #remaining = 2 - chi - (cycles of K) = 2g. Returns the generators added, or -1
/// when the cotree misses a face (K or T would separate the surface).
inline int add_homology_generators(const Mesh_index& index, const Surface_graph& graph,
                                   const std::vector<int>& interior_cones, std::vector<char>& is_seam)
{
  const int nv = index.number_of_vertices(), ne = index.number_of_edges(), nf = index.number_of_faces();
  std::vector<char> on_cut(nv, 0);
  for(int v = 0; v < nv; ++v)
    on_cut[v] = index.is_boundary_vertex[v];
  for(int v : interior_cones)
    on_cut[v] = 1;
  for(int e = 0; e < ne; ++e)
    if(is_seam[e])
      on_cut[index.edges[e][0]] = on_cut[index.edges[e][1]] = 1;
  std::vector<std::size_t> sources;
  for(int v = 0; v < nv; ++v)
    if(on_cut[v])
      sources.push_back(static_cast<std::size_t>(v));
  if(sources.empty())
    sources.push_back(0);  // closed, no cone: any root will do

  std::vector<double> distance;
  std::vector<int> parent_edge, label;
  shortest_path_forest(graph, sources, distance, parent_edge, label);
  std::vector<char> in_tree(ne, 0);
  for(int v = 0; v < nv; ++v)
    if(parent_edge[v] >= 0)
      in_tree[parent_edge[v]] = 1;

  std::vector<char> in_cotree(ne, 0), reached(nf, 0);
  std::vector<int> stack{0};
  reached[0] = 1;
  int reached_faces = 1;
  while(!stack.empty())
  {
    const int f = stack.back();
    stack.pop_back();
    for(int e : index.face_edges[f])
    {
      if(in_tree[e] || is_seam[e] || is_surface_border_edge(index, e))
        continue;
      const int g = index.edge_faces[e][0] == f ? index.edge_faces[e][1] : index.edge_faces[e][0];
      if(reached[g])
        continue;
      reached[g] = 1;
      in_cotree[e] = 1;
      ++reached_faces;
      stack.push_back(g);
    }
  }
  if(reached_faces != nf)
    return -1;

  int generators = 0;
  for(int e = 0; e < ne; ++e)
  {
    if(in_tree[e] || in_cotree[e] || is_seam[e] || is_surface_border_edge(index, e))
      continue;
    ++generators;
    is_seam[e] = 1;
    mark_path_to_source(index, parent_edge, index.edges[e][0], is_seam);
    mark_path_to_source(index, parent_edge, index.edges[e][1], is_seam);
  }
  return generators;
}

/// Repeatedly removes the seam edge at a vertex of seam-degree 1 that is neither a cone nor
/// on the border. Returns the number of edges removed.
inline int prune_dangling_seams(const Mesh_index& index, const Surface_graph& graph,
                                const std::vector<char>& is_cone, std::vector<char>& is_seam)
{
  std::vector<int> degree = seam_degrees(index, is_seam);
  const auto dangling = [&](int v) {
    return degree[v] == 1 && !index.is_boundary_vertex[v] && !(!is_cone.empty() && is_cone[v]);
  };
  std::vector<int> stack;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(dangling(v))
      stack.push_back(v);
  int removed = 0;
  while(!stack.empty())
  {
    const int v = stack.back();
    stack.pop_back();
    if(!dangling(v))
      continue;
    for(auto arc : boost::make_iterator_range(out_edges(static_cast<std::size_t>(v), graph)))
    {
      const int e = graph[arc].edge;
      if(!is_seam[e])
        continue;
      is_seam[e] = 0;
      ++removed;
      --degree[v];
      const int w = opposite_end(index, e, v);
      --degree[w];
      if(dangling(w))
        stack.push_back(w);
      break;
    }
  }
  return removed;
}

/// A seam edge whose two ends are interior and on no other seam edge: its two sides would
/// join the same two wedges, a two-edge border no triangle mesh can hold.
inline int find_lone_seam_edge(const Mesh_index& index, const std::vector<char>& is_seam,
                               const std::vector<int>& degree)
{
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    if(is_seam[e] && degree[a] == 1 && degree[b] == 1 && !index.is_boundary_vertex[a] &&
       !index.is_boundary_vertex[b])
      return e;
  }
  return -1;
}

/// Replaces a lone seam edge ab (two adjacent cones on a sphere) by the path a-c-b through
/// the third vertex of one of its faces: the same cut, with a border of four edges.
inline void split_lone_seam_edges(const Mesh_index& index, std::vector<char>& is_seam)
{
  std::vector<int> degree = seam_degrees(index, is_seam);
  for(int e = find_lone_seam_edge(index, is_seam, degree); e >= 0;
      e = find_lone_seam_edge(index, is_seam, degree))
  {
    const int f = index.edge_faces[e][0];
    is_seam[e] = 0;
    for(int other : index.face_edges[f])
      if(other != e)
        is_seam[other] = 1;
    degree = seam_degrees(index, is_seam);
  }
}

/// The sides of the surface vertices once cut: two corners of a vertex in the two faces of an
/// uncut interior edge lie on one wedge. Around each vertex this is the walk along its fan
/// that starts a new wedge at every seam or border edge, done for all vertices at once.
struct Wedges
{
  std::vector<std::array<int, 3>> of_corner;  ///< wedge of corner (f, c)
  std::vector<int> surface_vertex;            ///< wedge -> surface vertex
  int size() const { return static_cast<int>(surface_vertex.size()); }
};

inline Wedges cut_wedges(const Mesh_index& index, const std::vector<char>& is_seam)
{
  const int nf = index.number_of_faces(), nv = index.number_of_vertices();
  Union_find corners(3 * nf);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    if(is_seam[e] || is_surface_border_edge(index, e))
      continue;
    const int f = index.edge_faces[e][0], g = index.edge_faces[e][1];
    for(int v : index.edges[e])
      corners.unite(3 * f + corner_of_vertex(index, f, v), 3 * g + corner_of_vertex(index, g, v));
  }
  // The first wedge of vertex v is wedge v, so an uncut surface keeps its numbering.
  Wedges wedges;
  wedges.of_corner.assign(nf, {-1, -1, -1});
  wedges.surface_vertex.resize(nv);
  std::iota(wedges.surface_vertex.begin(), wedges.surface_vertex.end(), 0);
  std::vector<int> wedge_of_root(3 * static_cast<std::size_t>(nf), -1);
  std::vector<char> vertex_used(nv, 0);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      int& wedge = wedge_of_root[corners.find(3 * f + c)];
      if(wedge < 0)
      {
        const int v = index.faces[f][c];
        if(!vertex_used[v])
        {
          vertex_used[v] = 1;
          wedge = v;
        }
        else
        {
          wedge = wedges.size();
          wedges.surface_vertex.push_back(v);
        }
      }
      wedges.of_corner[f][c] = wedge;
    }
  return wedges;
}

/// Topology of the surface cut along `is_seam`, counted without building it.
struct Cut_topology
{
  int pieces = 0;
  int boundary_loops = 0;
  int euler_characteristic = 0;  // of all pieces together
  /// Genus of the cut surface (meaningful for one piece): chi = 2 - 2g - b.
  int genus() const { return (2 - euler_characteristic - boundary_loops) / 2; }
};

inline Cut_topology cut_topology(const Mesh_index& index, const std::vector<char>& is_seam,
                                 const Wedges& wedges)
{
  const int nf = index.number_of_faces(), ne = index.number_of_edges();
  Cut_topology topology;
  Union_find pieces(nf);
  int seams = 0;
  for(int e = 0; e < ne; ++e)
  {
    if(is_seam[e])
      ++seams;
    else if(!is_surface_border_edge(index, e))
      pieces.unite(index.edge_faces[e][0], index.edge_faces[e][1]);
  }
  for(int f = 0; f < nf; ++f)
    if(pieces.find(f) == f)
      ++topology.pieces;
  topology.euler_characteristic = wedges.size() - (ne + seams) + nf;

  // Every wedge on the cut has exactly one border halfedge leaving it; follow them.
  std::vector<int> next(wedges.size(), -1);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int e = index.face_edges[f][c];
      if(is_seam[e] || is_surface_border_edge(index, e))
        next[wedges.of_corner[f][(c + 2) % 3]] = wedges.of_corner[f][(c + 1) % 3];
    }
  std::vector<char> visited(wedges.size(), 0);
  for(int w = 0; w < wedges.size(); ++w)
  {
    if(next[w] < 0 || visited[w])
      continue;
    ++topology.boundary_loops;
    for(int x = w; !visited[x]; x = next[x])
      visited[x] = 1;
  }
  return topology;
}

inline std::string plural(int n, const std::string& word)
{
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

inline std::string describe_seam_edge(const Mesh_index& index, int e)
{
  return "edge " + std::to_string(e) + " (" + std::to_string(index.edges[e][0]) + "-" +
         std::to_string(index.edges[e][1]) + ")";
}

inline Status check_cone_flags(const Mesh_index& index, const std::vector<char>& is_cone)
{
  if(!is_cone.empty() && static_cast<int>(is_cone.size()) != index.number_of_vertices())
    return Status::wrong_parameter("the cone flags have " + std::to_string(is_cone.size()) +
                     " entries, the mesh has " + std::to_string(index.number_of_vertices()) + " vertices");
  return {};
}

} // namespace cutting
} // namespace internal

/// Checks that cutting `index` along `is_seam` (and its border) leaves one topological disk
/// with every cone (`is_cone`, per vertex; empty means none) on the cut or the border.
/// The message names the first failure: a malformed seam, a cone off the cut, or the pieces,
/// genus and boundary loops the cut leaves.
inline Status check_cut_graph(const internal::Mesh_index& index, const std::vector<char>& is_seam,
                                  const std::vector<char>& is_cone = {})
{
  using namespace internal::cutting;
  if(index.number_of_faces() == 0)
    return Status::failure(CGAL::Surface_mesh_parameterization::ERROR_EMPTY_MESH, "the mesh has no faces");
  if(static_cast<int>(is_seam.size()) != index.number_of_edges())
    return Status::wrong_parameter("the seam flags have " + std::to_string(is_seam.size()) + " entries, the mesh has " +
                     plural(index.number_of_edges(), "edge"));
  Status status = check_cone_flags(index, is_cone);
  if(!status.ok())
    return status;
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(is_seam[e] && is_surface_border_edge(index, e))
      return not_a_disk("a seam edge is a border edge: " + describe_seam_edge(index, e) +
                       " is on the border already");

  const std::vector<int> degree = internal::seam_degrees(index, is_seam);
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(!is_cone.empty() && is_cone[v] && degree[v] == 0 && !index.is_boundary_vertex[v])
      return not_a_disk("cone vertex " + std::to_string(v) + " is neither on a seam nor on the border");
  const int lone = find_lone_seam_edge(index, is_seam, degree);
  if(lone >= 0)
    return not_a_disk("seam " + describe_seam_edge(index, lone) +
                     " touches no other seam nor the border: its two sides would be one edge "
                     "(cut along a path of at least two edges)");

  const Cut_topology topology = cut_topology(index, is_seam, cut_wedges(index, is_seam));
  const int seams = static_cast<int>(std::count(is_seam.begin(), is_seam.end(), char(1)));
  if(topology.pieces > 1)
    return not_a_disk("the seams cut the surface into " + std::to_string(topology.pieces) + " pieces");
  if(topology.boundary_loops == 0)
    return not_a_disk(std::string(seams == 0 ? "there are no seams" : "the seams cut nothing open") +
                     " and the surface is closed (genus " + std::to_string(index.genus()) +
                     "): nothing to lay out as a disk");
  if(topology.genus() > 0)
    return not_a_disk("the seams leave genus " + std::to_string(topology.genus()) +
                     (topology.boundary_loops > 1
                        ? " and " + plural(topology.boundary_loops, "boundary loop")
                        : std::string()) +
                     " (a disk has genus 0 and one boundary loop)");
  if(topology.boundary_loops > 1)
    return not_a_disk("the seams leave " + plural(topology.boundary_loops, "boundary loop") +
                     " (a disk has one): they must join every border");
  return {};
}

/// Chooses seams that cut `index` into one disk through every cone (`is_cone`, per vertex;
/// empty means none): a shortest-path tree joining the interior cones and the boundary loops,
/// then 2g tree–cotree homology generators rooted on that tree, then dangling branches
/// pruned. A closed genus-0 surface needs at least two cones: cutting it anywhere else would
/// be arbitrary, so fewer is an error, not a guess.
inline Cut_graph_result cut_graph(const internal::Mesh_index& index, const std::vector<char>& is_cone,
                                  const Cut_graph_options& options = Cut_graph_options())
{
  using namespace internal::cutting;
  Cut_graph_result result;
  if(index.number_of_faces() == 0)
  {
    result.status = Status::failure(CGAL::Surface_mesh_parameterization::ERROR_EMPTY_MESH, "the mesh has no faces");
    return result;
  }
  result.status = check_cone_flags(index, is_cone);
  if(!result.status.ok())
    return result;
  std::vector<int> interior_cones;
  for(int v = 0; v < static_cast<int>(is_cone.size()); ++v)
    if(is_cone[v] && !index.is_boundary_vertex[v])
      interior_cones.push_back(v);
  result.number_of_terminals = index.number_of_boundary_loops() + static_cast<int>(interior_cones.size());
  if(index.number_of_boundary_loops() == 0 && index.genus() == 0 && interior_cones.size() < 2)
  {
    result.status = Status::wrong_parameter("a closed genus-0 surface needs at least 2 cones to be cut into a disk, got " +
                              std::to_string(interior_cones.size()));
    return result;
  }

  const Surface_graph graph = make_surface_graph(index);
  result.is_seam.assign(index.number_of_edges(), 0);
  result.number_of_tree_edges = join_terminals(index, graph, interior_cones, result.is_seam);
  if(index.genus() > 0)
  {
    result.number_of_generators = add_homology_generators(index, graph, interior_cones, result.is_seam);
    if(result.number_of_generators < 0)
    {
      result.status = not_a_disk("the cut and its shortest-path tree separate the faces (is the mesh connected?)");
      return result;
    }
    if(result.number_of_generators != 2 * index.genus())
    {
      result.status = not_a_disk("tree-cotree found " + std::to_string(result.number_of_generators) +
                                " homology generators on a surface of genus " +
                                std::to_string(index.genus()) + " (expected " +
                                std::to_string(2 * index.genus()) + ")");
      return result;
    }
  }
  if(options.prune)
    result.number_of_pruned_edges = prune_dangling_seams(index, graph, is_cone, result.is_seam);
  split_lone_seam_edges(index, result.is_seam);

  for(int e = 0; e < index.number_of_edges(); ++e)
    if(result.is_seam[e])
    {
      ++result.number_of_seam_edges;
      result.seam_length += edge_length(index, e);
    }
  result.status = check_cut_graph(index, result.is_seam, is_cone);
  return result;
}

/// Takes the user's seams (`user_seams`, per edge) as given, no cones needed, and checks that
/// they cut the surface into one disk through every cone of `is_cone` (empty means none).
/// Nothing is added or pruned: a dangling seam is a slit the user asked for.
inline Cut_graph_result cut_graph_from_seams(const internal::Mesh_index& index,
                                             const std::vector<char>& user_seams,
                                             const std::vector<char>& is_cone = {})
{
  Cut_graph_result result;
  result.is_seam = user_seams;
  result.status = check_cut_graph(index, user_seams, is_cone);
  if(!result.status.ok())
    return result;
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(user_seams[e])
    {
      ++result.number_of_seam_edges;
      result.seam_length += internal::edge_length(index, e);
    }
  for(int v = 0; v < static_cast<int>(is_cone.size()); ++v)
    if(is_cone[v] && !index.is_boundary_vertex[v])
      ++result.number_of_terminals;
  result.number_of_terminals += index.number_of_boundary_loops();
  return result;
}

/// Cuts `index` open along `is_seam` (per surface edge) into its own Mesh_index: one vertex
/// per wedge (a vertex of seam-degree d >= 1 inside the surface gets d copies, a border
/// vertex d + 1), the same faces, and the maps back to surface vertices and edges.
/// Fails with the reason when the cut is not one disk.
inline Cut_mesh cut_mesh(const internal::Mesh_index& index, const std::vector<char>& is_seam)
{
  using namespace internal::cutting;
  Cut_mesh cut;
  cut.status = check_cut_graph(index, is_seam);
  if(!cut.status.ok())
    return cut;

  const Wedges wedges = cut_wedges(index, is_seam);
  cut.surface_vertex = wedges.surface_vertex;
  cut.disk.faces = wedges.of_corner;
  cut.disk.points.reserve(wedges.surface_vertex.size());
  for(int v : wedges.surface_vertex)
    cut.disk.points.push_back(index.points[v]);
  // The disk's edges come from the surface's, not from their endpoints (an intrinsic
  // triangulation may join two vertices by two edges): an edge off the cut is one disk edge,
  // a seam edge one per side.
  const int ne = index.number_of_edges(), nf = index.number_of_faces();
  cut.disk_edges.assign(ne, {-1, -1});
  for(int e = 0; e < ne; ++e)
    for(int side = 0; side < (is_seam[e] ? 2 : 1); ++side)
    {
      cut.disk_edges[e][side] = static_cast<int>(cut.surface_edge.size());
      cut.surface_edge.push_back(e);
    }
  const int nd = static_cast<int>(cut.surface_edge.size());
  cut.disk.edges.assign(nd, {-1, -1});
  cut.disk.edge_faces.assign(nd, {-1, -1});
  cut.disk.face_edges.assign(nf, {-1, -1, -1});
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int e = index.face_edges[f][c];
      const int side = index.edge_faces[e][0] == f ? 0 : 1;
      const int d = cut.disk_edges[e][is_seam[e] ? side : 0];
      cut.disk.face_edges[f][c] = d;
      const int a = cut.disk.faces[f][(c + 1) % 3], b = cut.disk.faces[f][(c + 2) % 3];
      cut.disk.edges[d] = {std::min(a, b), std::max(a, b)};
      cut.disk.edge_faces[d][is_seam[e] ? 0 : side] = f;
    }
  const Status built = internal::build_border(cut.disk);
  if(!built.ok())
  {
    cut.status = not_a_disk("the cut surface is not a manifold: " + built.message);
    return cut;
  }
  if(!cut.disk.is_disk())
  {
    cut.status = not_a_disk("the cut surface is not a disk: " + internal::describe_topology(cut.disk));
    return cut;
  }
  return cut;
}

/// For each wedge (disk vertex) of `cut`, the wedge of `other_cut` with the same key, where
/// `cut` cuts `index` and `other_cut` cuts `other` along the same seam edges; empty when a
/// wedge has no partner.
inline std::vector<int> match_wedges(const internal::Mesh_index& index, const Cut_mesh& cut,
                                     const internal::Mesh_index& other, const Cut_mesh& other_cut,
                                     const std::vector<char>& is_seam)
{
  auto keys = [&](const internal::Mesh_index& surface, const Cut_mesh& c) {
    std::vector<long long> key(c.disk.number_of_vertices(), -1);
    for(int f = 0; f < c.disk.number_of_faces(); ++f)
      for(int k = 0; k < 3; ++k)
        if(key[c.disk.faces[f][k]] < 0)
          key[c.disk.faces[f][k]] = internal::wedge_key(surface, is_seam, f, k);
    return key;
  };
  const std::vector<long long> mine = keys(index, cut), theirs = keys(other, other_cut);
  if(mine.size() != theirs.size())
    return {};
  std::vector<std::pair<long long, int>> sorted(theirs.size());
  for(std::size_t w = 0; w < theirs.size(); ++w)
    sorted[w] = {theirs[w], static_cast<int>(w)};
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> match(mine.size());
  for(std::size_t w = 0; w < mine.size(); ++w)
  {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(mine[w], -1));
    if(it == sorted.end() || it->first != mine[w])
      return {};
    match[w] = it->second;
  }
  return match;
}

} // namespace ICM

#endif // ICM_CUT_GRAPH_H
