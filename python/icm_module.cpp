// The Python module `icm` (its compiled part `_icm`): ICM::parameterize, ICM's checked mesh
// readers and UV mesh writers, and the distortion measures, on numpy arrays (doc/python.md).
//
// One translation unit: ICM::parameterize is instantiated for CGAL::Surface_mesh with the
// default metric (`Default_metric`, intrinsic Delaunay) and each energy once. Every array
// that comes in is checked here (shape, dtype, finite coordinates, indices in range, not
// empty) and refused with `icm.Error`, never passed on unchecked; the meshes go through the
// same soup-to-mesh checks and repairs as a file read by icm_param (IO/read_triangle_mesh.h).

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Corner_uv_map = Mesh::Property_map<Mesh::Halfedge_index, Kernel::Point_2>;
namespace SMP = CGAL::Surface_mesh_parameterization;

/// A refusal or a failure, raised in Python as `icm.Error` with the reason, and the ICM
/// error code (`CGAL::Surface_mesh_parameterization::Error_code`) when there is one.
struct Icm_error : std::runtime_error
{
  std::optional<int> code;
  explicit Icm_error(const std::string& why, std::optional<int> code_ = std::nullopt)
    : std::runtime_error(why), code(code_)
  {}
};

// --- arrays in --------------------------------------------------------------------------

/// `object` as a C-contiguous (rows, columns) array of doubles, or `Icm_error` naming `what`.
py::array_t<double, py::array::c_style> real_rows(const py::object& object, py::ssize_t columns, const char* what)
{
  const py::array any = py::array::ensure(object);
  if(!any)
    throw Icm_error(std::string(what) + " must be an array of numbers (numpy.ndarray)");
  const char kind = any.dtype().kind();
  if(kind != 'f' && kind != 'i' && kind != 'u')
    throw Icm_error(std::string(what) + " must hold real numbers, not dtype " +
                    py::str(any.dtype()).cast<std::string>());
  if(any.ndim() != 2 || any.shape(1) != columns)
    throw Icm_error(std::string(what) + " must have shape (n, " + std::to_string(columns) + "), not " +
                    py::str(py::tuple(py::cast(std::vector<py::ssize_t>(any.shape(), any.shape() + any.ndim()))))
                      .cast<std::string>());
  if(any.shape(0) == 0)
    throw Icm_error(std::string(what) + " is empty");
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(any);
  if(!rows)
    throw Icm_error(std::string(what) + " cannot be converted to float64");
  const double* data = rows.data();
  for(py::ssize_t i = 0; i < rows.size(); ++i)
    if(!std::isfinite(data[i]))
      throw Icm_error(std::string(what) + " has a non-finite coordinate (NaN or infinity) in row " +
                      std::to_string(i / columns));
  return rows;
}

/// `object` as a C-contiguous (rows, 3) array of indices below `bound`, or `Icm_error`.
py::array_t<std::int64_t, py::array::c_style> index_rows(const py::object& object, std::size_t bound, const char* what,
                                                         const char* into)
{
  const py::array any = py::array::ensure(object);
  if(!any)
    throw Icm_error(std::string(what) + " must be an array of integers (numpy.ndarray)");
  const char kind = any.dtype().kind();
  if(kind != 'i' && kind != 'u')
    throw Icm_error(std::string(what) + " must hold integers (indices), not dtype " +
                    py::str(any.dtype()).cast<std::string>());
  if(any.ndim() != 2 || any.shape(1) != 3)
    throw Icm_error(std::string(what) + " must have shape (m, 3), not " +
                    py::str(py::tuple(py::cast(std::vector<py::ssize_t>(any.shape(), any.shape() + any.ndim()))))
                      .cast<std::string>());
  if(any.shape(0) == 0)
    throw Icm_error(std::string(what) + " is empty (no faces)");
  auto rows = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(any);
  if(!rows)
    throw Icm_error(std::string(what) + " cannot be converted to int64");
  const std::int64_t* data = rows.data();
  for(py::ssize_t i = 0; i < rows.size(); ++i)
    if(data[i] < 0 || static_cast<std::uint64_t>(data[i]) >= bound)
      throw Icm_error(std::string(what) + " row " + std::to_string(i / 3) + " has index " + std::to_string(data[i]) +
                      " out of range: " + into + " has " + std::to_string(bound) + " rows");
  return rows;
}

