// The Python module `icm` (its compiled part `_icm`): ICM::parameterize and the prescribed
// borders of Inverse_curvature_map_parameterizer_3, ICM's checked mesh readers and UV mesh
// writers, and the distortion measures, on numpy arrays (doc/python.md).
//
// This file checks and binds; the runs are icm_param's (examples/icm_param_energy.h): every
// metric, energy and border condition it takes, instantiated one energy (or the borders) per
// file, so that the module runs what icm_param runs. Every array that comes in is checked here
// (shape, dtype, finite coordinates, indices in range, not empty) and refused with
// `icm.Error`, never passed on unchecked; the meshes go through the same soup-to-mesh checks
// and repairs as a file read by icm_param (IO/read_triangle_mesh.h), and the arguments that
// icm_param refuses together are refused together, for the same reason.

#include "icm_param_energy.h"

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/border/Border_conditions.h>
#include <ICM/measures/Distortion.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/parameterize.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using Kernel = icm_param::Kernel;
using Mesh = icm_param::Mesh;
using Corner_uv_map = icm_param::Corner_uv_map;
namespace SMP = CGAL::Surface_mesh_parameterization;
/// The mesh's vertices that each row of V became: none for a dropped vertex, several for a
/// split one (icm_param's `vertices_by_file_index`).
using Vertices_by_row = std::vector<std::vector<Mesh::Vertex_index>>;

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

std::string shape_of(const py::array& a)
{
  return py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())))).cast<std::string>();
}

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
    throw Icm_error(std::string(what) + " must have shape (n, " + std::to_string(columns) + "), not " + shape_of(any));
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

/// How an array of indices is named in its refusals.
struct Index_array
{
  const char* what;  ///< "F"
  const char* shape; ///< "(m, 3)": the shape asked for
  const char* empty; ///< what an empty array lacks: "no faces"
  const char* into;  ///< the array it indexes: "V"
  py::ssize_t columns;
};

/// `object` as a C-contiguous (rows, `a.columns`) array of indices below `bound`, or
/// `Icm_error` naming the row at fault.
py::array_t<std::int64_t, py::array::c_style> index_rows(const py::object& object, std::size_t bound,
                                                         const Index_array& a)
{
  const std::string what = a.what;
  const py::array any = py::array::ensure(object);
  if(!any)
    throw Icm_error(what + " must be an array of integers (numpy.ndarray)");
  const char kind = any.dtype().kind();
  if(kind != 'i' && kind != 'u')
    throw Icm_error(what + " must hold integers (indices), not dtype " + py::str(any.dtype()).cast<std::string>());
  if(any.ndim() != 2 || any.shape(1) != a.columns)
    throw Icm_error(what + " must have shape " + a.shape + ", not " + shape_of(any));
  if(any.shape(0) == 0)
    throw Icm_error(what + " is empty (" + a.empty + ")");
  auto rows = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(any);
  if(!rows)
    throw Icm_error(what + " cannot be converted to int64");
  const std::int64_t* data = rows.data();
  for(py::ssize_t i = 0; i < rows.size(); ++i)
    if(data[i] < 0 || static_cast<std::uint64_t>(data[i]) >= bound)
      throw Icm_error(what + " row " + std::to_string(i / a.columns) + " has index " + std::to_string(data[i]) +
                      " out of range: " + a.into + " has " + std::to_string(bound) + " rows");
  return rows;
}

const Index_array faces_of_V{"F", "(m, 3)", "no faces", "V", 3};
const Index_array faces_of_uv{"fuv", "(m, 3)", "no faces", "uv", 3};
const Index_array edges_of_V{"seams", "(s, 2)", "no edges; seams=None cuts where the topology needs it", "V", 2};

