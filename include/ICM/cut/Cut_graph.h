// Step 6: cut a surface into one topological disk.
//
// Curvature and the metric live on the surface as given; the layout needs a disk. This header
// chooses the cut (the seam edges) and builds the cut surface as its own Mesh_index:
// - `cut_graph` joins the terminals (cone vertices and boundary loops) by a tree of short edge
//   paths, adds 2g homology generators by tree–cotree (Erickson & Whittlesey 2005) on a
//   surface of genus g, prunes the branches that lead nowhere, and passes more seams through
//   the cones wider than 2 pi (cut/Wide_cone_seams.h);
// - `cut_graph_from_seams` takes a user's seams as given and only checks them;
// - `check_cut_graph` (cut/Cut_mesh.h) is the check both use: the cut must leave one disk
//   and touch every cone, and `cut_mesh` there builds the disk.
// Everything works on the flat arrays of `internal::Mesh_index`; edge lengths are 3D
// Euclidean lengths. No exceptions: each result carries a status with the human reason.

#ifndef ICM_CUT_CUT_GRAPH_H
#define ICM_CUT_CUT_GRAPH_H

#include <ICM/Status.h>
#include <ICM/cut/Cut_mesh.h>
#include <ICM/cut/Surface_graph.h>
#include <ICM/cut/Wide_cone_seams.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Vector_geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numeric>
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
  /// Per edge, the length the paths joining the cones minimise (empty: the 3D length), such
  /// as the flat metric's: its shortest paths are nearly straight in the layout, where a 3D
  /// shortest path along a limb can lay its two sides over each other.
  std::vector<double> path_lengths;
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
inline int join_terminals(const Mesh_index& index, const Surface_graph& graph, const std::vector<double>& lengths,
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

  std::vector<std::pair<double, int>> bridges; // (terminal-to-terminal length, edge)
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    if(label[a] != label[b] && label[a] >= 0 && label[b] >= 0) // -1: unreachable, a second component
      bridges.emplace_back(distance[a] + (lengths.empty() ? edge_length(index, e) : lengths[e]) + distance[b], e);
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

  if(!options.path_lengths.empty() && options.path_lengths.size() != index.edges.size())
  {
    result.status = Status::wrong_parameter("path_lengths has " + std::to_string(options.path_lengths.size()) +
                                            " entries for " + std::to_string(index.edges.size()) + " edges");
    return result;
  }
  const Surface_graph graph = make_surface_graph(index, options.path_lengths);
  result.is_seam.assign(index.number_of_edges(), 0);
  result.number_of_tree_edges = join_terminals(index, graph, options.path_lengths, interior_cones, result.is_seam);
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