/// V and F checked and made a triangle mesh by ICM's soup checks (the repairs in `read`),
/// or `Icm_error` with the reason.
Mesh mesh_of(const py::object& V, const py::object& F, ICM::IO::Mesh_reading_report& read)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), "F", "V");
  ICM::IO::Polygon_soup soup;
  soup.points.reserve(points.shape(0));
  for(py::ssize_t i = 0; i < points.shape(0); ++i)
    soup.points.emplace_back(points.at(i, 0), points.at(i, 1), points.at(i, 2));
  soup.polygons.reserve(faces.shape(0));
  for(py::ssize_t f = 0; f < faces.shape(0); ++f)
    soup.polygons.push_back({static_cast<std::size_t>(faces.at(f, 0)), static_cast<std::size_t>(faces.at(f, 1)),
                             static_cast<std::size_t>(faces.at(f, 2))});
  Mesh mesh;
  if(!ICM::IO::polygon_soup_to_triangle_mesh(soup, mesh, read))
    throw Icm_error("V, F: " + read.message);
  return mesh;
}

/// A (rows, columns) numpy array of `T` filled from `rows`.
template <class T, class Rows>
py::array_t<T> array_of(const Rows& rows, py::ssize_t columns)
{
  py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), columns});
  auto view = out.template mutable_unchecked<2>();
  for(std::size_t i = 0; i < rows.size(); ++i)
    for(py::ssize_t j = 0; j < columns; ++j)
      view(static_cast<py::ssize_t>(i), j) = static_cast<T>(rows[i][j]);
  return out;
}

py::list list_of(const std::vector<std::string>& lines)
{
  py::list out;
  for(const std::string& line : lines)
    out.append(line);
  return out;
}

// --- measures -----------------------------------------------------------------------------

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

/// The UVs of a Uv_mesh-like (uv, fuv) pair checked against F: (rows, 2) finite reals and
/// (faces, 3) indices into them.
std::pair<py::array_t<double, py::array::c_style>, py::array_t<std::int64_t, py::array::c_style>>
uv_rows(const py::object& uv, const py::object& fuv, py::ssize_t faces)
{
  auto uvs = real_rows(uv, 2, "uv");
  auto corners = index_rows(fuv, static_cast<std::size_t>(uvs.shape(0)), "fuv", "uv");
  if(corners.shape(0) != faces)
    throw Icm_error("fuv has " + std::to_string(corners.shape(0)) + " rows and F " + std::to_string(faces) +
                    ": one row per face in both");
  return {uvs, corners};
}

py::dict measure_distortion(const py::object& V, const py::object& F, const py::object& uv, const py::object& fuv)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), "F", "V");
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

// --- parameterize -------------------------------------------------------------------------

/// The result of `icm.parameterize`.
struct Parameterization
{
  py::array_t<double> uv;
  py::array_t<std::int64_t> fuv;
  int charts = 0;
  py::array_t<std::int64_t> seams;
  py::dict report;
};

