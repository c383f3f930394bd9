// Step 6: cut a surface into one topological disk.
//
// Curvature and the metric live on the surface as given; the layout needs a disk. This header
// chooses the cut (the seam edges) and builds the cut surface as its own Mesh_index:
// - `cut_graph` joins the terminals (cone vertices and boundary loops) by a tree of short edge
//   paths, adds 2g homology generators by tree–cotree (Erickson & Whittlesey 2005) on a
//   surface of genus g, and prunes the branches that lead nowhere;
// - `cut_graph_from_seams` takes a user's seams as given and only checks them;
// - `check_cut_graph` (cut/Cut_mesh.h) is the check both use: the cut must leave one disk
//   and touch every cone, and `cut_mesh` there builds the disk.
// Everything works on the flat arrays of `internal::Mesh_index`; edge lengths are 3D
// Euclidean lengths. No exceptions: each result carries a status with the human reason.

#ifndef ICM_CUT_CUT_GRAPH_H
#define ICM_CUT_CUT_GRAPH_H

#include <ICM/cut/Cut_mesh.h>
#include <ICM/Status.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Vector_geometry.h>

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
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace ICM {

struct Cut_graph_options
{
  /// Remove seam branches that end at a vertex which is neither a cone nor on the border:
  /// they cut nothing the disk needs and only lengthen its border.
  bool prune = true;
  /// Per vertex, the curvature 2 pi - angle a cone is expected to take (NaN or empty:
  /// unknown). A cone of angle above 2 pi where a seam ends lays its neighbourhood over
  /// itself in the layout (each side of the cut at a cone is one wedge, and a wedge wider
  /// than 2 pi overlaps itself), so the cut passes seams through it until no wedge would
  /// be wider than 0.9 of 2 pi, at least ceil(angle / 2 pi) of them.
  std::vector<double> cone_curvatures;
};

/// The seam edges of a cut and what went into them.
struct Cut_graph_result
{
  std::vector<char> is_seam; ///< per surface edge; never a border edge
  int number_of_seam_edges = 0;
  int number_of_terminals = 0;    ///< interior cones + boundary loops
  int number_of_tree_edges = 0;   ///< edges of the tree joining the terminals
  int number_of_generators = 0;   ///< homology generators added, 2g on genus g
  int number_of_pruned_edges = 0; ///< dangling seam edges removed
  double seam_length = 0;         ///< total 3D length of the seam edges
  /// Cones of angle above 2 pi (`Cut_graph_options::cone_curvatures`) left with a wedge
  /// wider than 0.9 of 2 pi between their seams: no seam could be added there.
  int wide_cones_left_wide = 0;
  Status status;
  bool ok() const { return status.ok(); }
};

namespace internal {
/// The helpers of this header, in their own namespace: names such as `Union_find` are common
/// enough to meet another header's.
namespace cutting {

/// An arc of the surface graph: the mesh edge it runs along and its 3D length.
struct Surface_arc
{
  int edge = -1;
  double length = 0;
};

/// The edge graph of the surface, both directions of every edge, in Boost.Graph's compressed
/// form: built once per cut, then shared by every shortest-path search.
using Surface_graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, Surface_arc>;

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
  return Surface_graph(boost::edges_are_unsorted_multi_pass, arcs.begin(), arcs.end(), properties.begin(),
                       static_cast<std::size_t>(index.number_of_vertices()));
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
                                 std::vector<double>& distance, std::vector<int>& parent_edge, std::vector<int>& label)
{
  const std::size_t n = num_vertices(graph);
  distance.assign(n, std::numeric_limits<double>::max());
  parent_edge.assign(n, -1);
  label.resize(n, -1);
  const auto vertex_index = get(boost::vertex_index, graph);
  boost::dijkstra_shortest_paths(graph, sources.begin(), sources.end(), boost::dummy_property_map(),
                                 boost::make_iterator_property_map(distance.begin(), vertex_index),
                                 get(&Surface_arc::length, graph), vertex_index, std::less<double>(),
                                 boost::closed_plus<double>(), std::numeric_limits<double>::max(), 0.0,
                                 boost::make_dijkstra_visitor(Forest_recorder{&parent_edge, &label}));
}

inline int opposite_end(const Mesh_index& index, int e, int v)
{
  return index.edges[e][0] == v ? index.edges[e][1] : index.edges[e][0];
}

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
inline int join_terminals(const Mesh_index& index, const Surface_graph& graph, const std::vector<int>& interior_cones,
                          std::vector<char>& is_seam)
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

  std::vector<std::pair<double, int>> bridges; // (terminal-to-terminal length, edge)
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    if(label[a] != label[b] && label[a] >= 0 && label[b] >= 0) // -1: unreachable, a second component
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
    sources.push_back(0); // closed, no cone: any root will do

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
inline int prune_dangling_seams(const Mesh_index& index, const Surface_graph& graph, const std::vector<char>& is_cone,
                                std::vector<char>& is_seam)
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

/// Replaces a lone seam edge ab (two adjacent cones on a sphere) by the path a-c-b through
/// the third vertex of one of its faces: the same cut, with a border of four edges.
inline void split_lone_seam_edges(const Mesh_index& index, std::vector<char>& is_seam)
{
  std::vector<int> degree = seam_degrees(index, is_seam);
  for(int e = find_lone_seam_edge(index, is_seam, degree); e >= 0; e = find_lone_seam_edge(index, is_seam, degree))
  {
    const int f = index.edge_faces[e][0];
    is_seam[e] = 0;
    for(int other : index.face_edges[f])
      if(other != e)
        is_seam[other] = 1;
    degree = seam_degrees(index, is_seam);
  }
}

/// The seams a cone of curvature `k` (2 pi - angle) needs so that no wedge around it is
/// wider than 2 pi: ceil(angle / 2 pi), one for a cone of angle up to 2 pi or unknown.
inline int least_seam_degree(double k)
{
  if(!(k < 0))
    return 1;
  return static_cast<int>(std::ceil((2 * M_PI - k) / (2 * M_PI) - 1e-9));
}

/// Scratch space of `nearest_target`, allocated once for all its searches: every search
/// resets only the vertices it reached.
struct Path_search
{
  std::vector<double> distance;
  std::vector<int> parent_edge;
  std::vector<int> reached;
  std::vector<char> vertex_mark, edge_mark; ///< all 0 between uses of `add_seam_through`

  Path_search(int vertices, int edges)
    : distance(vertices, HUGE_VAL), parent_edge(vertices, -1), vertex_mark(vertices, 0), edge_mark(edges, 0)
  {}

  void reset()
  {
    for(int v : reached)
    {
      distance[v] = HUGE_VAL;
      parent_edge[v] = -1;
    }
    reached.clear();
  }
};

/// Dijkstra from `sources` (vertex, start distance, first edge) over the arcs whose edge
/// `usable` admits, through the vertices `passable` admits, up to the first vertex
/// `is_target` admits, which it returns (-1: none reachable). `search.parent_edge` then
/// leads back from it to a source, and on to the source's first edge.
template <class Usable, class Passable, class Target>
int nearest_target(const Surface_graph& graph, const std::vector<std::tuple<int, double, int>>& sources,
                   const Usable& usable, const Passable& passable, const Target& is_target, Path_search& search)
{
  search.reset();
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  const auto relax = [&](int v, double d, int edge) {
    if(d >= search.distance[v])
      return;
    if(search.distance[v] == HUGE_VAL)
      search.reached.push_back(v);
    search.distance[v] = d;
    search.parent_edge[v] = edge;
    queue.emplace(d, v);
  };
  for(const auto& [v, d, edge] : sources)
    relax(v, d, edge);
  while(!queue.empty())
  {
    const auto [d, v] = queue.top();
    queue.pop();
    if(d > search.distance[v])
      continue;
    if(is_target(v))
      return v;
    if(!passable(v))
      continue;
    for(auto arc : boost::make_iterator_range(out_edges(static_cast<std::size_t>(v), graph)))
      if(usable(graph[arc].edge))
        relax(static_cast<int>(target(arc, graph)), d + graph[arc].length, graph[arc].edge);
  }
  return -1;
}

/// The edges of the path `search` found from `end` back to where it started at `stop`.
inline std::vector<int> path_edges(const Mesh_index& index, const Path_search& search, int end, int stop)
{
  std::vector<int> edges;
  for(int v = end; v != stop && search.parent_edge[v] >= 0;)
  {
    edges.push_back(search.parent_edge[v]);
    v = opposite_end(index, search.parent_edge[v], v);
  }
  return edges;
}

/// Where a stretch of seam ends: a vertex whose seam degree is not 2, on the border, or a cone.
inline bool is_junction(const Mesh_index& index, const std::vector<char>& is_cone, const std::vector<int>& degree,
                        int v)
{
  return degree[v] != 2 || index.is_boundary_vertex[v] || (!is_cone.empty() && is_cone[v]);
}

/// One try of `add_seam_through` to the nearest seam vertex not marked `own`.
template <class StillFine>
bool try_seam_through(const Mesh_index& index, const Surface_graph& graph, const std::vector<char>& is_cone, int w,
                      const std::vector<std::tuple<int, double, int>>& starts, const StillFine& still_fine,
                      std::vector<char>& own, std::vector<int>& own_vertices, std::vector<char>& is_seam,
                      std::vector<int>& degree, Path_search& search)
{
  const auto important = [&](int v) { return is_junction(index, is_cone, degree, v); };
  const auto on_seam_off_own = [&](int v) { return degree[v] > 0 && !own[v] && !index.is_boundary_vertex[v]; };
  const int x = nearest_target(
    graph, starts, [&](int e) { return !is_seam[e] && !is_surface_border_edge(index, e); },
    [&](int v) { return v != w && degree[v] == 0 && !index.is_boundary_vertex[v]; }, on_seam_off_own, search);
  if(x < 0)
    return false;
  const std::vector<int> added = path_edges(index, search, x, w);
  for(int e : added)
  {
    is_seam[e] = 1;
    ++degree[index.edges[e][0]];
    ++degree[index.edges[e][1]];
  }

  // The cut's old way from x back to w, over seams and border edges.
  std::vector<char>& is_new = search.edge_mark;
  for(int e : added)
    is_new[e] = 1;
  const auto on_cut = [&](int e) { return !is_new[e] && (is_seam[e] || is_surface_border_edge(index, e)); };
  nearest_target(
    graph, {{x, 0.0, -1}}, on_cut, [](int) { return true; }, [&](int v) { return v == w; }, search);
  const std::vector<int> cycle = path_edges(index, search, w, x);
  for(int e : added)
    is_new[e] = 0;

  // Its stretches of seam between important vertices, the one at the cone left out.
  struct Stretch
  {
    double length;
    int from, to;
    std::vector<int> edges;
  };
  std::vector<Stretch> stretches;
  std::vector<int> stretch;
  double length = 0;
  bool on_border = false;
  int v = w, start = w;
  for(int e : cycle) // from w towards x
  {
    if(is_surface_border_edge(index, e))
      on_border = true;
    stretch.push_back(e);
    length += edge_length(index, e);
    v = opposite_end(index, e, v);
    if(important(v) || v == x)
    {
      if(!on_border && start != w)
        stretches.push_back({length, start, v, stretch});
      stretch.clear();
      length = 0;
      on_border = false;
      start = v;
    }
  }
  std::sort(stretches.begin(), stretches.end(), [](const Stretch& a, const Stretch& b) { return a.length > b.length; });
  for(const Stretch& candidate : stretches)
  {
    for(int e : candidate.edges)
    {
      is_seam[e] = 0;
      --degree[index.edges[e][0]];
      --degree[index.edges[e][1]];
    }
    if(still_fine(candidate.from) && still_fine(candidate.to) &&
       (index.genus() == 0 || check_cut_graph(index, is_seam, is_cone).ok()))
      return true;
    for(int e : candidate.edges)
    {
      is_seam[e] = 1;
      ++degree[index.edges[e][0]];
      ++degree[index.edges[e][1]];
    }
  }
  for(int e : added)
  {
    is_seam[e] = 0;
    --degree[index.edges[e][0]];
    --degree[index.edges[e][1]];
  }
  for(int e : cycle)
    for(int end : index.edges[e])
      if(!own[end])
      {
        own[end] = 1;
        own_vertices.push_back(end);
      }
  return false;
}

/// Passes a new seam through the wide cone `w`: a shortest path leaves it through one of
/// `starts` (ring neighbours: vertex, length, edge) and runs to the nearest seam vertex off
/// the cone's own branches; the cycle that closes is opened again by removing its longest
/// stretch of seam between branch points, cones or the border that keeps the cut one disk
/// and after which `still_fine(v)` holds at both its ends (the wide cones done before keep
/// their wedges). False, with the seams as they were, when no such path or stretch exists.
template <class StillFine>
bool add_seam_through(const Mesh_index& index, const Surface_graph& graph, const std::vector<char>& is_cone, int w,
                      const std::vector<std::tuple<int, double, int>>& starts, const StillFine& still_fine,
                      std::vector<char>& is_seam, std::vector<int>& degree, Path_search& search)
{
  const auto important = [&](int v) { return is_junction(index, is_cone, degree, v); };
  // The cone's own branches, up to the first vertex where they meet others: a path ending
  // there would close a cycle through the cone alone.
  std::vector<char>& own = search.vertex_mark;
  std::vector<int> own_vertices{w};
  own[w] = 1;
  for(auto arc : boost::make_iterator_range(out_edges(static_cast<std::size_t>(w), graph)))
  {
    int e = graph[arc].edge;
    if(!is_seam[e])
      continue;
    int v = static_cast<int>(target(arc, graph));
    for(;;)
    {
      own[v] = 1;
      own_vertices.push_back(v);
      if(important(v))
        break;
      int next_edge = -1;
      for(auto next : boost::make_iterator_range(out_edges(static_cast<std::size_t>(v), graph)))
        if(is_seam[graph[next].edge] && graph[next].edge != e)
          next_edge = graph[next].edge;
      e = next_edge;
      v = opposite_end(index, e, v);
    }
  }
  // Up to `attempts` targets: a cycle whose stretches all end at cones done before is not
  // opened, and its vertices are then no target for the next try.
  const int attempts = 4;
  bool placed = false;
  for(int attempt = 0; attempt < attempts && !placed; ++attempt)
    placed = try_seam_through(index, graph, is_cone, w, starts, still_fine, own, own_vertices, is_seam, degree, search);
  for(int v : own_vertices)
    own[v] = 0;
  return placed;
}

/// The ring of an interior vertex in counter-clockwise order, each neighbour with its 3D
/// angular position from the first (the corner angles at the vertex summed up to it).
struct Vertex_ring
{
  std::vector<int> neighbours;
  std::vector<double> position;
  double angle = 0; ///< the 3D angle sum
};

/// `faces`: the faces around `w`.
inline Vertex_ring vertex_ring(const Mesh_index& index, int w, const std::vector<int>& faces)
{
  std::vector<std::pair<int, std::pair<int, double>>> next; // a -> (b, angle of the corner at w)
  for(int f : faces)
  {
    const std::array<int, 3>& t = index.faces[f];
    const int c = t[0] == w ? 0 : t[1] == w ? 1 : 2;
    const int a = t[(c + 1) % 3], b = t[(c + 2) % 3];
    const Point3 da = difference(index.points[a], index.points[w]), db = difference(index.points[b], index.points[w]);
    next.push_back({a, {b, std::atan2(cross_norm(da, db), dot(da, db))}});
  }
  std::sort(next.begin(), next.end());
  Vertex_ring ring;
  if(next.empty())
    return ring;
  int v = next.front().first;
  for(std::size_t k = 0; k < next.size(); ++k)
  {
    ring.neighbours.push_back(v);
    ring.position.push_back(ring.angle);
    const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(v, std::make_pair(-1, 0.0)));
    if(it == next.end() || it->first != v)
      break; // not a closed ring (cannot happen at an interior vertex)
    ring.angle += it->second.second;
    v = it->second.first;
  }
  return ring;
}

/// The first steps of a seam that halves the widest wedge at `w` (between consecutive seams
/// around it): the ring neighbours in its middle third, or nearest its middle. Empty when no
/// wedge would be wider than `widest` in the layout, the 3D wedges scaled by `angle` over
/// the 3D angle sum (a conformal map scales the angles around a cone alike).
inline std::vector<std::tuple<int, double, int>>
widest_wedge_starts(const Mesh_index& index, const Surface_graph& graph, int w, const Vertex_ring& ring,
                    const std::vector<char>& is_seam, double angle, double widest)
{
  std::vector<int> edge_to(ring.neighbours.size(), -1);
  std::vector<double> length(ring.neighbours.size(), 0);
  std::vector<std::size_t> seams;
  for(auto arc : boost::make_iterator_range(out_edges(static_cast<std::size_t>(w), graph)))
  {
    const auto k = std::find(ring.neighbours.begin(), ring.neighbours.end(), static_cast<int>(target(arc, graph))) -
                   ring.neighbours.begin();
    if(k == static_cast<long>(ring.neighbours.size()))
      continue;
    edge_to[k] = graph[arc].edge;
    length[k] = graph[arc].length;
    if(is_seam[graph[arc].edge])
      seams.push_back(static_cast<std::size_t>(k));
  }
  if(seams.empty() || ring.angle <= 0)
    return {};
  std::sort(seams.begin(), seams.end());
  double from = 0, span = -1;
  for(std::size_t i = 0; i < seams.size(); ++i)
  {
    const double a = ring.position[seams[i]];
    const double b = i + 1 < seams.size() ? ring.position[seams[i + 1]] : ring.position[seams[0]] + ring.angle;
    if(b - a > span)
    {
      from = a;
      span = b - a;
    }
  }
  if(span * angle / ring.angle <= widest)
    return {};
  std::vector<std::tuple<int, double, int>> starts;
  double nearest = HUGE_VAL;
  int middle = -1;
  for(std::size_t k = 0; k < ring.neighbours.size(); ++k)
  {
    double offset = ring.position[k] - from;
    if(offset < 0)
      offset += ring.angle;
    if(offset <= 0 || offset >= span || is_seam[edge_to[k]] || index.is_boundary_vertex[ring.neighbours[k]])
      continue;
    if(std::abs(offset - span / 2) <= span / 6)
      starts.emplace_back(ring.neighbours[k], length[k], edge_to[k]);
    if(std::abs(offset - span / 2) < nearest)
    {
      nearest = std::abs(offset - span / 2);
      middle = static_cast<int>(k);
    }
  }
  if(starts.empty() && middle >= 0)
    starts.emplace_back(ring.neighbours[middle], length[middle], edge_to[middle]);
  return starts;
}

/// Seams through every cone expected to take an angle above 2 pi (`curvatures`) until no
/// wedge around it would be wider than 0.9 of 2 pi in the layout, where they can be added
/// (`add_seam_through`), at most `least_seam_degree` + 2 of them. Returns the cones left with
/// a wider wedge. The 0.9 leaves room for the prediction's error; on the shared meshes 0.75
/// and 0.6 added seams that split more charts than they saved (doc/benchmarks.md, Cones).
inline int pass_seams_through_wide_cones(const Mesh_index& index, const Surface_graph& graph,
                                         const std::vector<char>& is_cone, const std::vector<double>& curvatures,
                                         std::vector<char>& is_seam)
{
  const int nv = index.number_of_vertices();
  std::vector<char> is_wide(nv, 0);
  for(int v = 0; v < nv; ++v)
    is_wide[v] = !is_cone.empty() && is_cone[v] && !index.is_boundary_vertex[v] && curvatures[v] < 0;
  std::vector<std::vector<int>> faces_at(nv);
  for(int f = 0; f < index.number_of_faces(); ++f)
    for(int v : index.faces[f])
      if(is_wide[v])
        faces_at[v].push_back(f);
  std::vector<int> degree = seam_degrees(index, is_seam);
  std::vector<char> done(nv, 0);
  Path_search search(nv, index.number_of_edges());
  const double widest_wedge = 0.9 * 2 * M_PI;
  int left_wide = 0;
  std::vector<Vertex_ring> rings(nv);
  for(int v = 0; v < nv; ++v)
    if(is_wide[v])
      rings[v] = vertex_ring(index, v, faces_at[v]);
  const auto wedge_starts = [&](int v) {
    return widest_wedge_starts(index, graph, v, rings[v], is_seam, 2 * M_PI - curvatures[v], widest_wedge);
  };
  const auto still_fine = [&](int v) { return !done[v] || wedge_starts(v).empty(); };
  for(int w = 0; w < nv; ++w)
  {
    if(!is_wide[w])
      continue;
    bool wide = true;
    for(int added = 0; added < least_seam_degree(curvatures[w]) + 2; ++added)
    {
      const auto starts = wedge_starts(w);
      wide = !starts.empty();
      if(!wide || !add_seam_through(index, graph, is_cone, w, starts, still_fine, is_seam, degree, search))
        break;
    }
    left_wide += wide;
    done[w] = 1;
  }
  return left_wide;
}

} // namespace cutting
} // namespace internal

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
    result.status =
      Status::wrong_parameter("a closed genus-0 surface needs at least 2 cones to be cut into a disk, got " +
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
                                 " homology generators on a surface of genus " + std::to_string(index.genus()) +
                                 " (expected " + std::to_string(2 * index.genus()) + ")");
      return result;
    }
  }
  if(options.prune)
    result.number_of_pruned_edges = prune_dangling_seams(index, graph, is_cone, result.is_seam);
  if(!options.cone_curvatures.empty())
    result.wide_cones_left_wide =
      pass_seams_through_wide_cones(index, graph, is_cone, options.cone_curvatures, result.is_seam);
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
inline Cut_graph_result cut_graph_from_seams(const internal::Mesh_index& index, const std::vector<char>& user_seams,
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

} // namespace ICM

#endif // ICM_CUT_CUT_GRAPH_H
