// The surface cut open along given seams (step 6's second half, after cut/Cut_graph.h has
// chosen them):
// - `check_cut_graph`: the seams must leave one disk and touch every cone;
// - `cut_mesh` splits every vertex on the cut into its wedges (one copy per side) and indexes
//   the disk, keeping face ids and corner order, so corner (f, c) of the disk is corner (f, c)
//   of the surface;
// - `match_wedges` pairs the wedges of two triangulations cut along the same seams.
// No exceptions: each result carries a status with the human reason.

#ifndef ICM_CUT_CUT_MESH_H
#define ICM_CUT_CUT_MESH_H

#include <ICM/Status.h>
#include <ICM/internal/Mesh_index.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace ICM {

/// The surface cut open along its seams, as a mesh of its own.
/// Faces are the surface's faces with the same ids and corner order; a disk vertex is a
/// wedge, one side of a surface vertex: the corner (f, c) lies on wedge `disk.faces[f][c]`.
/// A vertex off the cut keeps its id (wedges `0 .. n-1` are the surface vertices' first
/// wedges), the extra sides of vertices on the cut are numbered from n on.
struct Cut_mesh
{
  internal::Mesh_index disk;
  std::vector<int> surface_vertex; ///< disk vertex (wedge) -> surface vertex
  std::vector<int> surface_edge;   ///< disk edge -> surface edge
  /// surface edge -> its disk edges: the side in `edge_faces[e][0]`, then the side in
  /// `edge_faces[e][1]` on a seam edge (-1 off the cut, where one disk edge serves both faces)
  std::vector<std::array<int, 2>> disk_edges;
  Status status;
  bool ok() const { return status.ok(); }
};

namespace internal {
/// The helpers of the cut, in their own namespace: names such as `Union_find` are common
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

inline bool is_surface_border_edge(const Mesh_index& index, int e)
{
  return index.edge_faces[e][1] < 0;
}

/// A seam edge whose two ends are interior and on no other seam edge: its two sides would
/// join the same two wedges, a two-edge border no triangle mesh can hold.
inline int find_lone_seam_edge(const Mesh_index& index, const std::vector<char>& is_seam,
                               const std::vector<int>& degree)
{
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    if(is_seam[e] && degree[a] == 1 && degree[b] == 1 && !index.is_boundary_vertex[a] && !index.is_boundary_vertex[b])
      return e;
  }
  return -1;
}

/// The sides of the surface vertices once cut: two corners of a vertex in the two faces of an
/// uncut interior edge lie on one wedge. Around each vertex this is the walk along its fan
/// that starts a new wedge at every seam or border edge, done for all vertices at once.
struct Wedges
{
  std::vector<std::array<int, 3>> of_corner; ///< wedge of corner (f, c)
  std::vector<int> surface_vertex;           ///< wedge -> surface vertex
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
  int euler_characteristic = 0; // of all pieces together
  /// Genus of the cut surface (meaningful for one piece): chi = 2 - 2g - b.
  int genus() const { return (2 - euler_characteristic - boundary_loops) / 2; }
};

inline Cut_topology cut_topology(const Mesh_index& index, const std::vector<char>& is_seam, const Wedges& wedges)
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
    return Status::wrong_parameter("the cone flags have " + std::to_string(is_cone.size()) + " entries, the mesh has " +
                                   std::to_string(index.number_of_vertices()) + " vertices");
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
      return not_a_disk("a seam edge is a border edge: " + describe_seam_edge(index, e) + " is on the border already");

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
    return not_a_disk(
      "the seams leave genus " + std::to_string(topology.genus()) +
      (topology.boundary_loops > 1 ? " and " + plural(topology.boundary_loops, "boundary loop") : std::string()) +
      " (a disk has genus 0 and one boundary loop)");
  if(topology.boundary_loops > 1)
    return not_a_disk("the seams leave " + plural(topology.boundary_loops, "boundary loop") +
                      " (a disk has one): they must join every border");
  return {};
}

namespace internal {
namespace cutting {

/// The surface's elimination order carried to its wedges: ranked by their vertex's rank, the
/// copies of one vertex side by side (empty when the surface has no order).
inline std::vector<int> wedge_elimination_rank(const Mesh_index& index, const std::vector<int>& surface_vertex)
{
  if(index.elimination_rank.empty())
    return {};
  const int n = static_cast<int>(surface_vertex.size());
  std::vector<int> by_rank(n);
  std::iota(by_rank.begin(), by_rank.end(), 0);
  std::stable_sort(by_rank.begin(), by_rank.end(), [&](int a, int b) {
    return index.elimination_rank[surface_vertex[a]] < index.elimination_rank[surface_vertex[b]];
  });
  std::vector<int> rank(n);
  for(int r = 0; r < n; ++r)
    rank[by_rank[r]] = r;
  return rank;
}

} // namespace cutting
} // namespace internal

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
  cut.disk.elimination_rank = internal::cutting::wedge_elimination_rank(index, wedges.surface_vertex);
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

#endif // ICM_CUT_CUT_MESH_H