/// V and F checked and made a triangle mesh by ICM's soup checks (the repairs in `read`),
/// or `Icm_error` with the reason.
Mesh mesh_of(const py::object& V, const py::object& F, ICM::IO::Mesh_reading_report& read)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), faces_of_V);
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
  auto corners = index_rows(fuv, static_cast<std::size_t>(uvs.shape(0)), faces_of_uv);
  if(corners.shape(0) != faces)
    throw Icm_error("fuv has " + std::to_string(corners.shape(0)) + " rows and F " + std::to_string(faces) +
                    ": one row per face in both");
  return {uvs, corners};
}

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

// --- the arguments of parameterize ----------------------------------------------------------

/// The names `energy`, `metric` and `boundary` take, the default first: icm_param's
/// --energy, --metric and --boundary.
const std::vector<std::string>& energy_names()
{
  static const std::vector<std::string> names = {ICM::Curvature_entropy::name, ICM::U_square::name,
                                                 ICM::Area_distortion::name, ICM::Angle_distortion::name,
                                                 ICM::Log_area_distortion::name};
  return names;
}

const std::vector<std::string>& metric_names()
{
  static const std::vector<std::string> names = {ICM::Intrinsic_delaunay_metric::name, ICM::Vertex_scaling_metric::name,
                                                 ICM::Inversive_distance_metric::name,
                                                 ICM::Circle_packing_metric::name};
  return names;
}

const std::vector<std::string>& boundary_names()
{
  static const std::vector<std::string> names = {"free", "circle", "square", "circle-domain"};
  return names;
}

/// Nothing if `value` is one of `names`, else `Icm_error` listing them.
void check_choice(const std::string& what, const std::string& value, const std::vector<std::string>& names)
{
  if(std::find(names.begin(), names.end(), value) != names.end())
    return;
  std::string known;
  for(const std::string& name : names)
    known += (known.empty() ? "" : ", ") + name;
  throw Icm_error(what + " '" + value + "' is not one of " + known);
}

/// The arguments of `icm.parameterize` but the arrays, each checked: what icm_param's
/// `Arguments` hold once its command line is parsed.
struct Request
{
  std::string energy, metric, boundary;
  /// `cones` is a count > 0 (icm_param's `--cones N`): automatic cones on the components
  /// without user seams too, and refused with a prescribed border. `cones=0` turns them off,
  /// which is no request, and "auto" is the default, which cannot be told from none either.
  bool cones_asked = false;
  bool keep_overlaps = false;
  ICM::Surface_parameterization_options options;

  bool prescribes_border() const { return boundary != "free"; }
};

/// `cones` ("auto" or a count) into `request`, as icm_param's `--cones` sets the options.
void read_cone_count(const py::object& cones, Request& request)
{
  if(py::isinstance<py::str>(cones))
  {
    if(cones.cast<std::string>() != "auto")
      throw Icm_error("cones takes 'auto' or a count >= 0, not '" + cones.cast<std::string>() + "'");
    return;
  }
  if(!py::isinstance<py::int_>(cones) || py::isinstance<py::bool_>(cones))
    throw Icm_error("cones takes 'auto' or an int, not " + py::repr(cones).cast<std::string>());
  const long long count = cones.cast<long long>();
  if(count < 0 || count > 100000)
    throw Icm_error("cones takes 'auto' or a count from 0 to 100000, not " + std::to_string(count));
  const int max_cones = static_cast<int>(count);
  ICM::Surface_parameterization_options& options = request.options;
  // A count is exact: no stop on distortion, and a disk gets its cones too (icm_param --cones N).
  options.automatic_cones = max_cones > 0;
  options.cones.max_cones = max_cones;
  options.initial_cones = std::min(options.initial_cones, max_cones);
  options.cones.max_log_scale = 0;
  options.border_max_log_scale = 0;
  request.cones_asked = max_cones > 0;
}

/// `atlas` (None or a texture size) and `padding` into the options, as icm_param's --atlas
/// and --padding.
void read_atlas(const py::object& atlas, int padding, ICM::Surface_parameterization_options& options)
{
  if(atlas.is_none())
    return;
  if(!py::isinstance<py::int_>(atlas) || py::isinstance<py::bool_>(atlas))
    throw Icm_error("atlas takes a texture size in texels (an int) or None, not " +
                    py::repr(atlas).cast<std::string>());
  ICM::Atlas_options a;
  const long long size = atlas.cast<long long>();
  a.size = static_cast<int>(std::clamp<long long>(size, -1, 1 << 20));
  a.padding = padding;
  options.atlas = a;
}

