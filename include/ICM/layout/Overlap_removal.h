// Removing global overlaps by cutting a chart into pieces.
//
// A layout with no flipped face can still fold over itself: the free-boundary map of the
// horse swings a leg over another one. The faces that land on top of each other come in
// layers that are far apart on the surface. The chart is cut between two overlapping layers
// along the shortest seam that separates them (a minimum s-t cut of the dual graph, edge
// capacity = 3D edge length, source = one layer, sink = the other), and again in each piece
// until no piece overlaps itself. The pieces keep their UVs up to a translation, so the
// metric, the distortion and the flip count are exactly those of the raw optimum: the only
// cost is seam length.
//
// The cut works on the chart's cut mesh (`Cut_mesh`, a disk or already several pieces): a
// wedge whose faces end in different pieces gets one copy per piece, and the new seams join
// the cut's surface edges, so seam lengths and wedges stay checkable as before.

#ifndef ICM_LAYOUT_OVERLAP_REMOVAL_H
#define ICM_LAYOUT_OVERLAP_REMOVAL_H

#include <ICM/cut/Cut_graph.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Chart_packing.h>
#include <ICM/layout/Layout.h>
#include <ICM/internal/Mesh_index.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace ICM {

/// What `remove_overlaps` did to one chart.
struct Overlap_removal
{
  int pieces = 1;                 ///< pieces the chart was cut into (1: it did not overlap)
  int cut_edges = 0;              ///< surface edges that became seams
  int overlapping_face_pairs = 0; ///< face pairs still overlapping inside a piece (0 unless `max_cuts` ran out)
};

namespace internal {
namespace overlaps {

/// Capacities are integers: a maximum flow of floating-point edge lengths is balanced only up
/// to rounding, which Boost's checks of a flow (exact equalities) refuse.
using Capacity = long long;
/// The flow network in compressed sparse rows, its arc properties in arrays by arc index: an
/// `adjacency_list` allocates every arc's properties apart, and at a million faces building
/// and freeing them took longer than the flow.
using Flow_graph = boost::compressed_sparse_row_graph<boost::directedS>;
using Arc = boost::graph_traits<Flow_graph>::edge_descriptor;

/// The arcs of a flow network, each with its zero-capacity reverse arc (on which Boost's
/// maximum flows keep the residual flow), before they are sorted into a `Flow_graph`.
struct Flow_arcs
{
  std::vector<std::pair<int, int>> ends;
  std::vector<Capacity> capacity;

