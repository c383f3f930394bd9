// Copyright (c) the ICM authors.
//
// Stanford PLY output of a parameterized mesh, ASCII or binary little-endian. PLY has one
// index per corner, so a vertex on a seam cannot take one UV per side as a vertex property:
// the UVs go on the faces instead, as a `texcoord` list of six floats (u, v per corner), the
// property MeshLab writes for wedge texture coordinates and PLY readers look for. Positions
// are vertices, shared across seams, so the mesh stays connected in the file.

#ifndef ICM_IO_WRITE_UV_PLY_H
#define ICM_IO_WRITE_UV_PLY_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/internal/Atomic_file.h>
#include <ICM/IO/Float32_output.h>

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace ICM {
namespace internal {

inline void put_ply_header(std::ostream& os, const IO::Uv_mesh& m, bool binary)
{
  os << "ply\n"
     << (binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n") << "comment written by ICM\n"
     << "element vertex " << m.positions.size() << "\n"
     << "property float x\nproperty float y\nproperty float z\n"
     << "element face " << m.number_of_faces() << "\n"
     << "property list uchar int vertex_indices\n"
     << "property list uchar float texcoord\n"
     << "end_header\n";
}

inline void put_ply_ascii_body(std::ostream& os, const IO::Uv_mesh& m)
{
  for(std::size_t i = 0; i < m.positions.size() && os; ++i)
  {
    const auto& p = m.positions[i];
    for(int k = 0; k < 3; ++k)
    {
      put_exact_number(os, static_cast<float>(p[k]));
      os << (k < 2 ? ' ' : '\n');
    }
  }
  for(std::size_t f = 0; f < m.number_of_faces() && os; ++f)
  {
    const auto& p = m.face_positions[f];
    os << "3 " << p[0] << ' ' << p[1] << ' ' << p[2] << " 6";
    for(int k = 0; k < 3; ++k)
    {
      const auto& t = m.uvs[m.face_uvs[f][k]];
      os << ' ';
      put_exact_number(os, static_cast<float>(t[0]));
      os << ' ';
      put_exact_number(os, static_cast<float>(t[1]));
    }
    os << '\n';
  }
}

inline void put_ply_binary_body(std::ostream& os, const IO::Uv_mesh& m)
{
  for(std::size_t i = 0; i < m.positions.size() && os; ++i)
    for(double x : m.positions[i])
      put_little_endian(os, static_cast<float>(x));
  for(std::size_t f = 0; f < m.number_of_faces() && os; ++f)
  {
    os.put(3);
    for(int p : m.face_positions[f])
      put_little_endian(os, static_cast<std::uint32_t>(p)); // two's complement of a non-negative int
    os.put(6);
    for(int t : m.face_uvs[f])
      for(double x : m.uvs[t])
        put_little_endian(os, static_cast<float>(x));
  }
}

} // namespace internal

namespace IO {

/// Writes `m` to `os` as PLY: `element vertex` with float `x y z`, then `element face` with
/// `vertex_indices` (0-based) and the per-corner `texcoord` list (u0 v0 u1 v1 u2 v2), in
/// ASCII or, with `binary`, in binary little-endian. A seam is where two faces give one
/// vertex different texcoords. Coordinates are rounded to float, the shortest text that
/// reads back as that float in ASCII. Returns whether the stream is still good.
/// \pre `m` is valid (`is_valid_uv_mesh()`) and its coordinates fit in a float
///      (`internal::why_not_float32()` is empty).
/// \pre a binary `os` is in binary mode where that matters (Windows).
inline bool write_uv_ply(std::ostream& os, const Uv_mesh& m, bool binary = false)
{
  internal::put_ply_header(os, m, binary);
  if(binary)
    internal::put_ply_binary_body(os, m);
  else
    internal::put_ply_ascii_body(os, m);
  return static_cast<bool>(os);
}

/// Why `m` cannot be written as PLY, or empty: an invalid mesh, or a coordinate beyond
/// the range of a float.
inline std::string why_not_ply(const Uv_mesh& m)
{
  std::string invalid;
  if(!is_valid_uv_mesh(m, invalid))
    return invalid;
  return internal::why_not_float32(m, "PLY");
}

/// Writes `m` to the PLY file `path` (see the stream overload for the format), replacing it
/// atomically: on any failure (invalid mesh, a coordinate beyond a float, missing
/// directory, no permission, full disk) `path` is left untouched, no temporary file remains,
/// `error` gets a one-line reason and the function returns false.
inline bool write_uv_ply(const std::string& path, const Uv_mesh& m, std::string& error, bool binary = false)
{
  const std::string refused = why_not_ply(m);
  if(!refused.empty())
  {
    error = "cannot write '" + path + "': " + refused;
    return false;
  }
  return internal::write_file_atomically(
    path, [&m, binary](std::ostream& os) { return write_uv_ply(os, m, binary); }, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_PLY_H
