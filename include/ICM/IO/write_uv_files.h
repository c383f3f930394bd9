// Copyright (c) the ICM authors.
//
// The outputs of a parameterization written together, all or nothing: the UV'd mesh (OBJ,
// PLY or glTF, by its extension: write_uv_mesh.h) and the SVG of its layout each go to a
// temporary file, and both replace their targets only once both were written
// (internal/Atomic_file.h). A failing SVG therefore never leaves a new mesh beside the
// user's old SVG, nor the other way round.

#ifndef ICM_IO_WRITE_UV_FILES_H
#define ICM_IO_WRITE_UV_FILES_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_mesh.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/internal/Atomic_file.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace ICM {
namespace IO {

/// Writes `m` to `mesh_path` in the format its extension names (.obj, .ply, .gltf, .glb:
/// `write_uv_mesh()`) and, when `svg_path` is not empty, its layout as SVG to `svg_path`, all
/// or nothing. Refused before anything is written: an extension that names no format, an
/// invalid mesh or one the format cannot hold, an invalid SVG option, the two paths naming
/// one file, a target that is read-only or not a regular file. On failure no target changes,
/// no temporary remains, `error` names the file and the reason, and the function returns
/// false.
inline bool write_uv_files(const std::string& mesh_path, const std::string& svg_path, const Uv_mesh& m,
                           std::string& error, const Svg_options& svg_options = Svg_options(),
                           const Mesh_writing_options& mesh_options = Mesh_writing_options())
{
  const std::function<bool(std::ostream&)> mesh_writer = internal::uv_mesh_writer(mesh_path, m, mesh_options, error);
  if(!mesh_writer)
    return false;
  std::string invalid;
  if(!svg_path.empty() && !internal::check_svg_options(svg_options, invalid))
  {
    error = "cannot write '" + svg_path + "': " + invalid;
    return false;
  }
  std::vector<internal::Atomic_output> outputs;
  outputs.push_back({mesh_path, mesh_writer});
  if(!svg_path.empty())
    outputs.push_back({svg_path, [&m, &svg_options](std::ostream& os) {
                         std::string ignored;
                         return write_uv_svg(os, m, ignored, svg_options);
                       }});
  return internal::write_files_atomically(outputs, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_FILES_H