/// The run's figures under the keys of icm_param's JSON line (doc/cli.md), summed over the
/// charts as icm_param sums them.
py::dict report_dict(const Mesh& mesh, const ICM::Surface_parameterization_report& r, const std::string& energy,
                     const std::optional<ICM::Atlas_options>& atlas, const std::vector<Mesh::Edge_index>& seams,
                     const ICM::IO::Mesh_reading_report& read, const ICM::Distortion_measures& m)
{
  const ICM::Surface_summary s = ICM::surface_summary(r);
  py::dict d;
  d["vertices"] = num_vertices(mesh);
  d["faces"] = num_faces(mesh);
  d["charts"] = s.charts;
  d["components"] = r.charts.size();
  d["boundary_loops"] = s.boundary_loops;
  d["genus"] = s.genus;
  d["cones"] = s.cones;
  d["cones_above_full_turn"] = s.wide_cones;
  d["seam_edges"] = seams.size();
  d["seam_length"] = ICM::seam_length_over_root_area(mesh, seams);
  d["layout"] = s.layouts;
  d["newton_iterations"] = s.newton_iterations;
  d["max_curvature_error"] = s.max_curvature_error;
  d["max_layout_length_error"] = s.max_layout_length_error;
  d["seam_length_error"] = s.seam_length_error;
  d["overlapping_border_edges"] = s.overlapping_border_edges;
  d["raw_overlapping_border_edges"] = s.raw_overlapping_border_edges;
  d["moved_vertices"] = s.moved_vertices;
  d["metric"] = s.metrics;
  d["metric_fallback"] = s.fallback_reason;
  d["energy"] = energy;
  if(energy != ICM::Curvature_entropy::name)
  {
    const ICM::Energy_summary summary = ICM::energy_summary(r);
    d["energy_iterations"] = summary.iterations;
    d["initial_energy"] = summary.initial_energy;
    d["final_energy"] = summary.final_energy;
    d["energy_message"] = summary.message;
  }
  d["boundary"] = "free";
  if(atlas)
  {
    d["atlas_size"] = atlas->size;
    d["atlas_padding"] = atlas->padding;
    d["atlas_packer"] = ICM::atlas_packer_name(atlas->packer);
    d["atlas_charts"] = r.atlas_charts;
    d["atlas_rotated_charts"] = r.atlas_rotated_charts;
    d["atlas_utilization"] = r.atlas_utilization;
  }
  d["flipped_faces"] = m.flipped_faces;
  d["log_area_distortion"] = m.log_area_distortion;
  d["log_area_distortion_area_weighted"] = m.log_area_distortion_area_weighted;
  d["area_ratio_min"] = m.area_ratio_min;
  d["area_ratio_max"] = m.area_ratio_max;
  d["qc_mean"] = m.qc_mean;
  d["isolated_vertices_dropped"] = read.isolated_vertices.size();
  d["vertices_split"] = read.split_vertices.size();
  d["faces_reoriented"] = read.reoriented_faces.size();
  d["repairs"] = list_of(read.repairs());
  d["seconds_index"] = r.seconds_index;
  d["seconds_cones"] = r.seconds_cones;
  d["seconds_optimum"] = r.seconds_optimum;
  d["seconds_cut"] = r.seconds_cut;
  d["seconds_layout"] = r.seconds_layout;
  d["seconds_parameterize"] = r.seconds_total;
  return d;
}

/// ICM::parameterize with the default metric and the energy named `energy`.
ICM::Surface_parameterization_report run(const std::string& energy, const Mesh& mesh, Corner_uv_map uv,
                                         const ICM::Surface_parameterization_options& options,
                                         const std::map<Mesh::Vertex_index, double>& cones,
                                         std::vector<Mesh::Edge_index>& seams)
{
  if(energy == ICM::U_square::name)
    return ICM::parameterize<CGAL::Default, CGAL::Default, ICM::U_square>(mesh, uv, options, cones, &seams);
  if(energy == ICM::Area_distortion::name)
    return ICM::parameterize<CGAL::Default, CGAL::Default, ICM::Area_distortion>(mesh, uv, options, cones, &seams);
  if(energy == ICM::Angle_distortion::name)
    return ICM::parameterize<CGAL::Default, CGAL::Default, ICM::Angle_distortion>(mesh, uv, options, cones, &seams);
  if(energy == ICM::Log_area_distortion::name)
    return ICM::parameterize<CGAL::Default, CGAL::Default, ICM::Log_area_distortion>(mesh, uv, options, cones, &seams);
  return ICM::parameterize(mesh, uv, options, cones, &seams);
}

