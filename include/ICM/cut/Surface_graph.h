// The edge graph of a surface that the cut searches (cut/Cut_graph.h, cut/Wide_cone_seams.h):
// every mesh edge both ways with its 3D length, in Boost.Graph's compressed form, and the
// multi-source shortest-path forest grown on it.

#ifndef ICM_CUT_SURFACE_GRAPH_H
#define ICM_CUT_SURFACE_GRAPH_H

#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Vector_geometry.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/visitors.hpp>
#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {
namespace cutting {
/// An arc of the surface graph: the mesh edge it runs along and its length (3D, or the one
/// the cut is asked to measure paths with).
struct Surface_arc
{
  int edge = -1;
  double length = 0;
};

/// The edge graph of the surface, both directions of every edge, in Boost.Graph's compressed
/// form: built once per cut, then shared by every shortest-path search.
using Surface_graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, Surface_arc>;

/// `lengths`, per edge, are what the shortest paths measure (empty: the 3D lengths).
inline Surface_graph make_surface_graph(const Mesh_index& index, const std::vector<double>& lengths = {})
{
  std::vector<std::pair<std::size_t, std::size_t>> arcs;
  std::vector<Surface_arc> properties;
  arcs.reserve(2 * index.edges.size());
  properties.reserve(2 * index.edges.size());
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const std::size_t a = index.edges[e][0], b = index.edges[e][1];
    const Surface_arc arc{e, lengths.empty() ? edge_length(index, e) : lengths[e]};
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
} // namespace cutting
} // namespace internal
} // namespace ICM

#endif // ICM_CUT_SURFACE_GRAPH_H
