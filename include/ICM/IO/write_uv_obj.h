// Copyright (c) the ICM authors.
//
// Wavefront OBJ output of a parameterized mesh: positions, texture coordinates and faces that
// index both, so seams survive the round trip (CGAL's own OBJ writer has no `vt`).

#ifndef ICM_IO_WRITE_UV_OBJ_H
#define ICM_IO_WRITE_UV_OBJ_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/internal/Atomic_file.h>

#include <cstddef>
#include <ios>
#include <ostream>
#include <string>

namespace ICM {
namespace IO {

/// Writes `m` to `os` as OBJ: `v x y z`, `vt u v` and `f a/ta b/tb c/tc` lines (1-based),
/// every number in full precision, so that reading the file back gives the same doubles.
/// Returns whether the stream is still good.
/// \pre `m` is valid (`is_valid_uv_mesh()`).
inline bool write_uv_obj(std::ostream& os, const Uv_mesh& m)
{
  using internal::put_exact_number;
  os << "# written by ICM\n";
  os << "# " << m.positions.size() << " vertices, " << m.uvs.size() << " texture coordinates, " << m.number_of_faces()
     << " faces\n";
  for(std::size_t i = 0; i < m.positions.size() && os; ++i)
  {
    const auto& p = m.positions[i];
    os << "v ";
    put_exact_number(os, p[0]);
    os << ' ';
    put_exact_number(os, p[1]);
    os << ' ';
    put_exact_number(os, p[2]);
    os << '\n';
  }
  for(std::size_t i = 0; i < m.uvs.size() && os; ++i)
  {
    const auto& t = m.uvs[i];
    os << "vt ";
    put_exact_number(os, t[0]);
    os << ' ';
    put_exact_number(os, t[1]);
    os << '\n';
  }
  for(std::size_t f = 0; f < m.number_of_faces() && os; ++f)
  {
    const auto& p = m.face_positions[f];
    const auto& t = m.face_uvs[f];
    os << "f " << p[0] + 1 << '/' << t[0] + 1 << ' ' << p[1] + 1 << '/' << t[1] + 1 << ' ' << p[2] + 1 << '/'
       << t[2] + 1 << '\n';
  }
  return static_cast<bool>(os);
}

/// Writes `m` to the OBJ file `path` (see the stream overload for the format).
///
/// The file is replaced atomically: on any failure (invalid mesh, missing directory, no
/// permission, full disk) `path` is left untouched, no temporary file remains, `error` gets a
/// one-line reason and the function returns false. A mesh with out-of-range indices or
/// non-finite coordinates is refused rather than written as a file other tools cannot read.
inline bool write_uv_obj(const std::string& path, const Uv_mesh& m, std::string& error)
{
  std::string invalid;
  if(!is_valid_uv_mesh(m, invalid))
  {
    error = "cannot write '" + path + "': " + invalid;
    return false;
  }
  return internal::write_file_atomically(
    path, [&m](std::ostream& os) { return write_uv_obj(os, m); }, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_OBJ_H
