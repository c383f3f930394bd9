// Copyright (c) the ICM authors.
//
// The outputs of a parameterization written together, all or nothing: the UV'd mesh (OBJ,
// PLY or glTF, by its extension: write_uv_mesh.h) and its pictures (the layout as SVG or PNG,
// the textured surface as PNG) each go to a temporary file, and all replace their targets
// only once all were written (internal/Atomic_file.h). A failing picture therefore never
// leaves a new mesh beside the user's old pictures, nor the other way round.

#ifndef ICM_IO_WRITE_UV_FILES_H
#define ICM_IO_WRITE_UV_FILES_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_mesh.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/internal/Atomic_file.h>
#ifdef ICM_HAS_STB_IMAGE_WRITE
#include <ICM/IO/write_uv_png.h>
#endif

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace ICM {
namespace IO {

/// The pictures written beside a UV'd mesh by `write_uv_files()`; an empty path writes none.
struct Uv_pictures
{
  std::string svg;     ///< the layout, as SVG (`write_uv_svg()`)
  std::string png;     ///< the layout, as PNG (`write_uv_png()`; needs ICM_HAS_STB_IMAGE_WRITE)
  std::string preview; ///< the surface with a checkerboard, as PNG (`write_uv_preview_png()`)
  Svg_options svg_options;
#ifdef ICM_HAS_STB_IMAGE_WRITE
  Png_options png_options;
  Preview_options preview_options;
#endif
};

/// Writes `m` to `mesh_path` in the format its extension names (.obj, .ply, .gltf, .glb:
/// `write_uv_mesh()`) and the `pictures` whose paths are not empty, all or nothing. Refused
/// before anything is written: an extension that names no format, an invalid mesh or one the
/// format cannot hold, an invalid picture option, a PNG without stb_image_write, a target
/// that is read-only or not a regular file. On failure no target changes, no temporary
/// remains, `error` names the file and the reason, and the function returns false.
inline bool write_uv_files(const std::string& mesh_path, const Uv_pictures& pictures, const Uv_mesh& m,
                           std::string& error, const Mesh_writing_options& mesh_options = Mesh_writing_options())
{
  const std::function<bool(std::ostream&)> mesh_writer = internal::uv_mesh_writer(mesh_path, m, mesh_options, error);
  if(!mesh_writer)
    return false;
  std::vector<internal::Atomic_output> outputs;
  outputs.push_back({mesh_path, mesh_writer});
  std::string invalid;
  const auto refuse = [&error, &invalid](const std::string& path) {
    error = "cannot write '" + path + "': " + invalid;
    return false;
  };
  if(!pictures.svg.empty())
  {
    if(!internal::check_svg_options(pictures.svg_options, invalid))
      return refuse(pictures.svg);
    outputs.push_back({pictures.svg, [&m, &pictures](std::ostream& os) {
                         std::string ignored;
                         return write_uv_svg(os, m, ignored, pictures.svg_options);
                       }});
  }
#ifdef ICM_HAS_STB_IMAGE_WRITE
  if(!pictures.png.empty())
  {
    if(!internal::check_png_options(pictures.png_options, invalid))
      return refuse(pictures.png);
    outputs.push_back({pictures.png, [&m, &pictures](std::ostream& os) {
                         return internal::put_layout_png(os, m, pictures.png_options);
                       }});
  }
  if(!pictures.preview.empty())
  {
    if(!internal::check_preview_options(pictures.preview_options, invalid))
      return refuse(pictures.preview);
    outputs.push_back({pictures.preview, [&m, &pictures](std::ostream& os) {
                         return internal::put_preview_png(os, m, pictures.preview_options);
                       }});
  }
#else
  invalid = "PNG pictures need stb_image_write (Debian: libstb-dev), which ICM was built without";
  if(!pictures.png.empty())
    return refuse(pictures.png);
  if(!pictures.preview.empty())
    return refuse(pictures.preview);
#endif
  return internal::write_files_atomically(outputs, error);
}

/// Writes `m` to `mesh_path` and, when `svg_path` is not empty, its layout as SVG, all or
/// nothing (`write_uv_files()` above with only an SVG picture).
inline bool write_uv_files(const std::string& mesh_path, const std::string& svg_path, const Uv_mesh& m,
                           std::string& error, const Svg_options& svg_options = Svg_options(),
                           const Mesh_writing_options& mesh_options = Mesh_writing_options())
{
  Uv_pictures pictures;
  pictures.svg = svg_path;
  pictures.svg_options = svg_options;
  return write_uv_files(mesh_path, pictures, m, error, mesh_options);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_FILES_H
