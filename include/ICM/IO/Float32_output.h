// Copyright (c) the ICM authors.
//
// What the PLY and glTF writers share: both store 32-bit floats (PLY as readers expect them,
// glTF because the specification allows nothing else for positions), so a mesh is checked to
// fit in that range before anything is written, and the binary forms are little-endian
// whatever the machine's byte order, written byte by byte rather than by copying memory.

#ifndef ICM_IO_FLOAT32_OUTPUT_H
#define ICM_IO_FLOAT32_OUTPUT_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/Status.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <ios>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace ICM {
namespace internal {

/// Whether `x` becomes a finite float (a double beyond the largest float becomes infinite).
inline bool fits_float(double x)
{
  return std::isfinite(x) && std::abs(x) <= static_cast<double>((std::numeric_limits<float>::max)());
}

/// Why `m`'s coordinates cannot be stored as 32-bit floats, or empty: the first position or
/// UV beyond the largest float, named by its index as `is_valid_uv_mesh()` names them.
/// \pre `m` is valid (`is_valid_uv_mesh()`).
inline std::string why_not_float32(const IO::Uv_mesh& m, const char* format)
{
  auto beyond = [format](const std::string& what, double x) {
    return what + " has a coordinate (" + message_number(x, 3) + ") beyond the range of the 32-bit floats " + format +
           " stores (scale the mesh down)";
  };
  for(std::size_t i = 0; i < m.positions.size(); ++i)
    for(double x : m.positions[i])
      if(!fits_float(x))
        return beyond("position " + std::to_string(i), x);
  for(std::size_t i = 0; i < m.uvs.size(); ++i)
    for(double x : m.uvs[i])
      if(!fits_float(x))
        return beyond("UV " + std::to_string(i), x);
  return {};
}

inline std::uint32_t float_bits(float x)
{
  static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "PLY and glTF need IEEE 754 floats");
  std::uint32_t bits;
  std::memcpy(&bits, &x, 4);
  return bits;
}

/// Appends `x` to `bytes`, least significant byte first.
inline void append_little_endian(std::vector<unsigned char>& bytes, std::uint32_t x)
{
  for(int k = 0; k < 4; ++k)
    bytes.push_back(static_cast<unsigned char>((x >> (8 * k)) & 0xffu));
}

inline void append_little_endian(std::vector<unsigned char>& bytes, float x)
{
  append_little_endian(bytes, float_bits(x));
}

/// Writes `x` to `os`, least significant byte first.
inline void put_little_endian(std::ostream& os, std::uint32_t x)
{
  const char bytes[4] = {static_cast<char>(x & 0xffu), static_cast<char>((x >> 8) & 0xffu),
                         static_cast<char>((x >> 16) & 0xffu), static_cast<char>((x >> 24) & 0xffu)};
  os.write(bytes, 4);
}

inline void put_little_endian(std::ostream& os, float x)
{
  put_little_endian(os, float_bits(x));
}

} // namespace internal
} // namespace ICM

#endif // ICM_IO_FLOAT32_OUTPUT_H
