// icm_param: parameterize any triangle mesh file with the inverse curvature map (cones and
// seams where its topology needs them, one chart per connected component) and write the UV'd
// OBJ (a vt per corner side of every seam), optionally an SVG of the layout and a JSON line.
//
//   icm_param INPUT -o OUTPUT.obj [--svg FILE] [--json]
//             [--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing]
//             [--cones auto|N] [--cone VERTEX:DEGREES]... [--seams FILE.selection.txt]
//             [--keep-overlaps]
//
// On any failure it prints one line on stderr naming the reason, exits non-zero and writes
// no file (outputs are written to a temporary file and renamed into place).

#include <ICM/Distortion.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/read_seam_selection.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/parameterize.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;

struct Arguments
{
  std::string input, output, svg, seams;
  bool json = false, keep_overlaps = false;
  std::string metric = ICM::Default_metric::name;
  int max_cones = -1;                     // -1: automatic
  std::vector<std::pair<int, double>> cones; // vertex index, cone angle in degrees
};

const char* const usage =
  "usage: icm_param INPUT -o OUTPUT.obj [--svg FILE] [--json] "
  "[--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing] "
  "[--cones auto|N] [--cone VERTEX:DEGREES]... [--seams FILE.selection.txt] [--keep-overlaps]\n";

int fail(const std::string& reason, int code = 1)
{
  std::cerr << "icm_param: " << reason << "\n";
  return code;
}

bool parse_arguments(int argc, char** argv, Arguments& args, std::string& error)
{
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&](std::string& out) {
      if(i + 1 >= argc)
      {
        error = a + " needs a value";
        return false;
      }
      out = argv[++i];
      return true;
    };
    if(a == "-o" || a == "--output")
    {
      if(!value(args.output))
        return false;
    }
    else if(a == "--svg")
    {
      if(!value(args.svg))
        return false;
    }
    else if(a == "--seams")
    {
      if(!value(args.seams))
        return false;
    }
    else if(a == "--json")
      args.json = true;
    else if(a == "--keep-overlaps")
      args.keep_overlaps = true;
    else if(a == "--cones")
    {
      std::string v;
      if(!value(v))
        return false;
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if(v == "auto")
        args.max_cones = -1;
      else if(!v.empty() && *end == '\0' && n >= 0 && n <= 100000)
        args.max_cones = static_cast<int>(n);
      else
      {
        error = "--cones takes 'auto' or a count, not '" + v + "'";
        return false;
      }
    }
    else if(a == "--cone")
    {
      std::string v;
      if(!value(v))
        return false;
      const std::size_t colon = v.find(':');
      char *end_vertex = nullptr, *end_angle = nullptr;
      const long vertex = colon == std::string::npos ? -1 : std::strtol(v.c_str(), &end_vertex, 10);
      const double degrees = colon == std::string::npos ? 0 : std::strtod(v.c_str() + colon + 1, &end_angle);
      if(colon == std::string::npos || end_vertex != v.c_str() + colon || vertex < 0 ||
         *end_angle != '\0' || !(degrees > 0) || !std::isfinite(degrees))
      {
        error = "--cone takes VERTEX:DEGREES with a vertex index >= 0 and an angle > 0, not '" + v + "'";
        return false;
      }
      args.cones.push_back({static_cast<int>(vertex), degrees});
    }
    else if(a == "--metric")
    {
      if(!value(args.metric))
        return false;
      if(args.metric != ICM::Intrinsic_delaunay_metric::name &&
         args.metric != ICM::Vertex_scaling_metric::name &&
         args.metric != ICM::Inversive_distance_metric::name &&
         args.metric != ICM::Circle_packing_metric::name)
      {
        error = "unknown metric '" + args.metric +
                "' (intrinsic-delaunay, vertex-scaling, inversive-distance or circle-packing)";
        return false;
      }
    }
    else if(!a.empty() && a[0] == '-')
    {
      error = "unknown option " + a;
      return false;
    }
    else if(args.input.empty())
      args.input = a;
    else
    {
      error = "more than one input file";
      return false;
    }
  }
  if(args.input.empty())
    error = "no input file";
  else if(args.output.empty())
    error = "no output file (-o OUTPUT.obj)";
  return error.empty();
}

