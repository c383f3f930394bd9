// Copyright (c) the ICM authors.
//
// The outputs of a parameterization written together, all or nothing: the UV'd OBJ and the
// SVG of its layout each go to a temporary file, and both replace their targets only once
// both were written (internal/Atomic_file.h). A failing SVG therefore never leaves a new
// OBJ beside the user's old SVG, nor the other way round.

#ifndef ICM_IO_WRITE_UV_FILES_H
#define ICM_IO_WRITE_UV_FILES_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/internal/Atomic_file.h>

#include <string>
#include <vector>

namespace ICM {
namespace IO {

/// Writes `m` as OBJ to `obj_path` and, when `svg_path` is not empty, its layout as SVG to
/// `svg_path`, all or nothing. Refused before anything is written: an invalid mesh or SVG
/// option, the two paths naming one file, a target that is read-only or not a regular file.
/// On failure no target changes, no temporary remains, `error` names the file and the
/// reason, and the function returns false.
inline bool write_uv_files(const std::string& obj_path, const std::string& svg_path, const Uv_mesh& m,
                           std::string& error, const Svg_options& svg_options = Svg_options())
{
  std::string invalid;
  if(!is_valid_uv_mesh(m, invalid))
  {
    error = "cannot write '" + obj_path + "': " + invalid;
    return false;
  }
  if(!svg_path.empty() && !internal::check_svg_options(svg_options, invalid))
  {
    error = "cannot write '" + svg_path + "': " + invalid;
    return false;
  }
  std::vector<internal::Atomic_output> outputs;
  outputs.push_back({obj_path, [&m](std::ostream& os) { return write_uv_obj(os, m); }});
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