  void add(int a, int b, Capacity c)
  {
    ends.emplace_back(a, b);
    capacity.push_back(c);
    ends.emplace_back(b, a);
    capacity.push_back(0); // arc 2k + 1 reverses arc 2k
  }
};

/// Vertices on the source side of a minimum cut of `arcs` between `s` and `t` (the source's
/// reach in the residual network; every maximum flow leaves the same one).
inline std::vector<char> source_side(const Flow_arcs& arcs, int vertices, int s, int t)
{
  // Sorted by tail (counting sort): a sorted arc list keeps its order in the graph.
  const int m = static_cast<int>(arcs.ends.size());
  std::vector<int> start(vertices + 1, 0), position(m);
  for(const auto& end : arcs.ends)
    ++start[end.first + 1];
  for(int v = 0; v < vertices; ++v)
    start[v + 1] += start[v];
  std::vector<int> next(start.begin(), start.end() - 1);
  std::vector<std::pair<int, int>> sorted(m);
  for(int i = 0; i < m; ++i)
  {
    position[i] = next[arcs.ends[i].first]++;
    sorted[position[i]] = arcs.ends[i];
  }
  const Flow_graph g(boost::edges_are_sorted, sorted.begin(), sorted.end(), static_cast<std::size_t>(vertices));
  std::vector<Capacity> capacity(m), residual(m);
  std::vector<Arc> reverse(m);
  for(int i = 0; i < m; ++i)
  {
    const int j = i ^ 1;
    capacity[position[i]] = arcs.capacity[i];
    reverse[position[i]] = Arc(arcs.ends[j].first, position[j]);
  }
  const auto arc_index = boost::get(boost::edge_index, g);
  const auto vertex_index = boost::get(boost::vertex_index, g);
  std::vector<boost::default_color_type> colour(vertices);
  std::vector<Arc> predecessor(vertices);
  std::vector<long> distance(vertices);
  // Boykov-Kolmogorov: on these planar dual graphs 10x faster than push-relabel (horse's
  // 40k faces: 0.4 s).
  boost::boykov_kolmogorov_max_flow(g, boost::make_iterator_property_map(capacity.begin(), arc_index),
                                    boost::make_iterator_property_map(residual.begin(), arc_index),
                                    boost::make_iterator_property_map(reverse.begin(), arc_index),
                                    boost::make_iterator_property_map(predecessor.begin(), vertex_index),
                                    boost::make_iterator_property_map(colour.begin(), vertex_index),
                                    boost::make_iterator_property_map(distance.begin(), vertex_index), vertex_index,
                                    static_cast<std::size_t>(s), static_cast<std::size_t>(t));
  std::vector<char> reached(vertices, 0);
  std::vector<int> stack{s};
  reached[s] = 1;
  while(!stack.empty())
  {
    const int a = stack.back();
    stack.pop_back();
    for(const Arc arc : boost::make_iterator_range(boost::out_edges(static_cast<std::size_t>(a), g)))
    {
      const int b = static_cast<int>(boost::target(arc, g));
      if(!reached[b] && residual[get(arc_index, arc)] > 0)
      {
        reached[b] = 1;
        stack.push_back(b);
      }
    }
  }
  return reached;
}

/// The faces of `piece_faces` on the source side of a minimum cut between `sources` and
/// `sinks` in the dual graph of the piece (faces joined through their interior edges whose
/// both faces are in the piece), each dual edge weighted by its 3D length.
inline std::vector<int> source_side_of_minimum_cut(const Mesh_index& disk, const std::vector<int>& piece_of_face,
                                                   const std::vector<int>& piece_faces, const std::vector<int>& sources,
                                                   const std::vector<int>& sinks)
{
  const int piece = piece_of_face[piece_faces.front()];
  std::vector<int> node_of_face(disk.number_of_faces(), -1);
  for(std::size_t i = 0; i < piece_faces.size(); ++i)
    node_of_face[piece_faces[i]] = static_cast<int>(i);
  const int n = static_cast<int>(piece_faces.size()), s = n, t = n + 1;
  std::vector<int> dual_edges;
  double total = 0;
  for(int e = 0; e < disk.number_of_edges(); ++e)
  {
    const int f = disk.edge_faces[e][0], h = disk.edge_faces[e][1];
    if(h < 0 || piece_of_face[f] != piece || piece_of_face[h] != piece)
      continue;
    dual_edges.push_back(e);
    total += edge_length(disk, e);
  }
  // Lengths in units of 2^-40 of their sum: any cut is then at most 2^40 units, and the
  // source arcs' capacities (2^41 + 1 each) sum below 2^62 for up to 2^20 sources.
  const double unit = total > 0 ? std::ldexp(1.0, -40) * total : 1.0;
  Flow_arcs arcs;
  arcs.ends.reserve(4 * dual_edges.size() + 2 * (sources.size() + sinks.size()));
  arcs.capacity.reserve(arcs.ends.capacity());
  for(int e : dual_edges)
  {
    const int f = node_of_face[disk.edge_faces[e][0]], h = node_of_face[disk.edge_faces[e][1]];
    const Capacity length = std::llround(edge_length(disk, e) / unit);
    arcs.add(f, h, length);
    arcs.add(h, f, length);
  }
  const Capacity unlimited = (Capacity(1) << 41) + 1;
  for(int f : sources)
    arcs.add(s, node_of_face[f], unlimited);
  for(int f : sinks)
    arcs.add(node_of_face[f], t, unlimited);
  const std::vector<char> reached = source_side(arcs, n + 2, s, t);
  std::vector<int> side;
  for(int i = 0; i < n; ++i)
    if(reached[i])
      side.push_back(piece_faces[i]);
  return side;
}

/// Renumbers `piece_of_face` so that each piece is one edge-connected set of faces.
inline int connected_pieces(const Mesh_index& disk, std::vector<int>& piece_of_face)
{
  cutting::Union_find sets(disk.number_of_faces());
  for(int e = 0; e < disk.number_of_edges(); ++e)
  {
    const int f = disk.edge_faces[e][0], h = disk.edge_faces[e][1];
    if(h >= 0 && piece_of_face[f] == piece_of_face[h])
      sets.unite(f, h);
  }
  std::map<int, int> number_of_root;
  for(int f = 0; f < disk.number_of_faces(); ++f)
    piece_of_face[f] = number_of_root.emplace(sets.find(f), static_cast<int>(number_of_root.size())).first->second;
  return static_cast<int>(number_of_root.size());
}

/// One pair of layers to separate inside a piece: the overlapping faces of the piece grouped
/// into edge-connected layers; the two layers with the most overlapping face pairs between
/// them (one face against the other when a layer overlaps itself).
inline std::pair<std::vector<int>, std::vector<int>> layers_to_separate(const Mesh_index& disk,
                                                                        const std::vector<int>& piece_of_face,
                                                                        const std::vector<std::pair<int, int>>& pairs)
{
  std::vector<char> overlapping(disk.number_of_faces(), 0);
  for(const auto& [f, g] : pairs)
    overlapping[f] = overlapping[g] = 1;
  cutting::Union_find layers(disk.number_of_faces());
  for(int e = 0; e < disk.number_of_edges(); ++e)
  {
    const int f = disk.edge_faces[e][0], h = disk.edge_faces[e][1];
    if(h >= 0 && overlapping[f] && overlapping[h] && piece_of_face[f] == piece_of_face[h])
      layers.unite(f, h);
  }
  std::map<std::pair<int, int>, int> count;
  for(const auto& [f, g] : pairs)
  {
    const int a = layers.find(f), b = layers.find(g);
    ++count[{std::min(a, b), std::max(a, b)}];
  }
  const auto strongest = std::max_element(count.begin(), count.end(), [](const auto& x, const auto& y) {
                           return x.second < y.second;
                         })->first;
  std::vector<int> first, second;
  if(strongest.first == strongest.second)
  {
    // One layer folded over itself (a flap joined to what it covers through the fold):
    // split the layer between a pair's two faces, each face of the layer going to the
    // nearer of them in face hops. Separating the two faces alone, the cheapest cut is
    // around one of them, and a fold needs as many cuts as it has faces.
    const int layer = strongest.first;
    int f = -1, g = -1;
    for(const auto& pair : pairs)
      if(layers.find(pair.first) == layer)
      {
        std::tie(f, g) = pair;
        break;
      }
    std::vector<int> side(disk.number_of_faces(), -1);
    std::vector<int> queue{f, g};
    side[f] = 0;
    side[g] = 1;
    for(std::size_t next = 0; next < queue.size(); ++next)
    {
      const int a = queue[next];
      for(int e : disk.face_edges[a])
        for(int b : disk.edge_faces[e])
          if(b >= 0 && side[b] < 0 && overlapping[b] && layers.find(b) == layer)
          {
            side[b] = side[a];
            queue.push_back(b);
          }
    }
    for(int h : queue)
      (side[h] == 0 ? first : second).push_back(h);
    return {first, second};
  }
  for(int f = 0; f < disk.number_of_faces(); ++f)
    if(overlapping[f])
    {
      if(layers.find(f) == strongest.first)
        first.push_back(f);
      else if(layers.find(f) == strongest.second)
        second.push_back(f);
    }
  return {first, second};
}

/// Whether the layout of `disk` is injective because every face is positively oriented and
/// its border is a simple curve: a point off the border's image then has as many preimages as
/// the border winds around it, at most one (the degree argument). It costs the border's
/// crossings instead of every face's overlaps.
inline bool is_injective_by_its_border(const Mesh_index& disk, const std::vector<Uv>& uv)
{
  if(!disk.is_disk())
    return false;
  for(const auto& f : disk.faces)
    if(orientation(uv[f[0]], uv[f[1]], uv[f[2]]) <= 0)
      return false;
  return count_border_overlaps(disk, uv).empty();
}

/// Joins pieces again where no overlapping pair of `pairs` would share the joined piece, the
/// smallest piece first (by faces), each into the neighbour it shares the longest border with.
/// The cuts are made one pair of layers at a time, so a piece cut off early, often a single
/// face, no longer overlaps the piece next to it once a later cut took away what it covered.
/// The pieces keep the chart's UVs, so a join is exact: it only gives the seam back.
inline void join_pieces_that_do_not_overlap(const Mesh_index& disk, const std::vector<std::pair<int, int>>& pairs,
                                            std::vector<int>& piece_of_face)
{
  const int pieces = 1 + *std::max_element(piece_of_face.begin(), piece_of_face.end());
  // Per piece: the border length it shares with each neighbour, and the pieces it overlaps.
  // A join merges the smaller tables into the larger, so the pass costs O(E + pairs) once
  // and a near-linear amount of table work after.
  std::vector<std::map<int, double>> shared(pieces);
  std::vector<std::set<int>> overlapped(pieces);
  for(int e = 0; e < disk.number_of_edges(); ++e)
  {
    const int f = disk.edge_faces[e][0], h = disk.edge_faces[e][1];
    if(h < 0 || piece_of_face[f] == piece_of_face[h])
      continue;
    const double length = edge_length(disk, e);
    shared[piece_of_face[f]][piece_of_face[h]] += length;
    shared[piece_of_face[h]][piece_of_face[f]] += length;
  }
  for(const auto& [f, g] : pairs)
    if(piece_of_face[f] != piece_of_face[g])
    {
      overlapped[piece_of_face[f]].insert(piece_of_face[g]);
      overlapped[piece_of_face[g]].insert(piece_of_face[f]);
    }
  std::vector<int> faces(pieces, 0), root(pieces);
  for(int p : piece_of_face)
    ++faces[p];
  std::iota(root.begin(), root.end(), 0);
  std::vector<int> order = root;
  std::sort(order.begin(), order.end(), [&faces](int a, int b) { return faces[a] < faces[b]; });
  for(int p : order)
  {
    if(root[p] != p)
      continue; // already joined into another piece
    int best = -1;
    for(const auto& [q, length] : shared[p])
      if(!overlapped[p].count(q) && (best < 0 || length > shared[p][best]))
        best = q;
    if(best < 0)
      continue;
    // Keep the piece with the larger tables; the other's entries move to it and every
    // neighbour's entry for the removed piece is renamed.
    const int keep =
      shared[p].size() + overlapped[p].size() >= shared[best].size() + overlapped[best].size() ? p : best;
    const int gone = keep == p ? best : p;
    for(const auto& [q, length] : shared[gone])
    {
      shared[q].erase(gone);
      if(q == keep)
        continue;
      shared[keep][q] += length;
      shared[q][keep] += length;
    }
    shared[keep].erase(gone);
    for(int q : overlapped[gone])
    {
      overlapped[q].erase(gone);
      overlapped[q].insert(keep);
      overlapped[keep].insert(q);
    }
    shared[gone].clear();
    overlapped[gone].clear();
    for(int& r : root)
      if(r == gone)
        r = keep;
    faces[keep] += faces[gone];
  }
  std::map<int, int> number_of_root;
  for(int& p : piece_of_face)
    p = number_of_root.emplace(root[p], static_cast<int>(number_of_root.size())).first->second;
}

/// Piece of each face of `disk` such that no two faces of a piece overlap in `uv`, by at most
/// `max_cuts` minimum cuts. The overlapping pairs are found once: the pieces keep their
/// UVs, so a cut only decides which pairs still share a piece. `remaining` receives the pairs
/// left inside pieces.
inline std::vector<int> pieces_without_overlaps(const Mesh_index& disk, const std::vector<Uv>& uv, int max_cuts,
                                                int& remaining)
{
  std::vector<int> piece_of_face(disk.number_of_faces(), 0);
  if(is_injective_by_its_border(disk, uv))
  {
    remaining = 0;
    return piece_of_face;
  }
  const std::vector<std::pair<int, int>> all_pairs = overlapping_face_pairs(disk, uv);
  std::vector<std::pair<int, int>> pairs = all_pairs;
  for(int cuts = 0; !pairs.empty() && cuts < max_cuts; ++cuts)
  {
    // The piece of the first pair still overlapping, its faces, and its two layers.
    const int piece = piece_of_face[pairs.front().first];
    std::vector<std::pair<int, int>> in_piece;
    for(const auto& pair : pairs)
      if(piece_of_face[pair.first] == piece)
        in_piece.push_back(pair);
    std::vector<int> faces;
    for(int f = 0; f < disk.number_of_faces(); ++f)
      if(piece_of_face[f] == piece)
        faces.push_back(f);
    const auto [sources, sinks] = layers_to_separate(disk, piece_of_face, in_piece);
    const int new_piece = 1 + *std::max_element(piece_of_face.begin(), piece_of_face.end());
    for(int f : source_side_of_minimum_cut(disk, piece_of_face, faces, sources, sinks))
      piece_of_face[f] = new_piece;
    connected_pieces(disk, piece_of_face);
    pairs.clear();
    for(const auto& pair : all_pairs)
      if(piece_of_face[pair.first] == piece_of_face[pair.second])
        pairs.push_back(pair);
  }
  join_pieces_that_do_not_overlap(disk, all_pairs, piece_of_face);
  remaining = static_cast<int>(pairs.size());
  return piece_of_face;
}

} // namespace overlaps
} // namespace internal