Request request_of(const py::object& cones, const std::string& energy, const std::string& metric,
                   const std::string& boundary, const py::object& atlas, int padding, bool keep_overlaps)
{
  check_choice("energy", energy, energy_names());
  check_choice("metric", metric, metric_names());
  check_choice("boundary", boundary, boundary_names());
  Request request;
  request.energy = energy;
  request.metric = metric;
  request.boundary = boundary;
  request.keep_overlaps = keep_overlaps;
  request.options.remove_overlaps = !keep_overlaps;
  read_cone_count(cones, request);
  read_atlas(atlas, padding, request.options);
  if(const ICM::Status checked = ICM::check_options(request.options); !checked.ok())
    throw Icm_error(checked.message, static_cast<int>(checked.code));
  return request;
}

/// Why the arguments cannot go together, or empty, as icm_param refuses them before reading
/// the mesh (its `energy_conflict` and `parse_atlas`): a prescribed border leaves no choice
/// to an energy, is solved on a disk without cones or seams, and packs no atlas.
std::string border_conflict(const Request& request, bool has_cone, bool has_seams)
{
  if(!request.prescribes_border())
    return {};
  const std::string with = " cannot go with boundary='" + request.boundary + "': ";
  if(request.energy != ICM::Curvature_entropy::name)
    return "energy='" + request.energy + "'" + with +
           "a prescribed border leaves one conformal map, nothing for an energy to choose";
  const char* argument = has_cone ? "cone" : has_seams ? "seams" : request.cones_asked ? "cones" : nullptr;
  if(argument != nullptr)
    return std::string(argument) + with + "a prescribed border is solved on the mesh as it is, without cones or seams";
  if(request.options.atlas)
    return "atlas" + with + "a prescribed border is laid out by the disk parameterizer, which packs no charts";
  return {};
}

// --- cones and seams on the rows of V ---------------------------------------------------------

Vertices_by_row vertices_by_row(const ICM::IO::Mesh_reading_report& read)
{
  Vertices_by_row by_row(read.file_vertices);
  for(std::size_t i = 0; i < read.file_vertex.size(); ++i)
    by_row[read.file_vertex[i]].push_back(Mesh::Vertex_index(static_cast<Mesh::size_type>(i)));
  return by_row;
}

/// `cone`'s (row of V, degrees) as curvatures at the mesh's vertices (icm_param's --cone).
std::map<Mesh::Vertex_index, double> user_cones_of(const std::vector<std::pair<long long, double>>& cone,
                                                   const Vertices_by_row& by_row)
{
  std::map<Mesh::Vertex_index, double> cones;
  for(const auto& [vertex, degrees] : cone)
  {
    const std::string what = "cone (" + std::to_string(vertex) + ", " + std::to_string(degrees) + "): ";
    if(!(degrees > 0) || !std::isfinite(degrees))
      throw Icm_error(what + "the angle must be a finite number of degrees > 0");
    if(vertex < 0 || static_cast<std::size_t>(vertex) >= by_row.size())
      throw Icm_error(what + "V has " + std::to_string(by_row.size()) + " rows");
    if(by_row[vertex].size() != 1)
      throw Icm_error(what + "vertex " + std::to_string(vertex) +
                      (by_row[vertex].empty() ? " is in no face"
                                              : " is non-manifold and was split into " +
                                                  std::to_string(by_row[vertex].size()) + " vertices"));
    cones[by_row[vertex].front()] = 2 * M_PI - degrees * M_PI / 180;
  }
  return cones;
}