const std::vector<std::string>& energy_names()
{
  static const std::vector<std::string> names = {ICM::Curvature_entropy::name, ICM::U_square::name,
                                                 ICM::Area_distortion::name, ICM::Angle_distortion::name,
                                                 ICM::Log_area_distortion::name};
  return names;
}

/// The options of `cones`, `energy`, `atlas` and `padding`, as icm_param sets them from
/// --cones, --energy, --atlas and --padding.
ICM::Surface_parameterization_options options_of(const py::object& cones, const std::string& energy,
                                                 const py::object& atlas, int padding)
{
  const std::vector<std::string>& names = energy_names();
  if(std::find(names.begin(), names.end(), energy) == names.end())
  {
    std::string known;
    for(const std::string& name : names)
      known += (known.empty() ? "" : ", ") + name;
    throw Icm_error("energy '" + energy + "' is not one of " + known);
  }
  ICM::Surface_parameterization_options options;
  if(py::isinstance<py::str>(cones))
  {
    if(cones.cast<std::string>() != "auto")
      throw Icm_error("cones takes 'auto' or a count >= 0, not '" + cones.cast<std::string>() + "'");
  }
  else if(py::isinstance<py::int_>(cones) && !py::isinstance<py::bool_>(cones))
  {
    const long long count = cones.cast<long long>();
    if(count < 0 || count > 100000)
      throw Icm_error("cones takes 'auto' or a count from 0 to 100000, not " + std::to_string(count));
    const int max_cones = static_cast<int>(count);
    // A count is exact: no stop on distortion, and a disk gets its cones too (icm_param --cones N).
    options.automatic_cones = max_cones > 0;
    options.cones.max_cones = max_cones;
    options.initial_cones = std::min(options.initial_cones, max_cones);
    options.cones.max_log_scale = 0;
    options.border_max_log_scale = 0;
  }
  else
    throw Icm_error("cones takes 'auto' or an int, not " + py::repr(cones).cast<std::string>());
  if(!atlas.is_none())
  {
    if(!py::isinstance<py::int_>(atlas) || py::isinstance<py::bool_>(atlas))
      throw Icm_error("atlas takes a texture size in texels (an int) or None, not " +
                      py::repr(atlas).cast<std::string>());
    ICM::Atlas_options a;
    const long long size = atlas.cast<long long>();
    a.size = static_cast<int>(std::clamp<long long>(size, -1, 1 << 20));
    a.padding = padding;
    options.atlas = a;
  }
  if(const ICM::Status checked = ICM::check_options(options); !checked.ok())
    throw Icm_error(checked.message, static_cast<int>(checked.code));
  return options;
}