/// Cuts the chart `cut` (the cut mesh of `surface`, laid out as `uv`, one UV per wedge) into
/// pieces none of which overlaps itself, and places the pieces side by side. `cut` and `uv`
/// are rewritten: every wedge whose faces end in different pieces is split, the separating
/// surface edges become seams (`disk_edges`), and each piece keeps its shape. At most
/// `max_cuts` cuts are made; what still overlaps then is counted in the result.
inline Overlap_removal remove_overlaps(const internal::Mesh_index& surface, Cut_mesh& cut, std::vector<Uv>& uv,
                                       int max_cuts = 64)
{
  using namespace internal;
  Overlap_removal result;
  const Mesh_index& disk = cut.disk;
  std::vector<int> piece_of_face = overlaps::pieces_without_overlaps(disk, uv, max_cuts, result.overlapping_face_pairs);
  result.pieces = 1 + *std::max_element(piece_of_face.begin(), piece_of_face.end());
  if(result.pieces == 1)
    return result;

  // One wedge per (wedge, piece).
  Cut_mesh split;
  std::map<std::pair<int, int>, int> wedge_of;
  std::vector<Uv> split_uv;
  std::vector<int> piece_of_wedge;
  split.disk.faces.resize(disk.number_of_faces());
  for(int f = 0; f < disk.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int w = disk.faces[f][c];
      const auto [it, added] = wedge_of.emplace(std::make_pair(w, piece_of_face[f]), static_cast<int>(split_uv.size()));
      if(added)
      {
        split.disk.points.push_back(disk.points[w]);
        split.surface_vertex.push_back(cut.surface_vertex[w]);
        split_uv.push_back(uv[w]);
        piece_of_wedge.push_back(piece_of_face[f]);
      }
      split.disk.faces[f][c] = it->second;
    }
  const Status built = build_connectivity(split.disk);
  split.status = cut.status;
  if(!built.ok())
    split.status = built.within("the pieces of an overlapping chart: ");

  // Disk edges keep their surface edge; a surface edge has two disk edges on every seam.
  split.surface_edge.assign(split.disk.number_of_edges(), -1);
  for(int f = 0; f < disk.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
      split.surface_edge[split.disk.face_edges[f][c]] = cut.surface_edge[disk.face_edges[f][c]];
  split.disk_edges.assign(surface.number_of_edges(), {-1, -1});
  for(int e = 0; e < split.disk.number_of_edges(); ++e)
  {
    const int s = split.surface_edge[e];
    const bool first_side = split.disk.edge_faces[e][0] == surface.edge_faces[s][0] ||
                            split.disk.edge_faces[e][1] == surface.edge_faces[s][0];
    if(split.disk.edge_faces[e][1] >= 0)
      split.disk_edges[s][0] = e; // off the cut: one disk edge for both faces
    else
      split.disk_edges[s][first_side ? 0 : 1] = e;
  }
  for(int s = 0; s < surface.number_of_edges(); ++s)
    if(cut.disk_edges[s][1] < 0 && split.disk_edges[s][1] >= 0)
      ++result.cut_edges;

  // The pieces side by side, each with its own UVs.
  std::vector<Chart_box> boxes(result.pieces, Chart_box{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  for(std::size_t w = 0; w < split_uv.size(); ++w)
  {
    Chart_box& b = boxes[piece_of_wedge[w]];
    b = {std::min(b[0], split_uv[w][0]), std::min(b[1], split_uv[w][1]), std::max(b[2], split_uv[w][0]),
         std::max(b[3], split_uv[w][1])};
  }
  const std::vector<Uv> offsets = shelf_pack(boxes);
  for(std::size_t w = 0; w < split_uv.size(); ++w)
    split_uv[w] = {split_uv[w][0] + offsets[piece_of_wedge[w]][0], split_uv[w][1] + offsets[piece_of_wedge[w]][1]};
  cut = std::move(split);
  uv = std::move(split_uv);
  return result;
}

} // namespace ICM

#endif // ICM_LAYOUT_OVERLAP_REMOVAL_H
