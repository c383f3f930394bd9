// Copyright (c) the ICM authors.
//
// glTF 2.0 output of a parameterized mesh (.gltf, its buffer embedded as base64, or binary
// .glb), serialized by tinygltf. A glTF vertex has one value per attribute, so a vertex on a
// seam becomes one glTF vertex per side (per distinct UV), each with the same position:
// what a renderer needs, at the price of the connectivity across seams, which the OBJ and
// PLY outputs keep.
//
// Needs tinygltf: this header includes <tiny_gltf.h>, and the program links its
// implementation (Debian: libtinygltf-dev, CMake target TinyGLTF::TinyGLTF; ICM's CMake
// package links it into ICM::ICM when found and defines ICM_HAS_TINYGLTF).

#ifndef ICM_IO_WRITE_UV_GLTF_H
#define ICM_IO_WRITE_UV_GLTF_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/internal/Atomic_file.h>
#include <ICM/IO/Float32_output.h>

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {

/// The mesh as glTF wants it: one vertex per distinct (position, UV) pair of a corner, in
/// the order the faces first reach them, and three indices per face into those vertices.
struct Gltf_vertices
{
  std::vector<std::array<int, 2>> corners; ///< per glTF vertex: position index, UV index
  std::vector<std::uint32_t> indices;      ///< three per face
};

inline Gltf_vertices split_at_seams(const IO::Uv_mesh& m)
{
  Gltf_vertices out;
  std::map<std::array<int, 2>, std::uint32_t> index;
  out.indices.reserve(3 * m.number_of_faces());
  for(std::size_t f = 0; f < m.number_of_faces(); ++f)
    for(int k = 0; k < 3; ++k)
    {
      const std::array<int, 2> corner{{m.face_positions[f][k], m.face_uvs[f][k]}};
      const auto inserted = index.emplace(corner, static_cast<std::uint32_t>(out.corners.size()));
      if(inserted.second)
        out.corners.push_back(corner);
      out.indices.push_back(inserted.first->second);
    }
  return out;
}

/// Appends a tightly packed buffer view of `bytes` to `model`'s only buffer; returns its index.
inline int add_buffer_view(tinygltf::Model& model, const std::vector<unsigned char>& bytes, int target)
{
  std::vector<unsigned char>& data = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size(); // a multiple of 4: every component is 4 bytes
  view.byteLength = bytes.size();
  view.target = target;
  data.insert(data.end(), bytes.begin(), bytes.end());
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

/// Appends an accessor of `count` elements of `type` over the whole buffer view `view`.
inline int add_accessor(tinygltf::Model& model, int view, int component_type, int type, std::size_t count)
{
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

/// The model of `m`: one buffer (positions, texture coordinates, indices), one mesh of one
/// triangle primitive, one node, one scene.
///
/// TEXCOORD_0 is (u, 1 - v): glTF puts the texture's origin at its top left corner, OBJ and
/// PLY at its bottom left, so the same image maps the same way in every output (importers
/// such as Blender's flip v back).
/// \pre `m` is valid, has faces, and its coordinates fit in a float.
inline tinygltf::Model gltf_model(const IO::Uv_mesh& m)
{
  const Gltf_vertices split = split_at_seams(m);
  std::vector<unsigned char> positions, texcoords, indices;
  positions.reserve(12 * split.corners.size());
  texcoords.reserve(8 * split.corners.size());
  std::vector<double> low(3, (std::numeric_limits<double>::max)()), high(3, std::numeric_limits<double>::lowest());
  for(const std::array<int, 2>& corner : split.corners)
  {
    for(int k = 0; k < 3; ++k)
    {
      const float x = static_cast<float>(m.positions[corner[0]][k]);
      append_little_endian(positions, x);
      low[k] = (std::min)(low[k], static_cast<double>(x)); // POSITION's bounds are required, as stored
      high[k] = (std::max)(high[k], static_cast<double>(x));
    }
    const std::array<double, 2>& uv = m.uvs[corner[1]];
    append_little_endian(texcoords, static_cast<float>(uv[0]));
    append_little_endian(texcoords, static_cast<float>(1. - uv[1]));
  }
  indices.reserve(4 * split.indices.size());
  for(std::uint32_t i : split.indices)
    append_little_endian(indices, i);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "ICM";
  model.buffers.resize(1);
  const int position_view = add_buffer_view(model, positions, TINYGLTF_TARGET_ARRAY_BUFFER);
  const int texcoord_view = add_buffer_view(model, texcoords, TINYGLTF_TARGET_ARRAY_BUFFER);
  const int index_view = add_buffer_view(model, indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] =
    add_accessor(model, position_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, split.corners.size());
  model.accessors.back().minValues = low;
  model.accessors.back().maxValues = high;
  primitive.attributes["TEXCOORD_0"] =
    add_accessor(model, texcoord_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, split.corners.size());
  primitive.indices =
    add_accessor(model, index_view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, split.indices.size());

  tinygltf::Mesh mesh;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

} // namespace internal

namespace IO {

/// Why `m` cannot be written as glTF, or empty: an invalid mesh, a mesh without faces (a
/// glTF accessor has at least one element), a coordinate beyond the range of a float, or
/// more corners than 32-bit indices reach.
inline std::string why_not_gltf(const Uv_mesh& m)
{
  std::string invalid;
  if(!is_valid_uv_mesh(m, invalid))
    return invalid;
  if(m.number_of_faces() == 0)
    return "the mesh has no faces, and glTF has no empty mesh";
  if(3 * m.number_of_faces() > (std::numeric_limits<std::uint32_t>::max)())
    return "the mesh has more corners than glTF's 32-bit indices reach";
  return internal::why_not_float32(m, "glTF");
}

/// Writes `m` to `os` as glTF 2.0: JSON with the buffer embedded as a base64 data URI, or
/// with `binary` a GLB (the JSON and the buffer in one binary container). One triangle
/// primitive with POSITION, TEXCOORD_0 (u, 1 - v: glTF's texture origin is at the top) and
/// 32-bit indices; a vertex on a seam is one glTF vertex per UV. Coordinates are floats.
/// Returns whether the stream is still good.
/// \pre `why_not_gltf(m)` is empty.
/// \pre a binary `os` is in binary mode where that matters (Windows).
inline bool write_uv_gltf(std::ostream& os, const Uv_mesh& m, bool binary = false)
{
  const tinygltf::Model model = internal::gltf_model(m);
  tinygltf::TinyGLTF gltf;
  return gltf.WriteGltfSceneToStream(&model, os, /* prettyPrint = */ !binary, binary) && os;
}

/// Writes `m` to the glTF file `path` (see the stream overload for the format; `binary` for
/// a .glb), replacing it atomically: on any failure `path` is left untouched, no temporary
/// file remains, `error` gets a one-line reason and the function returns false.
inline bool write_uv_gltf(const std::string& path, const Uv_mesh& m, std::string& error, bool binary = false)
{
  const std::string refused = why_not_gltf(m);
  if(!refused.empty())
  {
    error = "cannot write '" + path + "': " + refused;
    return false;
  }
  return internal::write_file_atomically(
    path, [&m, binary](std::ostream& os) { return write_uv_gltf(os, m, binary); }, error);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_GLTF_H