/// The edges `seams` names, an (s, 2) array of pairs of rows of V, as icm_param reads the
/// edges of a --seams file (ICM::IO::read_selection): a pair names the edge between the
/// vertices its rows became (any copy of a split vertex), each edge is kept once, in the
/// array's order. A pair that names no interior edge is refused naming its row; the library
/// would refuse a border edge too, without saying which.
std::vector<Mesh::Edge_index> user_seams_of(const py::object& seams, const Mesh& mesh, const Vertices_by_row& by_row)
{
  const auto pairs = index_rows(seams, by_row.size(), edges_of_V);
  std::vector<Mesh::Edge_index> edges;
  std::set<Mesh::Edge_index> kept;
  for(py::ssize_t r = 0; r < pairs.shape(0); ++r)
  {
    const std::int64_t a = pairs.at(r, 0), b = pairs.at(r, 1);
    const std::string row =
      "seams row " + std::to_string(r) + " (" + std::to_string(a) + ", " + std::to_string(b) + "): ";
    if(a == b)
      throw Icm_error(row + "a vertex paired with itself is not an edge");
    for(const std::int64_t v : {a, b})
      if(by_row[v].empty())
        throw Icm_error(row + "vertex " + std::to_string(v) + " is in no face");
    std::optional<Mesh::Halfedge_index> found;
    for(Mesh::Vertex_index u : by_row[a])
      for(Mesh::Vertex_index w : by_row[b])
        if(const auto [h, joined] = halfedge(u, w, mesh); joined && !found)
          found = h;
    if(!found)
      throw Icm_error(row + "vertices " + std::to_string(a) + " and " + std::to_string(b) +
                      " are not joined by an edge of the mesh");
    const Mesh::Edge_index e = edge(*found, mesh);
    if(is_border(e, mesh))
      throw Icm_error(row + "a border edge (the border is cut already)");
    if(kept.insert(e).second)
      edges.push_back(e);
  }
  return edges;
}

// --- the runs ---------------------------------------------------------------------------------

/// What the report says of a run of either parameterizer, as icm_param's JSON line reads it
/// (its `Run_figures`): totals over the charts, the worst of each check.
struct Run_figures
{
  ICM::Surface_summary summary;
  std::size_t components = 1, seam_edges = 0;
  double seam_length = 0; ///< over the square root of the 3D area
  std::string energy = ICM::Curvature_entropy::name;
  std::optional<ICM::Energy_summary> energy_run; ///< an energy other than the entropy
  std::string boundary = "free";
  int degenerate_faces = 0, border_iterations = 0; ///< a prescribed border
  double circle_deviation = 0;
  int atlas_charts = 0, atlas_rotated_charts = 0;
  double atlas_utilization = 0;
  double seconds_index = 0, seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_total = 0;
};

/// `ICM::parameterize`'s run of `energy`, which cut `seams`.
Run_figures figures_of(const ICM::Surface_parameterization_report& r, const Mesh& mesh,
                       const std::vector<Mesh::Edge_index>& seams, const std::string& energy)
{
  Run_figures t;
  t.summary = ICM::surface_summary(r);
  t.components = r.charts.size();
  t.seam_edges = seams.size();
  t.seam_length = ICM::seam_length_over_root_area(mesh, seams);
  t.energy = energy;
  if(energy != ICM::Curvature_entropy::name)
    t.energy_run = ICM::energy_summary(r);
  t.atlas_charts = r.atlas_charts;
  t.atlas_rotated_charts = r.atlas_rotated_charts;
  t.atlas_utilization = r.atlas_utilization;
  t.seconds_index = r.seconds_index;
  t.seconds_cones = r.seconds_cones;
  t.seconds_optimum = r.seconds_optimum;
  t.seconds_cut = r.seconds_cut;
  t.seconds_layout = r.seconds_layout;
  t.seconds_total = r.seconds_total;
  return t;
}