/// The reason the tool cannot take this mesh, or empty.
std::string check_input(const Mesh& mesh)
{
  if(faces(mesh).empty())
    return "the mesh has no faces";
  if(!CGAL::is_triangle_mesh(mesh))
    return "the mesh has non-triangle faces (triangulate it first)";
  return {};
}

std::string json_number(double x)
{
  if(!std::isfinite(x))
    return "null";
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

std::string json_string(const std::string& s)
{
  std::string out = "\"";
  for(char c : s)
  {
    if(c == '"' || c == '\\')
      out += '\\';
    if(static_cast<unsigned char>(c) < 0x20)
      continue;
    out += c;
  }
  return out + "\"";
}

} // namespace

int main(int argc, char** argv)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };

  Arguments args;
  std::string error;
  if(!parse_arguments(argc, argv, args, error))
  {
    std::cerr << usage;
    return fail(error, 2);
  }

  Clock::time_point t = Clock::now();
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(args.input, mesh))
    return fail("cannot read '" + args.input +
                "' as a polygon mesh (missing, unreadable, unsupported format or non-manifold)");
  const double seconds_read = since(t);
  for(Mesh::Vertex_index v : vertices(mesh))
  {
    const Kernel::Point_3& p = mesh.point(v);
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      return fail("vertex " + std::to_string(std::size_t(v)) +
                  " has a non-finite coordinate (NaN or inf)");
  }
  const std::string unsupported = check_input(mesh);
  if(!unsupported.empty())
    return fail(unsupported);

  ICM::Surface_parameterization_options options;
  options.remove_overlaps = !args.keep_overlaps;
  if(args.max_cones >= 0)
  {
    options.automatic_cones = args.max_cones > 0;
    options.cones.max_cones = args.max_cones;
    options.initial_cones = std::min(options.initial_cones, args.max_cones);
  }
  std::map<Mesh::Vertex_index, double> cones;
  for(const auto& [vertex, degrees] : args.cones)
  {
    if(static_cast<std::size_t>(vertex) >= num_vertices(mesh))
      return fail("--cone " + std::to_string(vertex) + ": the mesh has " +
                  std::to_string(num_vertices(mesh)) + " vertices");
    cones[Mesh::Vertex_index(static_cast<Mesh::size_type>(vertex))] = 2 * M_PI - degrees * M_PI / 180;
  }
  std::vector<Mesh::Edge_index> user_seams;
  if(!args.seams.empty() && !ICM::IO::read_seam_selection(args.seams, mesh, user_seams, error))
    return fail(error);
  auto uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  std::vector<Mesh::Edge_index> seams;
  ICM::Surface_parameterization_report report;
  auto run = [&](auto metric) {
    return ICM::parameterize<decltype(metric)>(mesh, uvmap, options, cones, &seams, user_seams);
  };
  report = args.metric == ICM::Circle_packing_metric::name      ? run(ICM::Circle_packing_metric())
           : args.metric == ICM::Inversive_distance_metric::name ? run(ICM::Inversive_distance_metric())
           : args.metric == ICM::Vertex_scaling_metric::name     ? run(ICM::Vertex_scaling_metric())
                                                                 : run(ICM::Intrinsic_delaunay_metric());
  if(report.status != SMP::OK)
    return fail(std::string(ICM::error_message(report.status)) + ": " + report.message);

  t = Clock::now();
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);
  if(!ICM::IO::write_uv_obj(args.output, uv_mesh, error))
    return fail(error);
  if(!args.svg.empty())
  {
    ICM::IO::Svg_options svg_options;
    svg_options.title = args.input.substr(args.input.find_last_of("/\\") + 1) + " — ICM";
    if(!ICM::IO::write_uv_svg(args.svg, uv_mesh, error, svg_options))
      return fail(error);
  }
  const double seconds_write = since(t);
  const ICM::Distortion_measures measures = ICM::measure_distortion_corner_uv(mesh, uvmap);

  // Totals over the charts, and the worst of each check.
  int cone_count = 0, genus = 0, loops = 0, newton = 0, overlaps = 0, raw_overlaps = 0, pieces = 0, moved = 0;
  double curvature_error = 0, length_error = 0, seam_error = 0;
  std::string metrics, fallbacks;
  for(const ICM::Chart_report& c : report.charts)
  {
    cone_count += static_cast<int>(c.cones.size());
    genus += c.genus;
    loops += c.boundary_loops;
    newton = std::max(newton, c.newton_iterations);
    overlaps += c.overlapping_border_edges;
    raw_overlaps += c.raw_overlapping_border_edges;
    pieces += c.pieces;
    moved += c.moved_vertices;
    curvature_error = std::max(curvature_error, c.max_curvature_error);
    length_error = std::max(length_error, c.max_layout_length_error);
    seam_error = std::max(seam_error, c.seam_length_error);
    if(metrics.find(c.metric) == std::string::npos)
      metrics += (metrics.empty() ? "" : ",") + c.metric;
    if(!c.fallback_reason.empty() && fallbacks.empty())
      fallbacks = c.fallback_reason;
  }

  if(args.json)
  {
    std::cout << "{\"input\":" << json_string(args.input) << ",\"output\":" << json_string(args.output)
              << ",\"vertices\":" << num_vertices(mesh) << ",\"faces\":" << num_faces(mesh)
              << ",\"charts\":" << pieces << ",\"components\":" << report.charts.size()
              << ",\"boundary_loops\":" << loops << ",\"genus\":" << genus
              << ",\"cones\":" << cone_count << ",\"seam_edges\":" << seams.size()
              << ",\"layout\":\"propagation\""
              << ",\"newton_iterations\":" << newton
              << ",\"max_curvature_error\":" << json_number(curvature_error)
              << ",\"max_layout_length_error\":" << json_number(length_error)
              << ",\"seam_length_error\":" << json_number(seam_error)
              << ",\"overlapping_border_edges\":" << overlaps
              << ",\"raw_overlapping_border_edges\":" << raw_overlaps
              << ",\"moved_vertices\":" << moved
              << ",\"metric\":" << json_string(metrics)
              << ",\"metric_fallback\":" << json_string(fallbacks)
              << ",\"flipped_faces\":" << measures.flipped_faces
              << ",\"log_area_distortion\":" << json_number(measures.log_area_distortion)
              << ",\"area_ratio_min\":" << json_number(measures.area_ratio_min)
              << ",\"area_ratio_max\":" << json_number(measures.area_ratio_max)
              << ",\"qc_mean\":" << json_number(measures.qc_mean)
              << ",\"seconds_read\":" << json_number(seconds_read)
              << ",\"seconds_cones\":" << json_number(report.seconds_cones)
              << ",\"seconds_optimum\":" << json_number(report.seconds_optimum)
              << ",\"seconds_cut\":" << json_number(report.seconds_cut)
              << ",\"seconds_layout\":" << json_number(report.seconds_layout)
              << ",\"seconds_parameterize\":" << json_number(report.seconds_total)
              << ",\"seconds_write\":" << json_number(seconds_write)
              << ",\"seconds_total\":" << json_number(since(start)) << "}\n";
  }
  else
  {
    std::cerr << args.input << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh)
              << " faces, " << report.charts.size() << " chart(s), " << cone_count << " cones, "
              << seams.size() << " seam edges, " << newton << " Newton iterations, max |k| "
              << curvature_error << ", " << measures.flipped_faces
              << " flipped faces, log area distortion " << measures.log_area_distortion << ", "
              << report.seconds_total << " s -> " << args.output << "\n";
  }
  return 0;
}
