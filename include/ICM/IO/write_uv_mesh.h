// Copyright (c) the ICM authors.
//
// A parameterized mesh written in the format its file name's extension names: OBJ, PLY
// (ASCII or binary) or glTF (.gltf, .glb). Any other extension is refused rather than
// written as one of these under a name that promises another format; the check is separate
// (`why_uv_mesh_path_is_refused()`) so that a program can refuse the name before hours of
// work. glTF needs tinygltf, which ICM's CMake package links when found (ICM_HAS_TINYGLTF);
// without it .gltf and .glb are refused with that reason.

#ifndef ICM_IO_WRITE_UV_MESH_H
#define ICM_IO_WRITE_UV_MESH_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_ply.h>
#include <ICM/internal/Atomic_file.h>
#ifdef ICM_HAS_TINYGLTF
#include <ICM/IO/write_uv_gltf.h>
#endif

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

namespace ICM {
namespace IO {

/// The formats `write_uv_mesh()` writes.
enum class Uv_mesh_format
{
  Obj,  ///< Wavefront OBJ, `write_uv_obj()`
  Ply,  ///< Stanford PLY, `write_uv_ply()`
  Gltf, ///< glTF 2.0 JSON with an embedded buffer, `write_uv_gltf()`
  Glb   ///< binary glTF 2.0, `write_uv_gltf()`
};

/// How `write_uv_mesh()` and `write_uv_files()` write the mesh.
struct Mesh_writing_options
{
  /// PLY in binary little-endian rather than ASCII (smaller, faster to read; no effect on
  /// the other formats).
  bool binary_ply = false;
};

/// The format the extension of `path` names (.obj, .ply, .gltf, .glb, any case), or none.
inline std::optional<Uv_mesh_format> uv_mesh_format(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if(ext == ".obj")
    return Uv_mesh_format::Obj;
  if(ext == ".ply")
    return Uv_mesh_format::Ply;
  if(ext == ".gltf")
    return Uv_mesh_format::Gltf;
  if(ext == ".glb")
    return Uv_mesh_format::Glb;
  return std::nullopt;
}

/// Whether this build of ICM writes glTF (tinygltf was found: ICM_HAS_TINYGLTF).
constexpr bool writes_gltf()
{
#ifdef ICM_HAS_TINYGLTF
  return true;
#else
  return false;
#endif
}

/// Why `write_uv_mesh()` would refuse the file name `path` whatever the mesh, or empty: an
/// extension that names no format it writes, or glTF in a build without tinygltf.
inline std::string why_uv_mesh_path_is_refused(const std::string& path)
{
  const std::optional<Uv_mesh_format> format = uv_mesh_format(path);
  if(!format)
  {
    const std::string ext = std::filesystem::path(path).extension().string();
    return "cannot write '" + path + "': " + (ext.empty() ? "no extension" : "unknown extension '" + ext + "'") +
           " (writes .obj, .ply, .gltf and .glb)";
  }
  if((*format == Uv_mesh_format::Gltf || *format == Uv_mesh_format::Glb) && !writes_gltf())
    return "cannot write '" + path +
           "': this build of ICM writes no glTF (it needs tinygltf: Debian's libtinygltf-dev, found by CMake)";
  return {};
}

} // namespace IO

namespace internal {

/// The writer of `m` into a stream for the format of `path`, or an empty function with the
/// reason in `error` (a refused name, or a mesh the format cannot hold).
inline std::function<bool(std::ostream&)> uv_mesh_writer(const std::string& path, const IO::Uv_mesh& m,
                                                         const IO::Mesh_writing_options& options, std::string& error)
{
  error = IO::why_uv_mesh_path_is_refused(path);
  if(!error.empty())
    return {};
  std::string refused;
  std::function<bool(std::ostream&)> writer;
  switch(*IO::uv_mesh_format(path))
  {
  case IO::Uv_mesh_format::Obj:
    if(IO::is_valid_uv_mesh(m, refused))
      writer = [&m](std::ostream& os) { return IO::write_uv_obj(os, m); };
    break;
  case IO::Uv_mesh_format::Ply:
    refused = IO::why_not_ply(m);
    writer = [&m, binary = options.binary_ply](std::ostream& os) { return IO::write_uv_ply(os, m, binary); };
    break;
  case IO::Uv_mesh_format::Gltf:
  case IO::Uv_mesh_format::Glb:
#ifdef ICM_HAS_TINYGLTF
    refused = IO::why_not_gltf(m);
    writer = [&m, binary = *IO::uv_mesh_format(path) == IO::Uv_mesh_format::Glb](std::ostream& os) {
      return IO::write_uv_gltf(os, m, binary);
    };
#endif
    break;
  }
  if(!refused.empty())
  {
    error = "cannot write '" + path + "': " + refused;
    return {};
  }
  return writer;
}

} // namespace internal

namespace IO {

/// Writes `m` to `path` in the format its extension names (`uv_mesh_format()`): OBJ, PLY
/// (ASCII, or binary with `options.binary_ply`), glTF or GLB.
///
/// Refused before anything is written: an extension that names none of them (a `.off` is
/// not written as OBJ text), glTF without tinygltf, a mesh the format cannot hold (invalid,
/// a coordinate beyond a float for PLY and glTF, no faces for glTF). The file is replaced
/// atomically: on any failure `path` is left untouched, no temporary file remains, `error`
/// gets a one-line reason and the function returns false.
inline bool write_uv_mesh(const std::string& path, const Uv_mesh& m, std::string& error,
                          const Mesh_writing_options& options = Mesh_writing_options())
{
  const std::function<bool(std::ostream&)> writer = internal::uv_mesh_writer(path, m, options, error);
  return writer && internal::write_file_atomically(path, writer, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_MESH_H