/// `Inverse_curvature_map_parameterizer_3`'s run with a prescribed border: one chart, never
/// cut, so that no overlap was removed (both overlap counts are the raw one).
Run_figures figures_of(const ICM::Parameterization_report& r)
{
  Run_figures t;
  ICM::Surface_summary& s = t.summary;
  s.charts = 1;
  s.genus = r.genus;
  s.boundary_loops = r.boundary_loops;
  s.newton_iterations = r.newton_iterations;
  s.moved_vertices = r.moved_vertices;
  s.overlapping_border_edges = s.raw_overlapping_border_edges = r.overlapping_border_edges;
  s.max_curvature_error = r.max_curvature_error;
  s.max_layout_length_error = r.max_layout_length_error;
  s.metrics = r.metric;
  s.layouts = r.layout;
  s.fallback_reason = r.fallback_reason;
  t.boundary = r.border_condition;
  t.degenerate_faces = r.degenerate_faces;
  t.border_iterations = r.border_iterations;
  t.circle_deviation = r.circle_deviation;
  t.seconds_index = r.seconds_index;
  t.seconds_optimum = r.seconds_optimum;
  t.seconds_layout = r.seconds_layout;
  t.seconds_total = r.seconds_total;
  return t;
}

/// The failure of a run as icm.Error: the library's reason and its code.
[[noreturn]] void fail_run(SMP::Error_code status, const std::string& message)
{
  throw Icm_error(std::string(ICM::error_message(status)) + ": " + message, static_cast<int>(status));
}

/// ICM::parameterize with the energy and metric asked, as icm_param's `run_surface` calls it:
/// a user's cut is the whole singular set unless `cones` asked for automatic cones besides.
Run_figures run_surface(const Request& request, const Mesh& mesh, Corner_uv_map uv,
                        const std::map<Mesh::Vertex_index, double>& cones,
                        const std::vector<Mesh::Edge_index>& user_seams, std::vector<Mesh::Edge_index>& seams)
{
  ICM::Surface_parameterization_options options = request.options;
  if(!user_seams.empty() && !request.cones_asked)
    options.automatic_cones = false;
  const std::string& metric = request.metric;
  ICM::Surface_parameterization_report report;
  {
    py::gil_scoped_release released;
    using namespace icm_param;
    report = request.energy == ICM::U_square::name
               ? parameterize_surface<ICM::U_square>(mesh, metric, uv, options, cones, seams, user_seams)
             : request.energy == ICM::Area_distortion::name
               ? parameterize_surface<ICM::Area_distortion>(mesh, metric, uv, options, cones, seams, user_seams)
             : request.energy == ICM::Angle_distortion::name
               ? parameterize_surface<ICM::Angle_distortion>(mesh, metric, uv, options, cones, seams, user_seams)
             : request.energy == ICM::Log_area_distortion::name
               ? parameterize_surface<ICM::Log_area_distortion>(mesh, metric, uv, options, cones, seams, user_seams)
               : parameterize_surface<ICM::Curvature_entropy>(mesh, metric, uv, options, cones, seams, user_seams);
  }
  if(report.status != SMP::OK)
    fail_run(report.status, report.message);
  return figures_of(report, mesh, seams, request.energy);
}

/// Inverse_curvature_map_parameterizer_3 with the border asked, on a disk (a circle domain:
/// genus 0 with borders), as icm_param's `run_border`; refused as icm_param refuses it: not
/// the surface the border needs, or a map that folds over itself unless `keep_overlaps`
/// (one chart with a UV per vertex cannot be cut apart where it folds, as a free border's is).
Run_figures run_border(const Request& request, Mesh& mesh, Corner_uv_map uv)
{
  if(const std::string refused =
       icm_param::why_the_border_is_refused("boundary='" + request.boundary + "'", request.boundary, mesh);
     !refused.empty())
    throw Icm_error(refused, static_cast<int>(SMP::ERROR_NO_TOPOLOGICAL_DISC));
  ICM::Parameterization_report report;
  {
    py::gil_scoped_release released;
    using namespace icm_param;
    report = request.boundary == "circle"   ? parameterize_disk<ICM::Circular_border<Mesh>>(mesh, request.metric, uv)
             : request.boundary == "square" ? parameterize_disk<ICM::Square_border<Mesh>>(mesh, request.metric, uv)
                                            : parameterize_disk<ICM::Circle_domain>(mesh, request.metric, uv);
  }
  if(report.status != SMP::OK)
    fail_run(report.status, report.message);
  if(report.overlapping_border_edges > 0 && !request.keep_overlaps)
    fail_run(SMP::ERROR_NO_1_TO_1_MAPPING,
             "the map with the " + request.boundary + " border folds over itself (" +
               std::to_string(report.overlapping_border_edges) +
               " pairs of border edges cross) and is one chart, not cut where it overlaps (with a free border it "
               "is); keep_overlaps=True returns it anyway");
  return figures_of(report);
}

