// icm_param: parameterize a mesh file with the inverse curvature map and write the UV'd OBJ,
// optionally an SVG of the layout and a JSON line of figures.
//
//   icm_param INPUT -o OUTPUT.obj [--svg FILE] [--json] [--layout auto|propagation|harmonic]
//             [--metric vertex-scaling|inversive-distance|circle-packing]
//
// On any failure it prints one line on stderr naming the reason, exits non-zero and writes
// no file (outputs are written to a temporary file and renamed into place).

#include <ICM/Distortion.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/helpers.h>

#include <chrono>
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
  std::string input, output, svg;
  bool json = false;
  ICM::Layout_method layout = ICM::Layout_method::Automatic;
  std::string metric = ICM::Default_metric::name;
};

const char* const usage =
  "usage: icm_param INPUT -o OUTPUT.obj [--svg FILE] [--json] "
  "[--layout auto|propagation|harmonic] "
  "[--metric vertex-scaling|inversive-distance|circle-packing]\n";

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
    else if(a == "--json")
      args.json = true;
    else if(a == "--layout")
    {
      std::string v;
      if(!value(v))
        return false;
      if(v == "auto")
        args.layout = ICM::Layout_method::Automatic;
      else if(v == "propagation")
        args.layout = ICM::Layout_method::Propagation;
      else if(v == "harmonic")
        args.layout = ICM::Layout_method::Harmonic;
      else
      {
        error = "unknown layout '" + v + "' (auto, propagation or harmonic)";
        return false;
      }
    }
    else if(a == "--metric")
    {
      if(!value(args.metric))
        return false;
      if(args.metric != ICM::Vertex_scaling_metric::name &&
         args.metric != ICM::Inversive_distance_metric::name &&
         args.metric != ICM::Circle_packing_metric::name)
      {
        error = "unknown metric '" + args.metric +
                "' (vertex-scaling, inversive-distance or circle-packing)";
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

/// The reason the tool cannot take this mesh yet, or empty when it is a disk it can take.
std::string check_input(Mesh& mesh)
{
  if(faces(mesh).empty())
    return "the mesh has no faces";
  if(!CGAL::is_triangle_mesh(mesh))
    return "the mesh has non-triangle faces (triangulate it first)";
  auto component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:icm_cc").first;
  const std::size_t components = PMP::connected_components(mesh, component);
  if(components > 1)
    return std::to_string(components) + " connected components: parameterize one at a time";
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  const int loops = static_cast<int>(borders.size());
  const int chi = static_cast<int>(num_vertices(mesh)) - static_cast<int>(num_edges(mesh)) +
                  static_cast<int>(num_faces(mesh));
  const int genus = (2 - chi - loops) / 2;
  if(loops != 1 || genus != 0)
    return std::to_string(loops) + " boundary loop" + (loops == 1 ? "" : "s") + ", genus " +
           std::to_string(genus) + ": not a disk";
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

  const Mesh::Halfedge_index bhd = PMP::longest_border(mesh).first;
  auto uvmap = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  ICM::Parameterization_options options;
  options.layout = args.layout;
  ICM::Parameterization_report report;
  auto run = [&](auto metric) {
    using Metric = decltype(metric);
    ICM::Inverse_curvature_map_parameterizer_3<Mesh, Metric> parameterizer(options);
    const SMP::Error_code code = SMP::parameterize(mesh, parameterizer, bhd, uvmap);
    report = parameterizer.report();
    return code;
  };
  const SMP::Error_code status = args.metric == ICM::Circle_packing_metric::name ? run(ICM::Circle_packing_metric())
                                 : args.metric == ICM::Inversive_distance_metric::name
                                   ? run(ICM::Inversive_distance_metric())
                                   : run(ICM::Vertex_scaling_metric());
  if(status != SMP::OK)
    return fail(std::string(ICM::error_message(status)) + ": " + report.message);

  t = Clock::now();
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh(mesh, uvmap);
  if(!ICM::IO::write_uv_obj(args.output, uv_mesh, error))
    return fail(error);
  if(!args.svg.empty())
  {
    ICM::IO::Svg_options svg_options;
    svg_options.title = args.input.substr(args.input.find_last_of("/\\") + 1) + " — ICM free boundary";
    if(!ICM::IO::write_uv_svg(args.svg, uv_mesh, error, svg_options))
      return fail(error);
  }
  const double seconds_write = since(t);
  const ICM::Distortion_measures measures = ICM::measure_distortion(mesh, uvmap);

  if(args.json)
  {
    std::cout << "{\"input\":" << json_string(args.input) << ",\"output\":" << json_string(args.output)
              << ",\"vertices\":" << report.vertices << ",\"faces\":" << report.faces
              << ",\"boundary_loops\":" << report.boundary_loops << ",\"genus\":" << report.genus
              << ",\"layout\":" << json_string(report.layout)
              << ",\"newton_iterations\":" << report.newton_iterations
              << ",\"max_curvature_error\":" << json_number(report.max_curvature_error)
              << ",\"max_layout_length_error\":" << json_number(report.max_layout_length_error)
              << ",\"metric\":" << json_string(report.metric)
              << ",\"metric_summary\":" << json_string(report.metric_summary)
              << ",\"metric_fallback\":" << json_string(report.fallback_reason)
              << ",\"flipped_faces\":" << measures.flipped_faces
              << ",\"log_area_distortion\":" << json_number(measures.log_area_distortion)
              << ",\"area_ratio_min\":" << json_number(measures.area_ratio_min)
              << ",\"area_ratio_max\":" << json_number(measures.area_ratio_max)
              << ",\"qc_mean\":" << json_number(measures.qc_mean)
              << ",\"seconds_read\":" << json_number(seconds_read)
              << ",\"seconds_index\":" << json_number(report.seconds_index)
              << ",\"seconds_metric\":" << json_number(report.seconds_metric)
              << ",\"seconds_optimum\":" << json_number(report.seconds_optimum)
              << ",\"seconds_layout\":" << json_number(report.seconds_layout)
              << ",\"seconds_parameterize\":" << json_number(report.seconds_total)
              << ",\"seconds_write\":" << json_number(seconds_write)
              << ",\"seconds_total\":" << json_number(since(start)) << "}\n";
  }
  else
  {
    std::cerr << args.input << ": " << report.vertices << " vertices, " << report.faces
              << " faces, " << report.newton_iterations << " Newton iterations, max interior |k| "
              << report.max_curvature_error << ", " << measures.flipped_faces
              << " flipped faces, log area distortion " << measures.log_area_distortion << ", "
              << report.seconds_total << " s -> " << args.output << "\n";
  }
  return 0;
}