Parameterization parameterize(const py::object& V, const py::object& F, const py::object& cones,
                              const std::vector<std::pair<long long, double>>& cone, const std::string& energy,
                              const py::object& atlas, int padding)
{
  const ICM::Surface_parameterization_options options = options_of(cones, energy, atlas, padding);
  ICM::IO::Mesh_reading_report read;
  Mesh mesh = mesh_of(V, F, read);
  const std::size_t input_vertices = read.file_vertices;

  // V's rows to the mesh's vertices (none for a dropped vertex, several for a split one).
  std::vector<std::vector<Mesh::Vertex_index>> by_row(input_vertices);
  for(std::size_t i = 0; i < read.file_vertex.size(); ++i)
    by_row[read.file_vertex[i]].push_back(Mesh::Vertex_index(static_cast<Mesh::size_type>(i)));
  std::map<Mesh::Vertex_index, double> user_cones;
  for(const auto& [vertex, degrees] : cone)
  {
    const std::string what = "cone (" + std::to_string(vertex) + ", " + std::to_string(degrees) + "): ";
    if(!(degrees > 0) || !std::isfinite(degrees))
      throw Icm_error(what + "the angle must be a finite number of degrees > 0");
    if(vertex < 0 || static_cast<std::size_t>(vertex) >= input_vertices)
      throw Icm_error(what + "V has " + std::to_string(input_vertices) + " rows");
    if(by_row[vertex].size() != 1)
      throw Icm_error(what + "vertex " + std::to_string(vertex) +
                      (by_row[vertex].empty() ? " is in no face"
                                              : " is non-manifold and was split into " +
                                                  std::to_string(by_row[vertex].size()) + " vertices"));
    user_cones[by_row[vertex].front()] = 2 * M_PI - degrees * M_PI / 180;
  }

  const Corner_uv_map uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  std::vector<Mesh::Edge_index> seams;
  ICM::Surface_parameterization_report report;
  {
    py::gil_scoped_release released;
    report = run(energy, mesh, uvmap, options, user_cones, seams);
  }
  if(report.status != SMP::OK)
    throw Icm_error(std::string(ICM::error_message(report.status)) + ": " + report.message,
                    static_cast<int>(report.status));
  const ICM::Distortion_measures measures = ICM::measure_distortion_corner_uv(mesh, uvmap);
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);

  // fuv follows F's rows and corners: face f of the mesh is row f of F (no face is added or
  // dropped), whose corners may have been reversed (a reoriented face) or renumbered.
  const auto faces = index_rows(F, input_vertices, "F", "V");
  std::vector<std::array<std::int64_t, 3>> fuv(uv_mesh.number_of_faces());
  for(std::size_t f = 0; f < fuv.size(); ++f)
    for(int k = 0; k < 3; ++k)
    {
      const std::size_t row = read.file_vertex[static_cast<std::size_t>(uv_mesh.face_positions[f][k])];
      int column = 0;
      while(column < 3 && static_cast<std::size_t>(faces.at(static_cast<py::ssize_t>(f), column)) != row)
        ++column;
      if(column == 3)
        throw Icm_error("internal error: face " + std::to_string(f) + " of the mesh is not row " + std::to_string(f) +
                        " of F");
      fuv[f][column] = uv_mesh.face_uvs[f][k];
    }
  std::vector<std::array<std::size_t, 2>> seam_rows;
  seam_rows.reserve(seams.size());
  for(Mesh::Edge_index e : seams)
    seam_rows.push_back({read.file_vertex[static_cast<std::size_t>(source(e, mesh))],
                         read.file_vertex[static_cast<std::size_t>(target(e, mesh))]});

  Parameterization result;
  result.uv = array_of<double>(uv_mesh.uvs, 2);
  result.fuv = array_of<std::int64_t>(fuv, 3);
  result.seams = seam_rows.empty() ? py::array_t<std::int64_t>(std::vector<py::ssize_t>{0, 2})
                                   : array_of<std::int64_t>(seam_rows, 2);
  result.report = report_dict(mesh, report, energy, options.atlas, seams, read, measures);
  result.charts = result.report["charts"].cast<int>();
  return result;
}

// --- files --------------------------------------------------------------------------------

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
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), "F", "V");
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

} // namespace