// --- the result -------------------------------------------------------------------------------

/// The result of `icm.parameterize`.
struct Parameterization
{
  py::array_t<double> uv;
  py::array_t<std::int64_t> fuv;
  int charts = 0;
  py::array_t<std::int64_t> seams;
  py::dict report;
};

/// The run's figures under the keys of icm_param's JSON line (doc/cli.md), in its order.
py::dict report_dict(const Mesh& mesh, const Run_figures& t, const Request& request,
                     const ICM::IO::Mesh_reading_report& read, const ICM::Distortion_measures& m)
{
  const ICM::Surface_summary& s = t.summary;
  py::dict d;
  d["vertices"] = num_vertices(mesh);
  d["faces"] = num_faces(mesh);
  d["charts"] = s.charts;
  d["components"] = t.components;
  d["boundary_loops"] = s.boundary_loops;
  d["genus"] = s.genus;
  d["cones"] = s.cones;
  d["cones_above_full_turn"] = s.wide_cones;
  d["cones_given_up"] = s.cones_given_up;
  d["seam_edges"] = t.seam_edges;
  d["seam_length"] = t.seam_length;
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
  d["energy"] = t.energy;
  if(t.energy_run)
  {
    d["energy_iterations"] = t.energy_run->iterations;
    d["initial_energy"] = t.energy_run->initial_energy;
    d["final_energy"] = t.energy_run->final_energy;
    d["energy_message"] = t.energy_run->message;
  }
  d["boundary"] = t.boundary;
  if(t.boundary != "free")
  {
    d["degenerate_faces"] = t.degenerate_faces;
    d["border_iterations"] = t.border_iterations;
    d["circle_deviation"] = t.circle_deviation;
  }
  if(const std::optional<ICM::Atlas_options>& atlas = request.options.atlas)
  {
    d["atlas_size"] = atlas->size;
    d["atlas_padding"] = atlas->padding;
    d["atlas_packer"] = ICM::atlas_packer_name(atlas->packer);
    d["atlas_charts"] = t.atlas_charts;
    d["atlas_rotated_charts"] = t.atlas_rotated_charts;
    d["atlas_utilization"] = t.atlas_utilization;
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
  d["seconds_index"] = t.seconds_index;
  d["seconds_cones"] = t.seconds_cones;
  d["seconds_optimum"] = t.seconds_optimum;
  d["seconds_cut"] = t.seconds_cut;
  d["seconds_layout"] = t.seconds_layout;
  d["seconds_parameterize"] = t.seconds_total;
  return d;
}

/// The UVs of `uvmap` on the rows of F and the seams on the rows of V: face f of the mesh is
/// row f of F (no face is added or dropped), whose corners may have been reversed (a
/// reoriented face) or renumbered (a dropped or split vertex).
Parameterization result_of(const py::object& F, const Mesh& mesh, Corner_uv_map uvmap,
                           const std::vector<Mesh::Edge_index>& seams, const ICM::IO::Mesh_reading_report& read)
{
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);
  const auto faces = index_rows(F, read.file_vertices, faces_of_V);
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
  return result;
}

