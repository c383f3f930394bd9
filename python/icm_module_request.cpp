// The arguments of `icm.parameterize` but V and F (icm_module_request.h).

#include "icm_module_request.h"

#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

namespace icm_module {

namespace {

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

} // namespace

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

Vertices_by_row vertices_by_row(const ICM::IO::Mesh_reading_report& read)
{
  Vertices_by_row by_row(read.file_vertices);
  for(std::size_t i = 0; i < read.file_vertex.size(); ++i)
    by_row[read.file_vertex[i]].push_back(Mesh::Vertex_index(static_cast<Mesh::size_type>(i)));
  return by_row;
}

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

} // namespace icm_module