PYBIND11_MODULE(_icm, m)
{
  m.doc() = "ICM: conformal parameterization of triangle meshes by the inverse curvature map (doc/python.md).";

  static py::exception<Icm_error> error(m, "Error", PyExc_ValueError);
  error.attr("__module__") = "icm"; // icm.Error, as users name it
  error.attr("__doc__") = "A refused input or a failed run: the reason is the message; `code` is ICM's error code "
                          "(CGAL::Surface_mesh_parameterization::Error_code) where there is one, else None.";
  py::register_exception_translator([](std::exception_ptr p) {
    try
    {
      if(p)
        std::rethrow_exception(p);
    }
    catch(const Icm_error& e)
    {
      py::object instance = py::handle(error.ptr())(e.what()); // an instance, not raised yet
      instance.attr("code") = e.code ? py::object(py::int_(*e.code)) : py::object(py::none());
      PyErr_SetObject(error.ptr(), instance.ptr());
    }
    catch(const std::bad_alloc&)
    {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    }
  });
  m.attr("ENERGIES") = py::cast(energy_names());
  m.attr("HAS_GLTF") = ICM::IO::writes_gltf();

  py::class_<Parameterization>(m, "Parameterization",
                               "The result of parameterize(): the UVs, their faces, the charts, the seams, the report.")
    .def_readonly("uv", &Parameterization::uv, "float64 array (k, 2): one row per UV corner index")
    .def_readonly("fuv", &Parameterization::fuv,
                  "int64 array (m, 3): for each row of F, the rows of uv of its three corners, in F's order")
    .def_readonly("charts", &Parameterization::charts, "the number of charts")
    .def_readonly("seams", &Parameterization::seams, "int64 array (s, 2): the seam edges, as pairs of rows of V")
    .def_readonly("report", &Parameterization::report,
                  "dict: the run's figures under the keys of icm_param's --json line (doc/cli.md)")
    .def("__repr__", [](const Parameterization& p) {
      return "<icm.Parameterization: " + std::to_string(p.uv.shape(0)) + " UVs, " + std::to_string(p.fuv.shape(0)) +
             " faces, " + std::to_string(p.charts) + " charts>";
    });

  m.def("parameterize", &parameterize, py::arg("V"), py::arg("F"), py::kw_only(), py::arg("cones") = "auto",
        py::arg("cone") = std::vector<std::pair<long long, double>>(), py::arg("energy") = "entropy",
        py::arg("atlas") = py::none(), py::arg("padding") = 4,
        R"(Parameterizes a triangle mesh (any topology) with ICM::parameterize, the default metric.

V: float64 array (n, 3) of vertex positions; F: integer array (m, 3) of rows of V.
cones: "auto" (cones where the distortion asks for them, as icm_param) or an exact count of
  automatic cones (0: only the border and the user's cones are singular).
cone: list of (vertex, degrees): vertices that must be cones with that total angle.
energy: one of icm.ENERGIES ("entropy", "u-square", "area", "angle", "log-area"); another
  energy than the entropy is minimised from the entropy optimum with its cones.
atlas: None (the charts at their 3D scale, side by side) or a texture size in texels: every
  chart in [0, 1]^2, `padding` texels apart.
The GIL is released during the solve. Returns an icm.Parameterization; raises icm.Error on a
refused input or a failed run (with `code`, ICM's error code, where there is one).)");
  m.def("read_mesh", &read_mesh, py::arg("path"), py::kw_only(), py::arg("triangulate") = false,
        R"(Reads a mesh file (OFF, OBJ, PLY or STL, by extension) through ICM's checked readers.

Returns (V, F, repairs): float64 (n, 3), int64 (m, 3) and the list of the repairs made
(isolated vertices dropped, non-manifold vertices split, faces reoriented, polygons
triangulated with triangulate=True). Raises icm.Error naming the reason of a refusal.)");
  m.def("write_mesh", &write_mesh, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("fuv"),
        py::kw_only(), py::arg("binary_ply") = false,
        R"(Writes the mesh with its UVs in the format the extension names: .obj, .ply, .gltf or .glb
(glTF only when icm.HAS_GLTF). uv/fuv as parameterize() returns them. The file is replaced only
once it is written whole. Raises icm.Error with the reason.)");
  m.def("measure_distortion", &measure_distortion, py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("fuv"),
        R"(The distortion of the map from each 3D triangle (V, F) to its UV triangle (uv, fuv), as
ICM::measure_distortion_corner_uv gives it (doc/distortion.md): a dict with faces, flipped_faces,
degenerate_uv_faces, degenerate_3d_faces, conformality, angle_distortion, l2_shear, l2_stretch,
log_area_distortion, log_area_distortion_area_weighted, area_ratio_min, area_ratio_max, qc_mean,
qc_max.)");
}
