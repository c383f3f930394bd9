// Copyright (c) the ICM authors.
//
// Seams from a CGAL selection file (`*.selection.txt`, as CGAL's Seam_mesh examples and the
// Polyhedron demo write it): the first line lists selected vertices, the second selected
// faces, the third and any later lines the selected edges as pairs of vertex indices, a
// vertex's index being its position in `vertices(mesh)`. CGAL's own reader
// (`Seam_mesh::add_seams`) throws on an index out of range and skips a pair that is not an
// edge without a word; this one checks every value and names what is wrong.

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
namespace IO {

/// Reads the seam edges of `mesh` from the CGAL selection file `path` into `seams` (in the
/// file's order, each edge once). Returns false with `error` naming the line and value at
/// fault when the file cannot be read, a value is not a vertex index of the mesh, a pair is
/// not an edge of the mesh, the count of values is odd, or the file names no edge at all.
///
/// `by_index[i]` are the vertices of the mesh that the file's index `i` names: one each when
/// the indices are positions in `vertices(mesh)`, none or several when the mesh was repaired
/// after reading (a dropped isolated vertex, a split non-manifold one: see
/// `Mesh_reading_report::file_vertex`); a pair names the edge between any of its vertices.
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

  std::vector<std::size_t> ends;                      // pending pair
  std::set<std::pair<std::size_t, std::size_t>> read; // to keep each edge once
  int line_number = 2;
  while(std::getline(in, line))
  {
    ++line_number;
    const char* p = line.data();
    const char* const end = line.data() + line.size();
    for(int value = 1;; ++value)
    {
      while(p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
        ++p;
      if(p == end)
        break;
      std::size_t index = 0;
      const std::from_chars_result r = std::from_chars(p, end, index);
      const char* const after = r.ptr;
      if(r.ec != std::errc() || (after < end && *after != ' ' && *after != '\t' && *after != '\r'))
      {
        const char* token_end = p;
        while(token_end < end && *token_end != ' ' && *token_end != '\t')
          ++token_end;
        error = "seam file '" + path + "', line " + std::to_string(line_number) + ", value " + std::to_string(value) +
                ": '" + std::string(p, token_end) + "' is not a vertex index";
        return false;
      }
      if(index >= by_index.size())
      {
        error = "seam file '" + path + "', line " + std::to_string(line_number) + ": vertex " + std::to_string(index) +
                " out of range (the mesh has " + std::to_string(by_index.size()) + " vertices)";
        return false;
      }
      if(by_index[index].empty())
      {
        error = "seam file '" + path + "', line " + std::to_string(line_number) + ": vertex " + std::to_string(index) +
                " is in no face of the mesh";
        return false;
      }
      p = after;
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
  if(seams.empty())
  {
    error = "seam file '" + path + "' names no edge of the mesh";
    return false;
  }
  return true;
}

/// Reads seams whose vertex indices are positions in `vertices(mesh)` (see the overload
/// with `by_index`).
template <class TriangleMesh>
bool read_seam_selection(const std::string& path, const TriangleMesh& mesh,
                         std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& seams,
                         std::string& error)
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  std::vector<std::vector<vertex_descriptor>> by_index;
  by_index.reserve(num_vertices(mesh));
  for(vertex_descriptor v : vertices(mesh))
    by_index.push_back({v});
  return read_seam_selection(path, mesh, by_index, seams, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_READ_SEAM_SELECTION_H
