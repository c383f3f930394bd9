// Seams through wide cones (part of step 6, cut/Cut_graph.h). A cone that takes an angle above
// 2 pi, where a seam ends, lays its neighbourhood over itself: each side of the cut at a cone
// is one wedge, and a wedge wider than 2 pi overlaps itself. So the cut passes more seams
// through such a cone, each a shortest path from the cone's widest wedge to the seams already
// there, until no wedge is wider than 0.9 of 2 pi.

#ifndef ICM_CUT_WIDE_CONE_SEAMS_H
#define ICM_CUT_WIDE_CONE_SEAMS_H

#include <ICM/cut/Cut_mesh.h>
#include <ICM/cut/Surface_graph.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Vector_geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {
namespace cutting {

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
} // namespace ICM

#endif // ICM_CUT_WIDE_CONE_SEAMS_H
