// Readers of the UV'd meshes ICM writes, for the tests that read them back: a small PLY
// parser (ASCII and binary little-endian, the properties named in the header, in any order),
// tinygltf's loader for glTF and GLB, and the check that a file holds a Uv_mesh's faces with
// the same position and the same UV at every corner.

#ifndef ICM_TEST_UV_OUTPUT_READERS_H
#define ICM_TEST_UV_OUTPUT_READERS_H

#include <ICM/IO/Uv_mesh.h>

#ifdef ICM_HAS_TINYGLTF
#include <tiny_gltf.h>
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace icm_test {

/// A mesh as a file stores it: its vertices, three indices per face into them, and the UV
/// of every corner of every face, as written (glTF's v is 1 - v).
struct Corner_mesh
{
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<int, 3>> faces;
  std::vector<std::array<std::array<float, 2>, 3>> corner_uvs;
  std::string format; ///< the PLY format line, or "glTF"
};

inline std::uint32_t little_endian_uint32(const unsigned char* bytes)
{
  return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
         std::uint32_t(bytes[3]) << 24;
}

inline float little_endian_float(const unsigned char* bytes)
{
  const std::uint32_t bits = little_endian_uint32(bytes);
  float x;
  std::memcpy(&x, &bits, 4);
  return x;
}

/// One PLY scalar or list count of type `type` (uchar, int or float: what ICM writes), read
/// from ASCII text or little-endian bytes.
class Ply_values
{
public:
  Ply_values(std::string body, bool binary) : text_(body), binary_(binary), bytes_(std::move(body))
  {
    text_.imbue(std::locale::classic());
  }
  double next(const std::string& type)
  {
    if(!binary_)
    {
      double x = 0;
      text_ >> x;
      EXPECT_TRUE(static_cast<bool>(text_)) << "a " << type << " is missing";
      return x;
    }
    const std::size_t size = type == "uchar" ? 1 : 4;
    if(at_ + size > bytes_.size())
    {
      ADD_FAILURE() << "the binary body ends early";
      at_ = bytes_.size();
      return 0;
    }
    const auto* p = reinterpret_cast<const unsigned char*>(bytes_.data() + at_);
    at_ += size;
    if(type == "uchar")
      return p[0];
    if(type == "int")
      return static_cast<std::int32_t>(little_endian_uint32(p));
    EXPECT_EQ(type, "float");
    return little_endian_float(p);
  }
  /// Whether everything was read (only white space is left in ASCII).
  bool at_end()
  {
    if(binary_)
      return at_ == bytes_.size();
    std::string rest;
    return !(text_ >> rest);
  }

private:
  std::istringstream text_;
  bool binary_;
  std::string bytes_;
  std::size_t at_ = 0;
};

/// The vertices (x, y, z) and faces (vertex_indices, texcoord) of a PLY file as ICM writes it.
inline Corner_mesh read_ply_corners(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Corner_mesh out;
  const std::size_t end = file.find("end_header\n");
  if(file.rfind("ply\n", 0) != 0 || end == std::string::npos)
  {
    ADD_FAILURE() << path << " is not a PLY file";
    return out;
  }
  struct Property
  {
    std::string name, type, count_type; // count_type empty for a scalar
  };
  struct Element
  {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  std::istringstream header(file.substr(0, end));
  for(std::string line; std::getline(header, line);)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if(keyword == "format")
      out.format = line;
    else if(keyword == "element")
    {
      elements.emplace_back();
      words >> elements.back().name >> elements.back().count;
    }
    else if(keyword == "property" && !elements.empty())
    {
      Property p;
      words >> p.type;
      if(p.type == "list")
        words >> p.count_type >> p.type;
      words >> p.name;
      elements.back().properties.push_back(p);
    }
  }
  Ply_values values(file.substr(end + std::strlen("end_header\n")), out.format == "format binary_little_endian 1.0");
  for(const Element& e : elements)
    for(std::size_t i = 0; i < e.count; ++i)
    {
      std::array<float, 3> position{};
      std::array<int, 3> face{};
      std::array<std::array<float, 2>, 3> uvs{};
      for(const Property& p : e.properties)
      {
        if(p.count_type.empty())
        {
          const double x = values.next(p.type);
          if(e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z"))
            position[p.name[0] - 'x'] = static_cast<float>(x);
          continue;
        }
        const int n = static_cast<int>(values.next(p.count_type));
        EXPECT_EQ(n, p.name == "texcoord" ? 6 : 3) << p.name << " of " << e.name << " " << i;
        for(int k = 0; k < n; ++k)
        {
          const double x = values.next(p.type);
          if(p.name == "vertex_indices" && k < 3)
            face[k] = static_cast<int>(x);
          else if(p.name == "texcoord" && k < 6)
            uvs[k / 2][k % 2] = static_cast<float>(x);
        }
      }
      if(e.name == "vertex")
        out.positions.push_back(position);
      else if(e.name == "face")
      {
        out.faces.push_back(face);
        out.corner_uvs.push_back(uvs);
      }
    }
  EXPECT_TRUE(values.at_end()) << path << " has bytes after its last element";
  return out;
}

#ifdef ICM_HAS_TINYGLTF
/// Element `i`, component `c` of an accessor of 4-byte components (float or unsigned int).
inline const unsigned char* gltf_component(const tinygltf::Model& model, int accessor, std::size_t i, int c)
{
  const tinygltf::Accessor& a = model.accessors.at(accessor);
  const tinygltf::BufferView& view = model.bufferViews.at(a.bufferView);
  const std::vector<unsigned char>& data = model.buffers.at(view.buffer).data;
  const std::size_t at = view.byteOffset + a.byteOffset + i * a.ByteStride(view) + 4 * c;
  EXPECT_LE(at + 4, data.size());
  return data.data() + at;
}

/// The one triangle primitive of a glTF or GLB file ICM wrote, loaded by tinygltf.
inline Corner_mesh read_gltf_corners(const std::string& path, bool binary)
{
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                             : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  Corner_mesh out;
  out.format = "glTF";
  EXPECT_TRUE(loaded) << path << ": " << error;
  EXPECT_TRUE(warning.empty()) << warning;
  if(!loaded || model.meshes.size() != 1 || model.meshes[0].primitives.size() != 1)
  {
    ADD_FAILURE() << path << " has not one mesh of one primitive";
    return out;
  }
  EXPECT_EQ(model.asset.version, "2.0");
  const tinygltf::Primitive& p = model.meshes[0].primitives[0];
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
  const int position = p.attributes.at("POSITION"), texcoord = p.attributes.at("TEXCOORD_0");
  EXPECT_EQ(model.accessors.at(position).type, TINYGLTF_TYPE_VEC3);
  EXPECT_EQ(model.accessors.at(position).componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(model.accessors.at(texcoord).type, TINYGLTF_TYPE_VEC2);
  EXPECT_EQ(model.accessors.at(texcoord).componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(model.accessors.at(p.indices).componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const std::size_t n = model.accessors[position].count;
  EXPECT_EQ(model.accessors[texcoord].count, n);
  std::vector<std::array<float, 2>> uvs(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    out.positions.push_back({});
    for(int c = 0; c < 3; ++c)
      out.positions.back()[c] = little_endian_float(gltf_component(model, position, i, c));
    for(int c = 0; c < 2; ++c)
      uvs[i][c] = little_endian_float(gltf_component(model, texcoord, i, c));
  }
  // POSITION's bounds are required, and must be those of the values.
  const tinygltf::Accessor& bounded = model.accessors[position];
  EXPECT_EQ(bounded.minValues.size(), 3u);
  EXPECT_EQ(bounded.maxValues.size(), 3u);
  for(std::size_t c = 0; c < 3 && c < bounded.minValues.size() && c < bounded.maxValues.size(); ++c)
    for(const auto& x : out.positions)
    {
      EXPECT_LE(bounded.minValues[c], x[c]);
      EXPECT_GE(bounded.maxValues[c], x[c]);
    }
  const std::size_t corners = model.accessors[p.indices].count;
  EXPECT_EQ(corners % 3, 0u);
  for(std::size_t f = 0; f + 2 < corners; f += 3)
  {
    std::array<int, 3> face{};
    std::array<std::array<float, 2>, 3> corner_uvs{};
    for(int k = 0; k < 3; ++k)
    {
      const std::uint32_t i = little_endian_uint32(gltf_component(model, p.indices, f + k, 0));
      EXPECT_LT(i, n);
      face[k] = static_cast<int>(i);
      corner_uvs[k] = i < n ? uvs[i] : std::array<float, 2>{};
    }
    out.faces.push_back(face);
    out.corner_uvs.push_back(corner_uvs);
  }
  return out;
}
#endif

/// Checks that `file` has the faces of `m` in its order, each corner with `m`'s position and
/// UV rounded to float (glTF's v as 1 - v), within `tolerance` times the mesh's extent (0:
/// the very float).
inline void expect_same_corners(const ICM::IO::Uv_mesh& m, const Corner_mesh& file, double tolerance = 0)
{
  ASSERT_EQ(file.faces.size(), m.number_of_faces());
  ASSERT_EQ(file.corner_uvs.size(), m.number_of_faces());
  const bool gltf = file.format == "glTF";
  const double scale = tolerance * (std::max)(ICM::internal::half_extent(m.positions), 1e-300);
  const double uv_scale = tolerance * (std::max)(ICM::internal::half_extent(m.uvs), 1e-300);
  auto same = [](double expected, float actual, double within) {
    return within == 0 ? static_cast<float>(expected) == actual : std::abs(expected - actual) <= within;
  };
  int reported = 0;
  for(std::size_t f = 0; f < m.number_of_faces() && reported < 10; ++f)
    for(int k = 0; k < 3; ++k)
    {
      const int i = file.faces[f][k];
      ASSERT_GE(i, 0);
      ASSERT_LT(static_cast<std::size_t>(i), file.positions.size());
      const auto& p = m.positions[m.face_positions[f][k]];
      const auto& q = file.positions[i];
      const auto& t = m.uvs[m.face_uvs[f][k]];
      const auto& s = file.corner_uvs[f][k];
      const bool ok = same(p[0], q[0], scale) && same(p[1], q[1], scale) && same(p[2], q[2], scale) &&
                      same(t[0], s[0], uv_scale) && same(gltf ? 1. - t[1] : t[1], s[1], uv_scale);
      EXPECT_TRUE(ok) << file.format << ": face " << f << " corner " << k << ": (" << q[0] << ", " << q[1] << ", "
                      << q[2] << ") uv (" << s[0] << ", " << s[1] << ") for (" << p[0] << ", " << p[1] << ", " << p[2]
                      << ") uv (" << t[0] << ", " << t[1] << ")";
      reported += ok ? 0 : 1;
    }
}

/// The `v`, `vt` and `f a/ta b/tb c/tc` lines of an OBJ ICM wrote, as a Uv_mesh.
inline ICM::IO::Uv_mesh read_obj_uv_mesh(const std::string& path)
{
  ICM::IO::Uv_mesh m;
  std::ifstream in(path);
  in.imbue(std::locale::classic());
  for(std::string line; std::getline(in, line);)
  {
    std::istringstream s(line);
    s.imbue(std::locale::classic());
    std::string tag;
    s >> tag;
    if(tag == "v")
    {
      m.positions.push_back({});
      s >> m.positions.back()[0] >> m.positions.back()[1] >> m.positions.back()[2];
    }
    else if(tag == "vt")
    {
      m.uvs.push_back({});
      s >> m.uvs.back()[0] >> m.uvs.back()[1];
    }
    else if(tag == "f")
    {
      std::array<int, 3> p{}, t{};
      char slash = 0;
      for(int k = 0; k < 3; ++k)
      {
        s >> p[k] >> slash >> t[k];
        --p[k];
        --t[k];
      }
      m.face_positions.push_back(p);
      m.face_uvs.push_back(t);
    }
    if(tag == "v" || tag == "vt" || tag == "f")
    {
      EXPECT_FALSE(s.fail()) << path << ": " << line;
    }
  }
  return m;
}

} // namespace icm_test

#endif // ICM_TEST_UV_OUTPUT_READERS_H
