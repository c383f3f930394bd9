// Copyright (c) the ICM authors.
//
// Cones and seams from a CGAL selection file (`*.selection.txt`, as CGAL's Seam_mesh examples
// and the Polyhedron demo write it): the first line lists selected vertices, the second
// selected faces, the third and any later lines the selected edges as pairs of vertex
// indices, a vertex's index being its position in `vertices(mesh)`. CGAL's Seam_mesh
// examples read the edges as seams (`Seam_mesh::add_seams`, which throws on an index out of
// range and skips a pair that is not an edge without a word); its orbifold examples read the
// first line as cones (`read_cones`, from a file that may have no other line).
// `read_selection` reads both; every value is checked and what is wrong is named.

#ifndef ICM_IO_READ_SEAM_SELECTION_H
#define ICM_IO_READ_SEAM_SELECTION_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <boost/graph/graph_traits.hpp>

#include <charconv>
#include <algorithm>
#include <fstream>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace ICM {
// Not in IO::internal: a header that names `internal::` from inside ICM::IO means ICM's.
namespace internal {

/// The vertex indices of one line of a selection file, each checked to name a vertex of the
/// mesh (see `read_selection`); false with `error` naming the line and the value at fault.
template <class VertexLists>
bool read_selection_line(const std::string& path, const std::string& line, int line_number, const VertexLists& by_index,
                         std::vector<std::size_t>& indices, std::string& error)
{
  indices.clear();
  const std::string where = "seam file '" + path + "', line " + std::to_string(line_number);
  const char* p = line.data();
  const char* const end = line.data() + line.size();
  for(int value = 1;; ++value)
  {
    while(p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
      ++p;
    if(p == end)
      return true;
    std::size_t index = 0;
    const std::from_chars_result r = std::from_chars(p, end, index);
    const char* const after = r.ptr;
    if(r.ec != std::errc() || (after < end && *after != ' ' && *after != '\t' && *after != '\r'))
    {
      const char* token_end = p;
      while(token_end < end && *token_end != ' ' && *token_end != '\t')
        ++token_end;
      error =
        where + ", value " + std::to_string(value) + ": '" + std::string(p, token_end) + "' is not a vertex index";
      return false;
    }
    if(index >= by_index.size())
    {
      error = where + ": vertex " + std::to_string(index) + " out of range (the mesh has " +
              std::to_string(by_index.size()) + " vertices)";
      return false;
    }
    if(by_index[index].empty())
    {
      error = where + ": vertex " + std::to_string(index) + " is in no face of the mesh";
      return false;
    }
    p = after;
    indices.push_back(index);
  }
}

/// The cones of the first line: each index once, one interior vertex of the mesh each (a cone
/// on a split non-manifold vertex would be on one of its copies, which the file cannot say).
template <class TriangleMesh>
bool selection_cones(
  const std::string& path, const TriangleMesh& mesh, const std::vector<std::size_t>& indices,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>>& by_index,
  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& cones, std::string& error)
{
  const std::string where = "seam file '" + path + "', line 1: vertex ";
  std::set<std::size_t> read;
  for(std::size_t index : indices)
  {
    const std::string why =
      by_index[index].size() > 1 ? " is non-manifold and was split into " + std::to_string(by_index[index].size()) +
                                     " vertices (which one is the cone?)"
      : CGAL::is_border(by_index[index].front(), mesh) ? " is on the border (a cone is an interior vertex)"
                                                       : std::string();
    if(!why.empty())
    {
      error = where + std::to_string(index) + why;
      return false;
    }
    if(read.insert(index).second)
      cones.push_back(by_index[index].front());
  }
  return true;
}

/// The edges of the third and later lines: pairs of indices (a pair may straddle two lines),
/// each an edge of the mesh, each edge once.
template <class TriangleMesh>
bool selection_edges(
  const std::string& path, std::istream& in, const TriangleMesh& mesh,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>>& by_index,
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams, std::string& error)
{
  std::string line;
  std::vector<std::size_t> indices, ends;             // the line's, the pending pair
  std::set<std::pair<std::size_t, std::size_t>> read; // to keep each edge once
  for(int line_number = 3; std::getline(in, line); ++line_number)
  {
    if(!read_selection_line(path, line, line_number, by_index, indices, error))
      return false;
    for(std::size_t index : indices)
    {
      ends.push_back(index);
      if(ends.size() < 2)
        continue;
      typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h;
      bool found = false;
      for(auto a : by_index[ends[0]])
        for(auto b : by_index[ends[1]])
          if(!found)
            std::tie(h, found) = halfedge(a, b, mesh);
      if(!found)
      {
        error = "seam file '" + path + "', line " + std::to_string(line_number) + ": vertices " +
                std::to_string(ends[0]) + " and " + std::to_string(ends[1]) + " are not joined by an edge";
        return false;
      }
      if(read.insert(std::minmax(ends[0], ends[1])).second)
        seams.push_back(edge(h, mesh));
      ends.clear();
    }
  }
  if(!ends.empty())
  {
    error = "seam file '" + path + "' has an odd number of vertex indices (edges are pairs)";
    return false;
  }
  return true;
}

/// One vertex per index: the index is the vertex's position in `vertices(mesh)`.
template <class TriangleMesh>
std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>>
vertices_by_position(const TriangleMesh& mesh)
{
  std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>> by_index;
  by_index.reserve(num_vertices(mesh));
  for(auto v : vertices(mesh))
    by_index.push_back({v});
  return by_index;
}

} // namespace internal

namespace IO {

/// Reads the cones and the seam edges of `mesh` from the CGAL selection file `path`: the
/// vertices of its first line become `cones` (CGAL's orbifold examples give their cones so,
/// in a file that may have no other line), the edges of its third and later lines `seams`
/// (as CGAL's Seam_mesh examples give them), each once, in the file's order; the second line
/// (faces) is not read. Returns false with `error` naming the line and value at fault when
/// the file cannot be read, a value is not a vertex index of the mesh, a cone is a border or
/// split vertex, a pair is not an edge of the mesh, the count of edge values is odd, or the
/// file names neither a vertex nor an edge.
///
/// `by_index[i]` are the vertices of the mesh that the file's index `i` names: one each when
/// the indices are positions in `vertices(mesh)`, none or several when the mesh was repaired
/// after reading (a dropped isolated vertex, a split non-manifold one: see
/// `Mesh_reading_report::file_vertex`); a pair names the edge between any of its vertices.
template <class TriangleMesh>
bool read_selection(
  const std::string& path, const TriangleMesh& mesh,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>>& by_index,
  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& cones,
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams, std::string& error)
{
  cones.clear();
  seams.clear();
  std::ifstream in(path);
  if(!in)
  {
    error = "cannot open seam file '" + path + "'";
    return false;
  }
  std::string line;
  std::vector<std::size_t> indices;
  if(std::getline(in, line) && !(ICM::internal::read_selection_line(path, line, 1, by_index, indices, error) &&
                                 ICM::internal::selection_cones(path, mesh, indices, by_index, cones, error)))
    return false;
  std::getline(in, line); // the faces
  if(!ICM::internal::selection_edges(path, in, mesh, by_index, seams, error))
    return false;
  if(cones.empty() && seams.empty())
  {
    error =
      "seam file '" + path + "' names no vertex (first line: cones) and no edge (third line on: seams) of the mesh";
    return false;
  }
  return true;
}

/// Reads the seam edges of `mesh` from the CGAL selection file `path` into `seams` (in the
/// file's order, each edge once), as CGAL's `Seam_mesh::add_seams` does: the first two lines
/// are not read. Returns false with `error` naming the line and value at fault when the file
/// cannot be read or has no third line, a value is not a vertex index of the mesh, a pair is
/// not an edge of the mesh, the count of values is odd, or the file names no edge at all.
/// `by_index` as for `read_selection`, which also reads the first line's cones.
template <class TriangleMesh>
bool read_seam_selection(
  const std::string& path, const TriangleMesh& mesh,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>>& by_index,
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams, std::string& error)
{
  seams.clear();
  std::ifstream in(path);
  if(!in)
  {
    error = "cannot open seam file '" + path + "'";
    return false;
  }
  std::string line;
  for(int skipped = 0; skipped < 2; ++skipped)
    if(!std::getline(in, line))
    {
      error = "seam file '" + path +
              "' has no third line (a CGAL selection file lists the selected "
              "vertices, faces, then edges as pairs of vertex indices, one line each)";
      return false;
    }
  if(!ICM::internal::selection_edges(path, in, mesh, by_index, seams, error))
    return false;
  if(seams.empty())
  {
    error = "seam file '" + path + "' names no edge of the mesh";
    return false;
  }
  return true;
}

/// Reads cones and seams whose vertex indices are positions in `vertices(mesh)` (see the
/// overload with `by_index`).
template <class TriangleMesh>
bool read_selection(const std::string& path, const TriangleMesh& mesh,
                    std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& cones,
                    std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams, std::string& error)
{
  return read_selection(path, mesh, ICM::internal::vertices_by_position(mesh), cones, seams, error);
}

/// Reads seams whose vertex indices are positions in `vertices(mesh)` (see the overload
/// with `by_index`).
template <class TriangleMesh>
bool read_seam_selection(const std::string& path, const TriangleMesh& mesh,
                         std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams,
                         std::string& error)
{
  return read_seam_selection(path, mesh, ICM::internal::vertices_by_position(mesh), seams, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_READ_SEAM_SELECTION_H
