// The functions of the module `icm` on meshes and their UVs but parameterize
// (icm_module_meshes.h).

#include "icm_module_meshes.h"

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/measures/Distortion.h>

#include <array>
#include <stdexcept>
#include <vector>

namespace icm_module {

namespace {

/// The distortion figures under the names of icm_param's JSON line (doc/cli.md).
py::dict measures_dict(const ICM::Distortion_measures& m)
{
  py::dict d;
  d["faces"] = m.faces;
  d["flipped_faces"] = m.flipped_faces;
  d["degenerate_uv_faces"] = m.degenerate_uv_faces;
  d["degenerate_3d_faces"] = m.degenerate_3d_faces;
  d["conformality"] = m.conformality;
  d["angle_distortion"] = m.angle_distortion;
  d["l2_shear"] = m.l2_shear;
  d["l2_stretch"] = m.l2_stretch;
  d["log_area_distortion"] = m.log_area_distortion;
  d["log_area_distortion_area_weighted"] = m.log_area_distortion_area_weighted;
  d["area_ratio_min"] = m.area_ratio_min;
  d["area_ratio_max"] = m.area_ratio_max;
  d["qc_mean"] = m.qc_mean;
  d["qc_max"] = m.qc_max;
  return d;
}

} // namespace

py::dict measure_distortion(const py::object& V, const py::object& F, const py::object& uv, const py::object& fuv)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), faces_of_V);
  const auto [uvs, corners] = uv_rows(uv, fuv, faces.shape(0));
  std::vector<std::array<double, 3>> xyz;
  std::vector<std::array<double, 2>> flat;
  xyz.reserve(3 * faces.shape(0));
  flat.reserve(3 * faces.shape(0));
  for(py::ssize_t f = 0; f < faces.shape(0); ++f)
    for(py::ssize_t k = 0; k < 3; ++k)
    {
      const py::ssize_t v = faces.at(f, k), t = corners.at(f, k);
      xyz.push_back({points.at(v, 0), points.at(v, 1), points.at(v, 2)});
      flat.push_back({uvs.at(t, 0), uvs.at(t, 1)});
    }
  try
  {
    return measures_dict(ICM::measure_distortion_of_triangles(xyz, flat));
  }
  catch(const std::invalid_argument& e)
  {
    throw Icm_error(e.what());
  }
}

py::tuple read_mesh(const std::string& path, bool triangulate)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_options options;
  options.triangulate = triangulate;
  ICM::IO::Mesh_reading_report read;
  bool ok = false;
  {
    py::gil_scoped_release released;
    ok = ICM::IO::read_triangle_mesh(path, mesh, read, options);
  }
  if(!ok)
    throw Icm_error(read.message +
                    (read.non_triangle_faces > 0 && !triangulate ? " (triangulate=True splits them)" : ""));
  const ICM::IO::Uv_mesh m = ICM::IO::make_uv_mesh(mesh, get(CGAL::vertex_point, mesh));
  return py::make_tuple(array_of<double>(m.positions, 3), array_of<std::int64_t>(m.face_positions, 3),
                        list_of(read.repairs()));
}

void write_mesh(const std::string& path, const py::object& V, const py::object& F, const py::object& uv,
                const py::object& fuv, bool binary_ply)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), faces_of_V);
  const auto [uvs, corners] = uv_rows(uv, fuv, faces.shape(0));
  if(points.shape(0) > 2147483647 || uvs.shape(0) > 2147483647)
    throw Icm_error("V or uv has more rows than a mesh file's 32-bit indices hold");
  ICM::IO::Uv_mesh m;
  for(py::ssize_t i = 0; i < points.shape(0); ++i)
    m.positions.push_back({points.at(i, 0), points.at(i, 1), points.at(i, 2)});
  for(py::ssize_t i = 0; i < uvs.shape(0); ++i)
    m.uvs.push_back({uvs.at(i, 0), uvs.at(i, 1)});
  for(py::ssize_t f = 0; f < faces.shape(0); ++f)
  {
    m.face_positions.push_back(
      {static_cast<int>(faces.at(f, 0)), static_cast<int>(faces.at(f, 1)), static_cast<int>(faces.at(f, 2))});
    m.face_uvs.push_back(
      {static_cast<int>(corners.at(f, 0)), static_cast<int>(corners.at(f, 1)), static_cast<int>(corners.at(f, 2))});
  }
  ICM::IO::Mesh_writing_options options;
  options.binary_ply = binary_ply;
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release released;
    ok = ICM::IO::write_uv_files(path, ICM::IO::Uv_pictures(), m, error, options);
  }
  if(!ok)
    throw Icm_error(error);
}

} // namespace icm_module