/// " (the input was repaired: ...)", or empty: a failure after the repairs names them, as
/// icm_param's do, since they may be why (a dropped vertex).
std::string repairs_note(const ICM::IO::Mesh_reading_report& read)
{
  std::string note;
  for(const std::string& repair : read.repairs())
    note += (note.empty() ? " (the input was repaired: " : "; ") + repair;
  return note.empty() ? note : note + ")";
}

Parameterization parameterize(const py::object& V, const py::object& F, const py::object& cones,
                              const std::vector<std::pair<long long, double>>& cone, const std::string& energy,
                              const py::object& atlas, int padding, const py::object& seams, const std::string& metric,
                              const std::string& boundary, bool keep_overlaps)
{
  const Request request = request_of(cones, energy, metric, boundary, atlas, padding, keep_overlaps);
  if(const std::string conflict = border_conflict(request, !cone.empty(), !seams.is_none()); !conflict.empty())
    throw Icm_error(conflict);
  ICM::IO::Mesh_reading_report read;
  Mesh mesh = mesh_of(V, F, read);
  try
  {
    const Vertices_by_row by_row = vertices_by_row(read);
    const std::map<Mesh::Vertex_index, double> user_cones = user_cones_of(cone, by_row);
    const std::vector<Mesh::Edge_index> user_seams =
      seams.is_none() ? std::vector<Mesh::Edge_index>() : user_seams_of(seams, mesh, by_row);
    const Corner_uv_map uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
    std::vector<Mesh::Edge_index> cut;
    const Run_figures figures = request.prescribes_border()
                                  ? run_border(request, mesh, uvmap)
                                  : run_surface(request, mesh, uvmap, user_cones, user_seams, cut);
    Parameterization result = result_of(F, mesh, uvmap, cut, read);
    result.report = report_dict(mesh, figures, request, read, ICM::measure_distortion_corner_uv(mesh, uvmap));
    result.charts = figures.summary.charts;
    return result;
  }
  catch(const Icm_error& e)
  {
    throw Icm_error(e.what() + repairs_note(read), e.code);
  }
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
  m.attr("METRICS") = py::cast(metric_names());
  m.attr("BOUNDARIES") = py::cast(boundary_names());
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
        py::arg("atlas") = py::none(), py::arg("padding") = 4, py::arg("seams") = py::none(),
        py::arg("metric") = ICM::Default_metric::name, py::arg("boundary") = "free", py::arg("keep_overlaps") = false,
        R"(Parameterizes a triangle mesh (any topology) with ICM::parameterize, or a disk with a
prescribed border; each argument is the icm_param option of the same name (doc/cli.md).

V: float64 array (n, 3) of vertex positions; F: integer array (m, 3) of rows of V.
cones: "auto" (cones where the distortion asks for them) or an exact count of automatic
  cones (0: only the border and the user's cones and seams are singular).
cone: list of (vertex, degrees): vertices that must be cones with that total angle.
energy: one of icm.ENERGIES ("entropy", "u-square", "area", "angle", "log-area"); another
  energy than the entropy is minimised from the entropy optimum with its cones.
atlas: None (the charts at their 3D scale, side by side) or a texture size in texels: every
  chart in [0, 1]^2, `padding` texels apart.
seams: None, or an integer array (s, 2) of pairs of rows of V joined by an interior edge
  (icm_param --seams FILE): a component with any is cut along exactly these edges, their ends
  and branch points are its cones, whose angles the optimum chooses, and it gets no automatic
  cone; the components without any get automatic cones only when `cones` is a count.
metric: one of icm.METRICS ("intrinsic-delaunay", "vertex-scaling", "inversive-distance",
  "circle-packing"), with any energy and border.
boundary: one of icm.BOUNDARIES: "free", or "circle" or "square" (a disk's border on a circle
  or a square) or "circle-domain" (genus 0, every border loop a circle): the entropy's map
  with that border, without energy, cone, cones (but 0), seams or atlas.
keep_overlaps: keep a chart that folds over itself rather than cut it into pieces that do
  not; with a prescribed border (one chart, never cut) return such a map rather than fail.
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
