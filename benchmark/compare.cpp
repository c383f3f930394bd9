// compare: runs ICM's parameterizers and CGAL's on the same meshes and prints the paper's
// Table I (conformality, angle distortion, L2 shear, L2 stretch, log area distortion) plus
// wall time, peak memory, flipped faces and quasi-conformal ratios, as Markdown or JSON lines.
//
//   compare [--json] [--runs N] [--time-limit SECONDS] [--methods a,b,c] [--subdivide K]
//           [--open] [--svg-panels FILE] [--quiet] MESH...
//
// A topological disk goes through CGAL's parameterize() with every method of the registry
// (ICM's rows, in each metric and with each energy, show the report's optimum time and the
// energy optimizer's steps and values).
// Any other connected mesh (closed, genus > 0, several boundary loops) is parameterized by
// ICM's one call, ICM::parameterize() (row `icm`: cones, cut, optimum, layout); CGAL's
// methods then run on a CGAL::Seam_mesh cut along ICM's seams (the same cut), and a closed
// genus-0 mesh also gets `icm_free_boundary_opened`, the free-boundary parameterizer on the
// mesh opened at its first vertex.
//
// Every run of every method happens in a forked child process on its own copy of the mesh:
// a method that hangs is killed at the time limit and shown as `timeout`, a method that
// crashes is shown as `crashed (signal N)`, and the child's peak resident memory is the
// method's (plus the process image inherited at fork, which holds the input mesh).
// See doc/benchmarks.md.

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/subdivision_method_3.h>

#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <nlohmann/json.hpp>

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;
// Keys stay in the order they are set, as the JSON lines always listed them.
using Json = nlohmann::ordered_json;

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = boost::graph_traits<Mesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;
using edge_descriptor = boost::graph_traits<Mesh>::edge_descriptor;
using UV_map = Mesh::Property_map<vertex_descriptor, Point_2>;

// A mesh that is not a disk, cut along seams without copying it. Its UVs live in a halfedge
// map of the underlying mesh: one UV per corner (the seam mesh reads a seam-mesh vertex's UV
// at its halfedge), which is also the layout ICM::parameterize() writes.
using Seam_edge_map = Mesh::Property_map<edge_descriptor, bool>;
using Seam_vertex_map = Mesh::Property_map<vertex_descriptor, bool>;
using Seam_mesh = CGAL::Seam_mesh<Mesh, Seam_edge_map, Seam_vertex_map>;
using seam_halfedge_descriptor = boost::graph_traits<Seam_mesh>::halfedge_descriptor;
using Corner_UV_map = Mesh::Property_map<halfedge_descriptor, Point_2>;

const double NaN = std::numeric_limits<double>::quiet_NaN();

// ------------------------------------------------------------------------------------------
// The method registry. A method takes a fresh mesh, its longest border halfedge and an empty
// UV map; it returns the error code, the wall time of the parameterize() call and, for ICM,
// the solver's report.
// ------------------------------------------------------------------------------------------

struct Run_result
{
  SMP::Error_code code = SMP::OK;
  double seconds = NaN;                 // wall time of the parameterize() call only
  std::string message;                  // extra failure reason (ICM's report)
  std::optional<int> newton_iterations; // ICM only
  std::string metric;                   // ICM only: the metric of the result (after a fallback)
  std::string fallback_reason;          // ICM only: why the requested metric was not used
  // ICM only: the report's times and, for an energy other than the entropy, its optimizer's
  // steps and values (energy_iterations, initial_energy, final_energy).
  std::vector<std::pair<std::string, double>> report_numbers;
};

struct Method
{
  std::string name;
  std::function<Run_result(Mesh&, halfedge_descriptor, UV_map)> run;
};

// Times CGAL's free function parameterize(); `p` is passed on by value, as CGAL does.
template <class TriangleMesh, class Parameterizer, class UVMap>
Run_result timed_parameterize(TriangleMesh& mesh, const Parameterizer& p,
                              typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd, UVMap uvmap)
{
  Run_result r;
  const auto t0 = std::chrono::steady_clock::now();
  r.code = SMP::parameterize(mesh, p, bhd, uvmap);
  const auto t1 = std::chrono::steady_clock::now();
  r.seconds = std::chrono::duration<double>(t1 - t0).count();
  return r;
}

// A CGAL parameterizer, default constructed.
template <class Parameterizer>
Method cgal_method(std::string name)
{
  return {std::move(name), [](Mesh& mesh, halfedge_descriptor bhd, UV_map uvmap) {
            return timed_parameterize(mesh, Parameterizer(), bhd, uvmap);
          }};
}

// An ICM parameterizer: its report() is shared between copies, so it can be read from the
// local object after CGAL's parameterize() has worked on a copy.
template <class Parameterizer>
Method icm_method(std::string name)
{
  return {std::move(name), [](Mesh& mesh, halfedge_descriptor bhd, UV_map uvmap) {
            Parameterizer p;
            Run_result r = timed_parameterize(mesh, p, bhd, uvmap);
            const ICM::Parameterization_report& report = p.report();
            r.newton_iterations = report.newton_iterations;
            r.message = report.message;
            r.metric = report.metric;
            r.fallback_reason = report.fallback_reason;
            r.report_numbers = {
              {"seconds_index", report.seconds_index},     {"seconds_metric", report.seconds_metric},
              {"seconds_optimum", report.seconds_optimum}, {"seconds_layout", report.seconds_layout},
              {"seconds_total", report.seconds_total},     {"border_crossings", report.overlapping_border_edges}};
            if(Parameterizer::optimizes_energy)
              r.report_numbers.insert(r.report_numbers.end(), {{"energy_iterations", report.energy_iterations},
                                                               {"initial_energy", report.initial_energy},
                                                               {"final_energy", report.final_energy}});
            if(report.border_condition == ICM::Circle_domain().name())
              r.report_numbers.insert(r.report_numbers.end(), {{"border_iterations", report.border_iterations},
                                                               {"circle_deviation", report.circle_deviation}});
            return r;
          }};
}

// ICM's free-boundary parameterizer minimising `Energy` instead of the curvature entropy.
template <class Energy>
Method icm_energy_method(std::string name)
{
  return icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh, CGAL::Default, CGAL::Default, Energy>>(
    std::move(name));
}

// Add a method here with one line; its name is what --methods selects.
std::vector<Method> make_registry()
{
  return {
    icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh>>("icm_free_boundary"),
    icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh, ICM::Vertex_scaling_metric>>("icm_vertex_scaling"),
    icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh, ICM::Inversive_distance_metric>>(
      "icm_inversive_distance"),
    icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh, ICM::Circle_packing_metric>>("icm_circle_packing"),
    // The other energies, minimised over the free-boundary maps from the entropy optimum
    // (icm_free_boundary), default metric.
    icm_energy_method<ICM::U_square>("icm_u_square"),
    icm_energy_method<ICM::Area_distortion>("icm_area"),
    icm_energy_method<ICM::Angle_distortion>("icm_angle"),
    icm_energy_method<ICM::Log_area_distortion>("icm_log_area"),
    // A genus-0 mesh with several border loops onto nested circles, without a cut.
    icm_method<ICM::Inverse_curvature_map_parameterizer_3<Mesh, CGAL::Default, CGAL::Default, CGAL::Default,
                                                          ICM::Circle_domain>>("icm_circle_domain"),
    cgal_method<SMP::LSCM_parameterizer_3<Mesh>>("lscm"),
    cgal_method<SMP::ARAP_parameterizer_3<Mesh>>("arap"),
    cgal_method<SMP::Discrete_conformal_map_parameterizer_3<Mesh>>("dcm"),
    cgal_method<SMP::Discrete_authalic_parameterizer_3<Mesh>>("dac"),
    cgal_method<SMP::Mean_value_coordinates_parameterizer_3<Mesh>>("mvc"),
  };
}

// CGAL's methods on a seam mesh (a surface that is not a disk, cut along ICM's seams); the
// names are those of the registry's CGAL rows.
struct Seam_method
{
  std::string name;
  std::function<Run_result(Seam_mesh&, seam_halfedge_descriptor, Corner_UV_map)> run;
};

template <class Parameterizer>
Seam_method seam_cgal_method(std::string name)
{
  return {std::move(name), [](Seam_mesh& mesh, seam_halfedge_descriptor bhd, Corner_UV_map uvmap) {
            return timed_parameterize(mesh, Parameterizer(), bhd, uvmap);
          }};
}

std::vector<Seam_method> make_seam_registry()
{
  return {
    seam_cgal_method<SMP::LSCM_parameterizer_3<Seam_mesh>>("lscm"),
    seam_cgal_method<SMP::ARAP_parameterizer_3<Seam_mesh>>("arap"),
    seam_cgal_method<SMP::Discrete_conformal_map_parameterizer_3<Seam_mesh>>("dcm"),
    seam_cgal_method<SMP::Discrete_authalic_parameterizer_3<Seam_mesh>>("dac"),
    seam_cgal_method<SMP::Mean_value_coordinates_parameterizer_3<Seam_mesh>>("mvc"),
  };
}

// Rows of a surface that is not a disk, besides the seam-mesh CGAL methods:
//   icm                       ICM::parameterize(), the whole pipeline (cones, cut, optimum, layout)
//   icm_u_square, icm_area,   the same with that energy minimised over the entropy's cones and
//   icm_angle, icm_log_area   border (ICM::parameterize<..., Energy>); on a disk these names
//                             are the parameterizer's free-boundary rows instead
//   icm_keep_overlaps         the same with remove_overlaps = false: the raw cut (shown, and
//                             given to CGAL's methods, when overlap removal made pieces)
//   icm_free_boundary_opened  icm_free_boundary on the closed mesh opened at its first vertex
//   icm_circle_domain         a genus-0 mesh with several loops onto nested circles, no cut
//   icm_cones_4, _8, _16, _32 the whole pipeline with exactly that many cones: the area
//                             distortion against the cone count (asked for by --methods)
//   icm_u_square_cones_4, ... the same with the u-square energy choosing the cones' angles
const std::vector<std::string> surface_methods = {"icm",
                                                  "icm_keep_overlaps",
                                                  "icm_free_boundary_opened",
                                                  "icm_circle_domain",
                                                  "icm_cones_4",
                                                  "icm_cones_8",
                                                  "icm_cones_16",
                                                  "icm_cones_32",
                                                  "icm_u_square_cones_4",
                                                  "icm_u_square_cones_8",
                                                  "icm_u_square_cones_16",
                                                  "icm_u_square_cones_32"};

const std::string u_square_cones_prefix = "icm_u_square_cones_";

// The cone count of an icm_cones_N or icm_u_square_cones_N row, or -1 for another name.
int exact_cone_count(const std::string& name)
{
  for(const std::string& prefix : {std::string("icm_cones_"), u_square_cones_prefix})
    if(name.rfind(prefix, 0) == 0)
      return std::stoi(name.substr(prefix.size()));
  return -1;
}

// The methods drawn by --svg-panels, in this order.
const std::vector<std::string> panel_methods = {"icm_free_boundary", "lscm", "arap"};

// ------------------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------------------

struct Options
{
  bool json = false;
  bool quiet = false;
  int runs = 0; // 0: automatic (3 if one run takes < 2 s, else 1)
  double time_limit = 600.0;
  int subdivide = 0;
  bool open = false;
  std::vector<std::string> methods; // empty: all
  std::string svg_panels;
  std::string json_file; // --json-file: the JSON lines also go to this file
  std::vector<std::string> meshes;
};

const char* usage_text = "usage: compare [--json] [--runs N] [--time-limit SECONDS] [--methods a,b,c]\n"
                         "               [--subdivide K] [--open] [--svg-panels FILE] [--json-file FILE]\n"
                         "               [--quiet] MESH...\n"
                         "\n"
                         "Runs each parameterization method on each mesh (OFF/OBJ/PLY) and prints the paper's\n"
                         "Table I plus time, memory and flips as Markdown (or JSON lines). A disk gets every\n"
                         "method of the registry: ICM's free boundary in each metric (icm_free_boundary,\n"
                         "icm_vertex_scaling, icm_inversive_distance, icm_circle_packing), ICM's other energies\n"
                         "(icm_u_square, icm_area, icm_angle, icm_log_area) and CGAL's lscm, arap, dcm, dac, mvc.\n"
                         "A mesh that is not a disk gets ICM::parameterize() (row icm) and CGAL's methods on a\n"
                         "seam mesh cut along ICM's seams; a closed genus-0 mesh also icm_free_boundary_opened.\n"
                         "\n"
                         "  --json             one JSON object per (mesh, method) on stdout instead of Markdown\n"
                         "  --runs N           timed runs per method, median reported (default: 3 if one run\n"
                         "                     takes < 2 s, else 1)\n"
                         "  --time-limit S     per-run limit in seconds; slower runs are killed and shown as\n"
                         "                     'timeout' (default 600)\n"
                         "  --methods a,b      run only these methods (default: all); besides the registry's:\n"
                         "                     icm, icm_keep_overlaps, icm_free_boundary_opened, icm_cones_4,\n"
                         "                     icm_cones_8, icm_cones_16, icm_cones_32 (exactly that many\n"
                         "                     cones) and icm_u_square_cones_4, ..._32 (the same, the\n"
                         "                     angles by u-square); on a surface\n"
                         "                     that is not a disk, icm_u_square, icm_area, icm_angle and\n"
                         "                     icm_log_area run ICM::parameterize with that energy\n"
                         "  --subdivide K      apply K steps of Loop subdivision to each mesh first\n"
                         "  --open             open each closed mesh by removing the faces around its first\n"
                         "                     vertex: a nearly closed disk, like a scan with one small hole\n"
                         "  --json-file FILE   also write the JSON lines to FILE (with the Markdown on stdout)\n"
                         "  --svg-panels FILE  write the UV layouts of icm_free_boundary, lscm and arap for the\n"
                         "                     first mesh side by side to FILE (faces coloured by log area ratio)\n"
                         "  --quiet            no progress lines on stderr\n";

std::vector<std::string> split_commas(const std::string& s)
{
  std::vector<std::string> out;
  std::string cur;
  for(char c : s)
  {
    if(c == ',')
    {
      if(!cur.empty())
        out.push_back(cur);
      cur.clear();
    }
    else if(c != ' ')
    {
      cur += c;
    }
  }
  if(!cur.empty())
    out.push_back(cur);
  return out;
}

[[noreturn]] void usage_error(const std::string& what)
{
  std::cerr << "compare: " << what << "\n\n" << usage_text;
  std::exit(2);
}

bool parse_int(const std::string& s, int& v)
{
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(s.c_str(), &end, 10);
  if(s.empty() || *end != '\0' || errno != 0 || x < std::numeric_limits<int>::min() ||
     x > std::numeric_limits<int>::max())
    return false;
  v = static_cast<int>(x);
  return true;
}

bool parse_double(const std::string& s, double& v)
{
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0' && errno == 0 && std::isfinite(v);
}

Options parse_options(int argc, char** argv, const std::vector<Method>& registry)
{
  Options o;
  auto value = [&](int& i, const std::string& opt) -> std::string {
    if(i + 1 >= argc)
      usage_error("option " + opt + " needs a value");
    return argv[++i];
  };
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "-h" || a == "--help")
    {
      std::cout << usage_text;
      std::exit(0);
    }
    else if(a == "--json")
    {
      o.json = true;
    }
    else if(a == "--quiet" || a == "-q")
    {
      o.quiet = true;
    }
    else if(a == "--runs")
    {
      if(!parse_int(value(i, a), o.runs) || o.runs < 1)
        usage_error("--runs needs a positive integer");
    }
    else if(a == "--time-limit")
    {
      if(!parse_double(value(i, a), o.time_limit) || o.time_limit <= 0)
        usage_error("--time-limit needs a positive number of seconds");
    }
    else if(a == "--subdivide")
    {
      if(!parse_int(value(i, a), o.subdivide) || o.subdivide < 0 || o.subdivide > 8)
        usage_error("--subdivide needs an integer in [0, 8]");
    }
    else if(a == "--open")
    {
      o.open = true;
    }
    else if(a == "--methods")
    {
      o.methods = split_commas(value(i, a));
      if(o.methods.empty())
        usage_error("--methods needs at least one name");
    }
    else if(a == "--svg-panels")
    {
      o.svg_panels = value(i, a);
    }
    else if(a == "--json-file")
    {
      o.json_file = value(i, a);
    }
    else if(a.size() > 1 && a[0] == '-' && a != "-")
    {
      usage_error("unknown option " + a);
    }
    else
    {
      o.meshes.push_back(a);
    }
  }
  for(const std::string& m : o.methods)
  {
    const bool known = std::any_of(registry.begin(), registry.end(), [&](const Method& r) { return r.name == m; }) ||
                       std::find(surface_methods.begin(), surface_methods.end(), m) != surface_methods.end();
    if(!known)
    {
      std::string valid;
      for(const Method& r : registry)
        valid += (valid.empty() ? "" : ", ") + r.name;
      for(const std::string& name : surface_methods)
        valid += ", " + name;
      std::cerr << "compare: unknown method '" << m << "'; valid methods: " << valid << "\n";
      std::exit(2);
    }
  }
  if(o.meshes.empty())
    usage_error("no mesh given");
  return o;
}

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------

struct Measures
{
  double faces = NaN, flipped = NaN, degenerate = NaN;
  double conformality = NaN, angle_distortion = NaN, l2_shear = NaN, l2_stretch = NaN, log_area_distortion = NaN,
         log_area_weighted = NaN, qc_mean = NaN, qc_max = NaN, area_ratio_min = NaN, area_ratio_max = NaN;
};

Measures to_measures(const ICM::Distortion_measures& d)
{
  Measures m;
  m.faces = static_cast<double>(d.faces);
  m.flipped = static_cast<double>(d.flipped_faces);
  m.degenerate = static_cast<double>(d.degenerate_uv_faces);
  m.conformality = d.conformality;
  m.angle_distortion = d.angle_distortion;
  m.l2_shear = d.l2_shear;
  m.l2_stretch = d.l2_stretch;
  m.log_area_distortion = d.log_area_distortion;
  m.log_area_weighted = d.log_area_distortion_area_weighted;
  m.qc_mean = d.qc_mean;
  m.qc_max = d.qc_max;
  m.area_ratio_min = d.area_ratio_min;
  m.area_ratio_max = d.area_ratio_max;
  return m;
}

// One (mesh, method) row of the table.
struct Row
{
  std::string mesh;
  std::size_t vertices = 0, faces = 0;
  std::string method;
  std::string status;
  double seconds = NaN;
  double peak_rss_mb = NaN;
  bool has_measures = false;
  Measures m;
  std::optional<int> newton_iterations;
  std::string metric;
  // Surfaces that are not disks only (empty for a disk, whose output is unchanged):
  std::string topology; // "genus G, B loops", shown in the Markdown model label
  std::string detail;   // shown in parentheses after the method in Markdown (e.g. the cut)
  std::string note;     // appended to the Markdown status (e.g. ICM's stage times)
  std::vector<std::pair<std::string, Json>> json_extra; // key, value
};

// What one child process sends back through its pipe: "key value" lines.
struct Child_result
{
  bool complete = false;
  int code = 0;
  double seconds = NaN;
  double peak_rss_mb = NaN;
  bool has_measures = false;
  Measures m;
  std::optional<int> newton_iterations;
  std::string metric;
  std::string message;
  std::string exception;
  std::vector<std::pair<std::string, double>> extra; // named numbers (ICM's report), in order
  std::string fallback_reason;                       // ICM's, when it fell back
  std::vector<std::size_t> seams;                    // ICM's seam edges (edge indices)
};

double extra_value(const Child_result& r, const std::string& key)
{
  for(const auto& [k, v] : r.extra)
    if(k == key)
      return v;
  return NaN;
}

std::string fmt_g(double x)
{
  if(std::isnan(x))
    return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string one_line(std::string s)
{
  for(char& c : s)
    if(c == '\n' || c == '\r')
      c = ' ';
  return s;
}

std::string serialize(const Child_result& r)
{
  std::ostringstream out;
  out << "code " << r.code << "\n";
  out << "seconds " << fmt_g(r.seconds) << "\n";
  out << "rss " << fmt_g(r.peak_rss_mb) << "\n";
  if(r.newton_iterations)
    out << "newton " << *r.newton_iterations << "\n";
  if(!r.metric.empty())
    out << "metric " << one_line(r.metric) << "\n";
  if(r.has_measures)
  {
    const Measures& m = r.m;
    const std::pair<const char*, double> fields[] = {{"faces", m.faces},
                                                     {"flipped", m.flipped},
                                                     {"degenerate", m.degenerate},
                                                     {"conformality", m.conformality},
                                                     {"angle_distortion", m.angle_distortion},
                                                     {"l2_shear", m.l2_shear},
                                                     {"l2_stretch", m.l2_stretch},
                                                     {"log_area_distortion", m.log_area_distortion},
                                                     {"log_area_weighted", m.log_area_weighted},
                                                     {"qc_mean", m.qc_mean},
                                                     {"qc_max", m.qc_max},
                                                     {"area_ratio_min", m.area_ratio_min},
                                                     {"area_ratio_max", m.area_ratio_max}};
    out << "measured 1\n";
    for(const auto& f : fields)
      out << "m." << f.first << " " << fmt_g(f.second) << "\n";
  }
  if(!r.message.empty())
    out << "message " << one_line(r.message) << "\n";
  if(!r.exception.empty())
    out << "exception " << one_line(r.exception) << "\n";
  for(const auto& [key, value] : r.extra)
    out << "x." << key << " " << fmt_g(value) << "\n";
  if(!r.fallback_reason.empty())
    out << "fallback " << one_line(r.fallback_reason) << "\n";
  if(!r.seams.empty())
  {
    out << "seams";
    for(std::size_t e : r.seams)
      out << " " << e;
    out << "\n";
  }
  out << "end 1\n";
  return out.str();
}

Child_result deserialize(const std::string& text)
{
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  std::string line;
  Child_result r;
  while(std::getline(in, line))
  {
    const auto sp = line.find(' ');
    if(sp == std::string::npos)
      continue;
    const std::string key = line.substr(0, sp), value = line.substr(sp + 1);
    kv[key] = value;
    if(key.rfind("x.", 0) == 0)
      r.extra.emplace_back(key.substr(2), std::strtod(value.c_str(), nullptr));
  }
  if(kv.count("fallback"))
    r.fallback_reason = kv["fallback"];
  if(kv.count("seams"))
  {
    std::istringstream seams(kv["seams"]);
    std::size_t e;
    while(seams >> e)
      r.seams.push_back(e);
  }
  r.complete = kv.count("end") > 0;
  auto num = [&](const char* key) {
    auto it = kv.find(key);
    return it == kv.end() ? NaN : std::strtod(it->second.c_str(), nullptr);
  };
  r.code = kv.count("code") ? std::atoi(kv["code"].c_str()) : 0;
  r.seconds = num("seconds");
  r.peak_rss_mb = num("rss");
  if(kv.count("newton"))
    r.newton_iterations = std::atoi(kv["newton"].c_str());
  if(kv.count("metric"))
    r.metric = kv["metric"];
  r.has_measures = kv.count("measured") > 0;
  Measures& m = r.m;
  m.faces = num("m.faces");
  m.flipped = num("m.flipped");
  m.degenerate = num("m.degenerate");
  m.conformality = num("m.conformality");
  m.angle_distortion = num("m.angle_distortion");
  m.l2_shear = num("m.l2_shear");
  m.l2_stretch = num("m.l2_stretch");
  m.log_area_distortion = num("m.log_area_distortion");
  m.log_area_weighted = num("m.log_area_weighted");
  m.qc_mean = num("m.qc_mean");
  m.qc_max = num("m.qc_max");
  m.area_ratio_min = num("m.area_ratio_min");
  m.area_ratio_max = num("m.area_ratio_max");
  if(kv.count("message"))
    r.message = kv["message"];
  if(kv.count("exception"))
    r.exception = kv["exception"];
  return r;
}

// VmHWM (peak resident set size) of a process in MB, NaN when unknown.
double vm_hwm_mb(const std::string& status_path)
{
  std::ifstream status(status_path);
  std::string line;
  while(std::getline(status, line))
  {
    if(line.rfind("VmHWM:", 0) == 0)
    {
      const double kb = std::strtod(line.c_str() + 6, nullptr);
      if(kb > 0)
        return kb / 1024.0;
    }
  }
  return NaN;
}

// Peak resident set size of this process in MB: VmHWM, else getrusage's ru_maxrss.
double peak_rss_mb()
{
  const double hwm = vm_hwm_mb("/proc/self/status");
  if(std::isfinite(hwm))
    return hwm;
  rusage ru{};
  if(getrusage(RUSAGE_SELF, &ru) == 0)
    return static_cast<double>(ru.ru_maxrss) / 1024.0;
  return NaN;
}

// UVs are worth measuring when the method produced a complete map (possibly with flips).
bool has_usable_uvs(SMP::Error_code code)
{
  return code == SMP::OK || code == SMP::ERROR_NO_1_TO_1_MAPPING;
}

// ------------------------------------------------------------------------------------------
// Running one method in a child process
// ------------------------------------------------------------------------------------------

void write_all(int fd, const std::string& s)
{
  const char* p = s.data();
  std::size_t left = s.size();
  while(left > 0)
  {
    const ssize_t n = ::write(fd, p, left);
    if(n < 0)
    {
      if(errno == EINTR)
        continue;
      return;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

// What a child does: fill `r` (copy the mesh, run, measure). `measure` is false for the
// extra timing runs.
using Job = std::function<void(Child_result& r, bool measure)>;

// A registry method on a disk: its own copy of the mesh, the longest border, a vertex UV map.
Job method_job(const Mesh& input, const Method& method)
{
  return [&input, &method](Child_result& r, bool measure) {
    Mesh mesh = input; // the method's own copy
    UV_map uvmap = mesh.add_property_map<vertex_descriptor, Point_2>("v:compare_uv", Point_2(0, 0)).first;
    const halfedge_descriptor bhd = PMP::longest_border(mesh).first;
    const Run_result run = method.run(mesh, bhd, uvmap);
    r.peak_rss_mb = peak_rss_mb(); // right after the run, before measuring
    r.code = static_cast<int>(run.code);
    r.seconds = run.seconds;
    r.newton_iterations = run.newton_iterations;
    r.metric = run.metric;
    r.message = run.message;
    r.extra = run.report_numbers;
    r.fallback_reason = run.fallback_reason;
    if(measure && has_usable_uvs(run.code))
    {
      r.m = to_measures(ICM::measure_distortion(mesh, uvmap));
      r.has_measures = true;
    }
  };
}

// The child's work: run the job, report. Never returns.
[[noreturn]] void child_main(int fd, const Job& job, bool measure)
{
  Child_result r;
  try
  {
    job(r, measure);
  }
  catch(const std::exception& e)
  {
    r.exception = e.what();
    if(r.exception.empty())
      r.exception = "std::exception";
  }
  catch(...)
  {
    r.exception = "unknown exception";
  }
  write_all(fd, serialize(r));
  ::close(fd);
  std::_Exit(0);
}

struct Child_outcome
{
  enum Kind
  {
    finished,
    timeout,
    crashed,
    lost
  } kind = lost;
  int signal = 0;
  int exit_code = 0;
  double peak_rss_mb = NaN; // timeout only: the child's peak memory when it was killed
  Child_result result;
};

Child_outcome run_in_child(const Job& job, bool measure, double time_limit)
{
  Child_outcome out;
  int fds[2];
  if(::pipe(fds) != 0)
  {
    std::perror("compare: pipe");
    return out;
  }
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if(pid < 0)
  {
    std::perror("compare: fork");
    ::close(fds[0]);
    ::close(fds[1]);
    return out;
  }
  if(pid == 0)
  {
    ::close(fds[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL); // never outlive the runner
    if(::getppid() != parent)
      std::_Exit(3);
    // The results go through the pipe; keep whatever a method prints off our stdout.
    const int devnull = ::open("/dev/null", O_WRONLY);
    if(devnull >= 0)
    {
      ::dup2(devnull, STDOUT_FILENO);
      ::close(devnull);
    }
    child_main(fds[1], job, measure);
  }
  ::close(fds[1]);

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(time_limit);
  std::string data;
  bool eof = false, timed_out = false;
  char buf[4096];
  while(!eof)
  {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if(left <= 0)
    {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int wait_ms = static_cast<int>(std::min(left * 1000.0 + 1.0, 60000.0));
    const int rc = ::poll(&p, 1, wait_ms);
    if(rc < 0)
    {
      if(errno == EINTR)
        continue;
      break;
    }
    if(rc == 0)
      continue;
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if(n < 0)
    {
      if(errno == EINTR)
        continue;
      break;
    }
    if(n == 0)
      eof = true;
    else
      data.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);

  int status = 0;
  if(timed_out)
  {
    // The peak memory so far, read before the kill: a lower bound of what the run needs.
    out.peak_rss_mb = vm_hwm_mb("/proc/" + std::to_string(pid) + "/status");
    ::kill(pid, SIGKILL);
    while(::waitpid(pid, &status, 0) < 0 && errno == EINTR)
    {}
    out.kind = Child_outcome::timeout;
    return out;
  }
  // The pipe is closed: the child has written its result or died. Give it a moment to exit.
  pid_t w = 0;
  for(int i = 0; i < 1000; ++i)
  {
    w = ::waitpid(pid, &status, WNOHANG);
    if(w != 0 && !(w < 0 && errno == EINTR))
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if(w == 0)
  { // closed its pipe but still running: treat as hung
    ::kill(pid, SIGKILL);
    while(::waitpid(pid, &status, 0) < 0 && errno == EINTR)
    {}
    out.kind = Child_outcome::timeout;
    return out;
  }
  out.result = deserialize(data);
  if(w > 0 && WIFSIGNALED(status))
  {
    out.kind = Child_outcome::crashed;
    out.signal = WTERMSIG(status);
  }
  else if(w > 0 && WIFEXITED(status) && WEXITSTATUS(status) != 0)
  {
    out.kind = Child_outcome::crashed;
    out.exit_code = WEXITSTATUS(status);
  }
  else if(out.result.complete)
  {
    out.kind = Child_outcome::finished;
  }
  else
  {
    out.kind = Child_outcome::lost;
  }
  return out;
}

std::string status_of(const Child_outcome& o)
{
  switch(o.kind)
  {
  case Child_outcome::timeout:
    return "timeout";
  case Child_outcome::crashed:
    if(o.signal != 0)
      return "crashed (signal " + std::to_string(o.signal) + ")";
    return "crashed (exit code " + std::to_string(o.exit_code) + ")";
  case Child_outcome::lost:
    return "crashed (no result)";
  case Child_outcome::finished:
    break;
  }
  const Child_result& r = o.result;
  if(!r.exception.empty())
    return "failed: exception: " + r.exception;
  if(r.code != SMP::OK)
  {
    std::string s = std::string("failed: ") + ICM::error_message(static_cast<SMP::Error_code>(r.code));
    if(!r.message.empty())
      s += "; " + r.message;
    return s;
  }
  return "ok";
}

double median(std::vector<double> v)
{
  if(v.empty())
    return NaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// All runs of one job on one mesh: the first run measures; more runs only time. The first
// run's result goes to `first_result` when given (ICM's seams and report).
Row run_job(const Job& job, const std::string& name, const Options& opt, Row row, Child_result* first_result = nullptr)
{
  row.method = name;
  const Child_outcome first = run_in_child(job, /*measure=*/true, opt.time_limit);
  row.status = status_of(first);
  if(first_result)
    *first_result = first.result;
  if(first.kind == Child_outcome::timeout)
    row.peak_rss_mb = first.peak_rss_mb;
  if(first.kind != Child_outcome::finished)
    return row;
  const Child_result& r = first.result;
  row.has_measures = r.has_measures;
  row.m = r.m;
  row.newton_iterations = r.newton_iterations;
  row.metric = r.metric;
  row.peak_rss_mb = r.peak_rss_mb;
  std::vector<double> times{r.seconds};
  // Named times of the report (ICM's stages): the median over the runs, like the time.
  std::map<std::string, std::vector<double>> stage_times;
  for(const auto& [key, value] : r.extra)
    if(key.rfind("seconds", 0) == 0)
      stage_times[key].push_back(value);
  if(row.status == "ok")
  {
    const int runs = opt.runs > 0 ? opt.runs : (r.seconds < 2.0 ? 3 : 1);
    for(int k = 1; k < runs; ++k)
    {
      const Child_outcome more = run_in_child(job, /*measure=*/false, opt.time_limit);
      const std::string st = status_of(more);
      if(st != "ok")
      { // a method that is not deterministic in its outcome: show it
        row.status = st + " (run " + std::to_string(k + 1) + ")";
        break;
      }
      times.push_back(more.result.seconds);
      for(const auto& [key, value] : more.result.extra)
        if(stage_times.count(key))
          stage_times[key].push_back(value);
      row.peak_rss_mb = std::max(row.peak_rss_mb, more.result.peak_rss_mb);
    }
  }
  row.seconds = median(times);
  if(first_result)
    for(auto& [key, value] : first_result->extra)
      if(stage_times.count(key))
        value = median(stage_times[key]);
  return row;
}

// ------------------------------------------------------------------------------------------
// Meshes
// ------------------------------------------------------------------------------------------

std::string mesh_name(const std::string& path)
{
  std::string name = path;
  const auto slash = name.find_last_of('/');
  if(slash != std::string::npos)
    name = name.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  if(dot != std::string::npos && dot > 0)
    name = name.substr(0, dot);
  return name;
}

// Opens a closed mesh by removing the faces around its first vertex (--open, and the mesh of
// icm_free_boundary_opened): a nearly closed disk, like a scan with one small hole.
void open_at_first_vertex(Mesh& mesh)
{
  std::vector<face_descriptor> around;
  for(face_descriptor f : CGAL::faces_around_target(halfedge(*vertices(mesh).begin(), mesh), mesh))
    around.push_back(f);
  for(face_descriptor f : around)
    CGAL::Euler::remove_face(halfedge(f, mesh), mesh);
}

// Reads and prepares a mesh; on failure returns false with a reason.
bool load_mesh(const std::string& path, const Options& opt, Mesh& mesh, std::string& error)
{
  mesh.clear();
  bool ok = false;
  try
  {
    ok = CGAL::IO::read_polygon_mesh(path, mesh);
  }
  catch(const std::exception& e)
  {
    error = e.what();
    return false;
  }
  if(!ok)
  {
    error = "cannot read a polygon mesh from this file";
    return false;
  }
  if(num_faces(mesh) == 0)
  {
    error = "the mesh has no faces";
    return false;
  }
  if(!CGAL::is_triangle_mesh(mesh))
    PMP::triangulate_faces(mesh);
  if(opt.subdivide > 0)
    CGAL::Subdivision_method_3::Loop_subdivision(
      mesh, CGAL::parameters::number_of_iterations(static_cast<unsigned int>(opt.subdivide)));
  if(opt.open && CGAL::is_closed(mesh))
    open_at_first_vertex(mesh);
  if(mesh.has_garbage())
    mesh.collect_garbage();
  return true;
}

// Components, boundary loops and Euler characteristic chi = V - E + F = 2C - 2G - B.
struct Topology
{
  std::size_t components = 0;
  long loops = 0;
  long chi = 0;
  long two_g() const { return 2 * static_cast<long>(components) - loops - chi; }
  bool closed() const { return loops == 0; }
  bool disk() const { return components == 1 && loops == 1 && two_g() == 0; }
  // The genus when the mesh is connected, else "?".
  std::string genus() const { return components == 1 && two_g() % 2 == 0 ? std::to_string(two_g() / 2) : "?"; }
  std::string description() const
  {
    std::string s = components == 1 ? std::string() : std::to_string(components) + " components, ";
    return s + "genus " + genus() + ", " + std::to_string(loops) + " loops";
  }
};

Topology topology_of(Mesh& mesh)
{
  Topology t;
  auto fccmap = mesh.add_property_map<face_descriptor, std::size_t>("f:compare_cc").first;
  t.components = PMP::connected_components(mesh, fccmap);
  mesh.remove_property_map(fccmap);
  std::vector<halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  t.loops = static_cast<long>(cycles.size());
  t.chi =
    static_cast<long>(num_vertices(mesh)) - static_cast<long>(num_edges(mesh)) + static_cast<long>(num_faces(mesh));
  return t;
}

// "" when the mesh is a topological disk (one component, one boundary loop, genus 0),
// else the reason for skipping it.
std::string disk_check(Mesh& mesh)
{
  const Topology t = topology_of(mesh);
  const long b = t.loops;
  if(t.components != 1)
    return "skipped: not a disk (" + std::to_string(t.components) + " components, " + std::to_string(b) + " loops)";
  const long two_g = 2 - b - t.chi;
  const std::string genus = two_g % 2 == 0 ? std::to_string(two_g / 2) : "?";
  if(b != 1 || two_g != 0)
    return "skipped: not a disk (" + std::to_string(b) + " loops, genus " + genus + ")";
  return "";
}

// ------------------------------------------------------------------------------------------
// Surfaces that are not disks: ICM's one call, and CGAL's methods on ICM's cut
// ------------------------------------------------------------------------------------------

// ICM::parameterize() with `Energy` on its own copy of the mesh, timed as a whole, measured per
// corner. The report's stage times and counts go back as extras, the seam edges as edge
// indices; for an energy other than the entropy also its steps (summed over the components)
// and E at the entropy optimum and at the result (the components' means weighted by faces).
// `exact_cones` >= 0 places exactly that many automatic cones (as `icm_param --cones N`).
template <class Energy = CGAL::Default>
Job icm_job(const Mesh& input, bool remove_overlaps, int exact_cones = -1)
{
  return [&input, remove_overlaps, exact_cones](Child_result& r, bool measure) {
    Mesh mesh = input;
    Corner_UV_map uvmap = mesh.add_property_map<halfedge_descriptor, Point_2>("h:compare_uv", Point_2(0, 0)).first;
    ICM::Surface_parameterization_options options;
    options.remove_overlaps = remove_overlaps;
    if(exact_cones >= 0)
    {
      options.cones.max_cones = exact_cones;
      options.cones.max_log_scale = 0;
      options.border_max_log_scale = 0;
    }
    std::vector<edge_descriptor> seams;
    const auto t0 = std::chrono::steady_clock::now();
    const ICM::Surface_parameterization_report report =
      ICM::parameterize<CGAL::Default, CGAL::Default, Energy>(mesh, uvmap, options, {}, &seams);
    const auto t1 = std::chrono::steady_clock::now();
    r.peak_rss_mb = peak_rss_mb();
    r.code = static_cast<int>(report.status);
    r.seconds = std::chrono::duration<double>(t1 - t0).count();
    r.message = report.message;
    int newton = 0, cones = 0, given_up = 0, pieces = 0, raw_crossings = 0, crossings = 0, overlap_cuts = 0;
    std::string metric, fallback;
    for(const ICM::Chart_report& c : report.charts)
    {
      newton += c.newton_iterations;
      cones += static_cast<int>(c.cones.size());
      given_up += c.cones_given_up;
      pieces += c.pieces;
      raw_crossings += c.raw_overlapping_border_edges;
      crossings += c.overlapping_border_edges;
      overlap_cuts += c.overlap_cut_edges;
      if(metric.find(c.metric) == std::string::npos)
        metric += (metric.empty() ? "" : "/") + c.metric;
      if(!c.fallback_reason.empty() && fallback.empty())
        fallback = c.fallback_reason;
    }
    r.newton_iterations = newton;
    r.metric = metric + (fallback.empty() ? "" : ", fallback");
    double seam_length = 0; // over the square root of the area; one component's, else summed
    for(const ICM::Chart_report& c : report.charts)
      seam_length += c.seam_length;
    r.extra = {{"cones", cones},
               {"cones_given_up", given_up},
               {"seam_edges", static_cast<double>(seams.size())},
               {"seam_length", seam_length},
               {"charts", pieces},
               {"overlap_cut_edges", overlap_cuts},
               {"raw_border_crossings", raw_crossings},
               {"border_crossings", crossings},
               {"seconds_index", report.seconds_index},
               {"seconds_cones", report.seconds_cones},
               {"seconds_optimum", report.seconds_optimum},
               {"seconds_cut", report.seconds_cut},
               {"seconds_layout", report.seconds_layout},
               {"seconds_total", report.seconds_total}};
    if constexpr(!std::is_same<Energy, CGAL::Default>::value)
    {
      const ICM::Energy_summary energy = ICM::energy_summary(report);
      r.extra.push_back({"energy_iterations", static_cast<double>(energy.iterations)});
      r.extra.push_back({"initial_energy", energy.initial_energy});
      r.extra.push_back({"final_energy", energy.final_energy});
    }
    // Only a successful call writes UVs (a failing component returns before the layout is
    // written), so nothing is measured otherwise.
    if(report.status == SMP::OK)
    {
      for(edge_descriptor e : seams)
        r.seams.push_back(static_cast<std::size_t>(e));
      if(measure)
      {
        r.m = to_measures(ICM::measure_distortion_corner_uv(mesh, uvmap));
        r.has_measures = true;
      }
    }
  };
}

// The job of an icm, icm_keep_overlaps or exact-cone-count row.
Job icm_pipeline_job(const Mesh& mesh, const std::string& name)
{
  if(name.rfind(u_square_cones_prefix, 0) == 0)
    return icm_job<ICM::U_square>(mesh, true, exact_cone_count(name));
  return icm_job(mesh, name != "icm_keep_overlaps", exact_cone_count(name));
}

// A CGAL method on the mesh cut along `seams` (edge indices of the mesh): a CGAL::Seam_mesh,
// its longest border (the cut, plus the holes it joins) as the border halfedge, one UV per
// seam-mesh vertex stored at its halfedge. The cut must make one disk; else the row says so.
Job seam_job(const Mesh& input, const std::vector<std::size_t>& seams, const Seam_method& method)
{
  return [&input, &seams, &method](Child_result& r, bool measure) {
    Mesh mesh = input;
    Seam_edge_map seam_edge = mesh.add_property_map<edge_descriptor, bool>("e:compare_seam", false).first;
    Seam_vertex_map seam_vertex = mesh.add_property_map<vertex_descriptor, bool>("v:compare_seam", false).first;
    Corner_UV_map uvmap = mesh.add_property_map<halfedge_descriptor, Point_2>("h:compare_uv", Point_2(0, 0)).first;
    Seam_mesh seam_mesh(mesh, seam_edge, seam_vertex);
    for(std::size_t i : seams)
    {
      const edge_descriptor e(static_cast<Mesh::size_type>(i));
      seam_mesh.add_seam(source(e, mesh), target(e, mesh));
    }
    std::vector<seam_halfedge_descriptor> cycles;
    PMP::extract_boundary_cycles(seam_mesh, std::back_inserter(cycles));
    const long chi = static_cast<long>(num_vertices(seam_mesh)) - static_cast<long>(num_edges(seam_mesh)) +
                     static_cast<long>(num_faces(seam_mesh));
    if(cycles.size() != 1 || chi != 1)
    {
      r.code = static_cast<int>(SMP::ERROR_NO_TOPOLOGICAL_DISC);
      r.message = "the cut leaves " + std::to_string(cycles.size()) + " border loops, chi " + std::to_string(chi);
      return;
    }
    const seam_halfedge_descriptor bhd = PMP::longest_border(seam_mesh).first;
    const Run_result run = method.run(seam_mesh, bhd, uvmap);
    r.peak_rss_mb = peak_rss_mb();
    r.code = static_cast<int>(run.code);
    r.seconds = run.seconds;
    r.message = run.message;
    if(measure && has_usable_uvs(run.code))
    {
      r.m = to_measures(ICM::measure_distortion(seam_mesh, uvmap));
      r.has_measures = true;
    }
  };
}

// ------------------------------------------------------------------------------------------
// Output
// ------------------------------------------------------------------------------------------

// A measured number in JSON: 10 significant digits (as the Markdown and the previous JSON
// lines gave them), null when not finite.
Json json_num(double x)
{
  if(!std::isfinite(x))
    return nullptr;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return std::strtod(buf, nullptr);
}

// A count in JSON: an integer, null when not finite.
Json json_count(double x)
{
  if(!std::isfinite(x))
    return nullptr;
  return static_cast<long long>(std::llround(x));
}

// A count in the Markdown: digits, empty when not finite.
std::string count_text(double x)
{
  if(!std::isfinite(x))
    return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f", x);
  return buf;
}

void print_json(const Row& r, std::ostream& out = std::cout)
{
  const Measures& m = r.m;
  const bool h = r.has_measures;
  Json o;
  o["mesh"] = r.mesh;
  o["vertices"] = r.vertices;
  o["faces"] = r.faces;
  o["method"] = r.method;
  o["status"] = r.status;
  o["seconds"] = json_num(r.seconds);
  o["peak_rss_mb"] = json_num(r.peak_rss_mb);
  o["flipped"] = h ? json_count(m.flipped) : Json();
  o["degenerate"] = h ? json_count(m.degenerate) : Json();
  o["conformality"] = h ? json_num(m.conformality) : Json();
  o["angle_distortion"] = h ? json_num(m.angle_distortion) : Json();
  o["l2_shear"] = h ? json_num(m.l2_shear) : Json();
  o["l2_stretch"] = h ? json_num(m.l2_stretch) : Json();
  o["log_area_distortion"] = h ? json_num(m.log_area_distortion) : Json();
  o["log_area_distortion_area_weighted"] = h ? json_num(m.log_area_weighted) : Json();
  o["qc_mean"] = h ? json_num(m.qc_mean) : Json();
  o["qc_max"] = h ? json_num(m.qc_max) : Json();
  o["area_ratio_min"] = h ? json_num(m.area_ratio_min) : Json();
  o["area_ratio_max"] = h ? json_num(m.area_ratio_max) : Json();
  o["newton_iterations"] = r.newton_iterations ? Json(*r.newton_iterations) : Json();
  o["metric"] = r.metric.empty() ? Json() : Json(r.metric);
  for(const auto& [key, value] : r.json_extra)
    o[key] = value;
  out << o.dump(-1, ' ', false, Json::error_handler_t::replace) << "\n" << std::flush;
}

// Fixed decimals as in the paper's table, switching to scientific notation when that would
// show fewer than two significant digits (or a huge number).
std::string fmt_fixed(double x, int decimals)
{
  if(std::isnan(x))
    return "nan";
  if(std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  char buf[64];
  const double ax = std::fabs(x);
  if(x != 0 && (ax < 10.0 * std::pow(10.0, -decimals) || ax >= 1e7))
    std::snprintf(buf, sizeof buf, "%.2e", x);
  else
    std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// Seconds with three significant digits below 10 s (0.00291, 0.0412, 1.23), else 0.1 s.
std::string fmt_seconds(double x)
{
  if(!std::isfinite(x))
    return "";
  char buf[64];
  if(x < 10.0)
    std::snprintf(buf, sizeof buf, "%.3g", x);
  else
    std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

std::string md_cell(std::string s)
{
  std::string o;
  for(char c : s)
  {
    if(c == '|')
      o += "\\|";
    else
      o += c;
  }
  return o;
}

std::string model_label(const Row& r)
{
  return r.mesh + " #v: " + std::to_string(r.vertices) + " #f: " + std::to_string(r.faces) +
         (r.topology.empty() ? std::string() : " (" + r.topology + ")");
}

void print_markdown_header()
{
  std::cout << "| Model | Method | conformality | angle distortion | L2 shear | L2 stretch | "
               "log area distortion | time (s) | flipped | QC mean | QC max | peak MB | "
               "Newton its | status |\n"
               "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
}

void print_markdown_row(const Row& r, bool first)
{
  const Measures& m = r.m;
  const bool h = r.has_measures;
  auto cell = [&](double x, int decimals) { return h ? fmt_fixed(x, decimals) : std::string(); };
  std::ostringstream o;
  // An ICM row names the metric of its result: after a fallback it is not the requested one.
  std::string details = r.metric;
  if(!r.detail.empty())
    details += (details.empty() ? "" : ", ") + r.detail;
  const std::string method = details.empty() ? r.method : r.method + " (" + details + ")";
  o << "| " << (first ? md_cell(model_label(r)) : "") << " | " << md_cell(method) << " | " << cell(m.conformality, 5)
    << " | " << cell(m.angle_distortion, 5) << " | " << cell(m.l2_shear, 4) << " | " << cell(m.l2_stretch, 4) << " | "
    << cell(m.log_area_distortion, 5) << " | " << fmt_seconds(r.seconds) << " | " << (h ? count_text(m.flipped) : "")
    << " | " << cell(m.qc_mean, 4) << " | " << cell(m.qc_max, 3) << " | "
    << (std::isfinite(r.peak_rss_mb) ? fmt_fixed(r.peak_rss_mb, 1) : "") << " | "
    << (r.newton_iterations ? std::to_string(*r.newton_iterations) : "") << " | "
    << md_cell(r.note.empty() ? r.status : r.status + "; " + r.note) << " |\n";
  std::cout << o.str() << std::flush;
}

// --json-file's stream, opened in main().
std::ofstream json_file;

// One row on stdout (JSON or Markdown) and, with --json-file, as JSON in that file.
void emit(const Row& row, bool first, const Options& opt)
{
  if(opt.json)
    print_json(row);
  else
    print_markdown_row(row, first);
  if(json_file.is_open())
    print_json(row, json_file);
}

std::string machine_description()
{
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model;
  int processors = 0;
  while(std::getline(cpuinfo, line))
  {
    if(line.rfind("processor", 0) == 0)
      ++processors;
    if(model.empty() && line.rfind("model name", 0) == 0)
    {
      const auto colon = line.find(':');
      if(colon != std::string::npos)
      {
        model = line.substr(colon + 1);
        model.erase(0, model.find_first_not_of(" \t"));
      }
    }
  }
  if(model.empty())
    model = "unknown CPU";
  if(processors == 0)
    processors = static_cast<int>(std::thread::hardware_concurrency());
  return model + ", " + std::to_string(processors) + " logical cores";
}

std::string date_now()
{
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

// ------------------------------------------------------------------------------------------
// --svg-panels: the UV layouts, recomputed in this process (no time limit) for the picture.
// ------------------------------------------------------------------------------------------

bool write_panels(const std::string& mesh_path, const Options& opt, const std::vector<Method>& registry)
{
  Mesh mesh;
  std::string error;
  if(!load_mesh(mesh_path, opt, mesh, error))
  {
    std::cerr << "compare: --svg-panels: " << mesh_path << ": " << error << "\n";
    return false;
  }
  const std::string skip = disk_check(mesh);
  if(!skip.empty())
  {
    std::cerr << "compare: --svg-panels: " << mesh_path << ": " << skip << "\n";
    return false;
  }
  std::vector<std::pair<std::string, ICM::IO::Uv_mesh>> panels;
  for(const std::string& name : panel_methods)
  {
    const auto it = std::find_if(registry.begin(), registry.end(), [&](const Method& m) { return m.name == name; });
    if(it == registry.end())
      continue;
    Mesh copy = mesh;
    UV_map uvmap = copy.add_property_map<vertex_descriptor, Point_2>("v:compare_uv", Point_2(0, 0)).first;
    const halfedge_descriptor bhd = PMP::longest_border(copy).first;
    const Run_result r = it->run(copy, bhd, uvmap);
    if(!has_usable_uvs(r.code))
    {
      std::cerr << "compare: --svg-panels: " << name << " failed (" << ICM::error_message(r.code)
                << (r.message.empty() ? "" : "; " + r.message) << "), panel left out\n";
      continue;
    }
    panels.emplace_back(name, ICM::IO::make_uv_mesh(copy, uvmap));
  }
  if(panels.empty())
  {
    std::cerr << "compare: --svg-panels: no method produced a layout\n";
    return false;
  }
  if(!ICM::IO::write_uv_svg_panels(opt.svg_panels, panels, error))
  {
    std::cerr << "compare: --svg-panels: " << opt.svg_panels << ": " << error << "\n";
    return false;
  }
  if(!opt.quiet)
    std::cerr << "compare: wrote " << opt.svg_panels << "\n";
  return true;
}

// ------------------------------------------------------------------------------------------
// A mesh that is not a disk: the rows in order
// ------------------------------------------------------------------------------------------

// ICM's report in a row: the named numbers as JSON keys, the counts and stage times in the
// Markdown status.
void add_icm_report(Row& row, const Child_result& result)
{
  auto is_measure = [](const std::string& key) {
    return key.rfind("seconds", 0) == 0 || key == "initial_energy" || key == "final_energy" || key == "seam_length";
  };
  for(const auto& [key, value] : result.extra)
    row.json_extra.emplace_back(key, is_measure(key) ? json_num(value) : json_count(value));
  if(result.extra.empty() || row.status.rfind("ok", 0) != 0)
    return;
  auto x = [&](const char* key) { return extra_value(result, key); };
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%.0f cones, %.0f seam edges, %.0f chart%s; cones %s s, optimum %s s, cut %s s, "
                "layout %s s",
                x("cones"), x("seam_edges"), x("charts"), x("charts") == 1 ? "" : "s",
                fmt_seconds(x("seconds_cones")).c_str(), fmt_seconds(x("seconds_optimum")).c_str(),
                fmt_seconds(x("seconds_cut")).c_str(), fmt_seconds(x("seconds_layout")).c_str());
  row.note = buf;
  if(x("border_crossings") > 0)
    row.note += "; " + count_text(x("border_crossings")) + " border crossings";
  if(std::isfinite(x("energy_iterations")))
  {
    std::snprintf(buf, sizeof buf, "; %.0f energy steps, E %.4g -> %.4g", x("energy_iterations"), x("initial_energy"),
                  x("final_energy"));
    row.note += buf;
  }
}

// The job of a surface row with an energy (icm_u_square, ...), or none for another name.
Job icm_energy_job(const Mesh& mesh, const std::string& name)
{
  if(name == "icm_u_square")
    return icm_job<ICM::U_square>(mesh, true);
  if(name == "icm_area")
    return icm_job<ICM::Area_distortion>(mesh, true);
  if(name == "icm_angle")
    return icm_job<ICM::Angle_distortion>(mesh, true);
  if(name == "icm_log_area")
    return icm_job<ICM::Log_area_distortion>(mesh, true);
  return {};
}

// ICM's report on a disk: its numbers as JSON keys; the optimum's time and, for an energy
// other than the entropy, the optimizer's steps and values in the Markdown status.
void add_disk_icm_report(Row& row, const Child_result& result)
{
  auto is_count = [](const std::string& key) {
    return key == "energy_iterations" || key == "border_iterations" || key == "border_crossings";
  };
  for(const auto& [key, value] : result.extra)
    row.json_extra.emplace_back(key, is_count(key) ? json_count(value) : json_num(value));
  if(result.extra.empty() || row.status.rfind("ok", 0) != 0)
    return;
  row.note = "optimum " + fmt_seconds(extra_value(result, "seconds_optimum")) + " s";
  if(extra_value(result, "border_crossings") > 0)
    row.note += "; " + count_text(extra_value(result, "border_crossings")) + " border crossings";
  const double deviation = extra_value(result, "circle_deviation");
  if(std::isfinite(deviation))
  {
    char circles[120];
    std::snprintf(circles, sizeof circles, "; %.0f circle iterations, circle deviation %.2g",
                  extra_value(result, "border_iterations"), deviation);
    row.note += circles;
  }
  const double steps = extra_value(result, "energy_iterations");
  if(!std::isfinite(steps))
    return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "; %.0f energy steps, E %.4g -> %.4g", steps, extra_value(result, "initial_energy"),
                extra_value(result, "final_energy"));
  row.note += buf;
}

Row run_method(const Mesh& mesh, const Method& method, const Options& opt, Row row)
{
  Child_result result;
  row = run_job(method_job(mesh, method), method.name, opt, std::move(row), &result);
  add_disk_icm_report(row, result);
  return row;
}

// Default rows of a mesh that is not a disk: ICM's one call, CGAL's methods on its cut and,
// for a closed genus-0 mesh, the free-boundary parameterizer on the mesh opened at one vertex.
std::vector<std::string> surface_names(const Topology& t)
{
  std::vector<std::string> names = {"icm", "lscm", "arap", "dcm", "dac", "mvc"};
  if(t.components == 1 && t.closed() && t.two_g() == 0)
    names.push_back("icm_free_boundary_opened");
  if(t.components == 1 && t.loops > 1 && t.two_g() == 0)
    names.push_back("icm_circle_domain");
  return names;
}

void run_surface(const Mesh& mesh, const Topology& topology, Row base, const Options& opt,
                 const std::vector<std::string>& asked, const std::vector<Method>& registry,
                 const std::vector<Seam_method>& seam_registry)
{
  std::vector<std::string> names = asked.empty() ? surface_names(topology) : asked;
  base.topology = topology.description();
  const std::string genus = topology.genus(); // "?" when 2g is odd (a non-orientable cut)
  base.json_extra = {{"components", topology.components},
                     {"genus", topology.components != 1 ? Json()
                               : genus == "?"           ? Json(genus)
                                                        : Json(std::stol(genus))},
                     {"loops", topology.loops}};
  const bool connected = topology.components == 1;
  auto seam_method = [&](const std::string& name) -> const Seam_method* {
    for(const Seam_method& m : seam_registry)
      if(m.name == name)
        return &m;
    return nullptr;
  };
  auto asks = [&](const std::string& name) { return std::find(names.begin(), names.end(), name) != names.end(); };
  const bool wants_cgal =
    std::any_of(names.begin(), names.end(), [&](const std::string& n) { return seam_method(n) != nullptr; });
  auto progress = [&](const std::string& name) {
    if(!opt.quiet)
      std::cerr << "compare: " << base.mesh << " (" << base.faces << " faces, " << base.topology << "): " << name
                << " ..." << std::flush;
  };
  auto progress_done = [&](const Row& row) {
    if(!opt.quiet)
      std::cerr << " " << row.status << (std::isfinite(row.seconds) ? ", " + fmt_seconds(row.seconds) + " s" : "")
                << "\n";
  };

  // ICM first: its row, and its seams for CGAL's methods. When overlap removal cut the chart
  // into pieces, the seams do not make one disk: CGAL's methods get the raw cut, ICM's with
  // remove_overlaps = false (shown as icm_keep_overlaps when icm is shown).
  std::map<std::string, Row> done;
  std::vector<std::size_t> cut;
  std::string cut_name, no_cut;
  auto icm_run = [&](bool remove_overlaps, bool shown, Child_result& result) {
    const std::string name = remove_overlaps ? "icm" : "icm_keep_overlaps";
    if(shown)
    {
      progress(name);
      Row row = run_job(icm_job(mesh, remove_overlaps), name, opt, base, &result);
      add_icm_report(row, result);
      progress_done(row);
      done[name] = row;
      return row.status;
    }
    if(!opt.quiet)
      std::cerr << "compare: " << base.mesh << ": " << name << " for the cut ...";
    const Child_outcome o = run_in_child(icm_job(mesh, remove_overlaps), false, opt.time_limit);
    result = o.result;
    const std::string status = status_of(o);
    if(!opt.quiet)
      std::cerr << " " << status << "\n";
    return status;
  };
  if(asks("icm") || (connected && wants_cgal))
  {
    Child_result icm;
    const std::string status = icm_run(true, asks("icm"), icm);
    if(connected && wants_cgal)
    {
      if(status != "ok")
      {
        no_cut = "skipped: no cut (icm " + status + ")";
      }
      else if(extra_value(icm, "charts") > 1)
      {
        Child_result raw;
        const bool show = asks("icm") || asks("icm_keep_overlaps");
        const std::string raw_status = icm_run(false, show, raw);
        if(show && !asks("icm_keep_overlaps"))
          names.insert(std::find(names.begin(), names.end(), "icm") + 1, "icm_keep_overlaps");
        if(raw_status == "ok")
        {
          cut = raw.seams;
          cut_name = "icm_keep_overlaps";
        }
        else
        {
          no_cut = "skipped: no cut (icm_keep_overlaps " + raw_status + ")";
        }
      }
      else
      {
        cut = icm.seams;
        cut_name = "icm";
      }
    }
  }

  bool first = true;
  for(const std::string& name : names)
  {
    Row row;
    if(done.count(name))
    {
      row = done[name];
    }
    else if(name == "icm" || name == "icm_keep_overlaps" || exact_cone_count(name) >= 0)
    {
      progress(name);
      Child_result result;
      row = run_job(icm_pipeline_job(mesh, name), name, opt, base, &result);
      add_icm_report(row, result);
      progress_done(row);
    }
    else if(const Seam_method* m = seam_method(name))
    {
      row = base;
      row.method = name;
      if(!connected)
      {
        row.status = "skipped: " + std::to_string(topology.components) +
                     " components (CGAL's parameterizers take one connected mesh)";
      }
      else if(!no_cut.empty())
      {
        row.status = no_cut;
      }
      else
      {
        progress(name);
        row = run_job(seam_job(mesh, cut, *m), name, opt, base);
        row.detail = "cut: " + cut_name;
        row.json_extra.emplace_back("cut", cut_name);
        row.json_extra.emplace_back("cut_seam_edges", cut.size());
        progress_done(row);
      }
    }
    else if(Job job = icm_energy_job(mesh, name))
    {
      progress(name);
      Child_result result;
      row = run_job(job, name, opt, base, &result);
      add_icm_report(row, result);
      progress_done(row);
    }
    else if(name == "icm_circle_domain")
    {
      const auto method =
        std::find_if(registry.begin(), registry.end(), [&](const Method& r) { return r.name == name; });
      if(!connected || topology.loops < 2 || topology.two_g() != 0)
      {
        row = base;
        row.method = name;
        row.status = "skipped: a circle domain needs one component of genus 0 with several loops";
      }
      else
      {
        progress(name);
        row = run_method(mesh, *method, opt, base);
        progress_done(row);
      }
    }
    else if(name == "icm_free_boundary_opened")
    {
      row = base;
      row.method = name;
      if(!connected || !topology.closed())
      {
        row.status = connected ? "skipped: the mesh is not closed"
                               : "skipped: " + std::to_string(topology.components) + " components";
      }
      else
      {
        Mesh opened = mesh;
        open_at_first_vertex(opened);
        opened.collect_garbage();
        const std::string skip = disk_check(opened);
        const auto method =
          std::find_if(registry.begin(), registry.end(), [](const Method& r) { return r.name == "icm_free_boundary"; });
        if(!skip.empty())
        {
          row.status = "skipped: the opened mesh is " + skip.substr(std::string("skipped: ").size());
        }
        else
        {
          progress(name);
          Child_result result;
          row = run_job(method_job(opened, *method), name, opt, base, &result);
          row.json_extra.emplace_back("opened_vertices", num_vertices(opened));
          row.json_extra.emplace_back("opened_faces", num_faces(opened));
          // The parameterizer's report: its stage times and why it fell back, if it did.
          for(const auto& [key, value] : result.extra)
            row.json_extra.emplace_back(key, json_num(value));
          row.json_extra.emplace_back("fallback_reason",
                                      result.fallback_reason.empty() ? Json() : Json(result.fallback_reason));
          row.note = "opened: " + std::to_string(num_faces(opened)) + " faces";
          if(!result.extra.empty() && row.status == "ok")
          {
            auto x = [&](const char* key) { return fmt_seconds(extra_value(result, key)); };
            row.note += "; index " + x("seconds_index") + " s, metric " + x("seconds_metric") + " s, optimum " +
                        x("seconds_optimum") + " s, layout " + x("seconds_layout") + " s";
          }
          if(!result.fallback_reason.empty())
            row.note += "; fell back: " + result.fallback_reason;
          progress_done(row);
        }
      }
    }
    else
    { // a registry method for disks only
      row = base;
      row.method = name;
      Mesh copy = mesh;
      row.status = disk_check(copy);
    }
    emit(row, first, opt);
    first = false;
  }
}

} // namespace

int main(int argc, char** argv)
{
  ::signal(SIGPIPE, SIG_IGN);
  const std::vector<Method> registry = make_registry();
  const Options opt = parse_options(argc, argv, registry);

  const std::vector<Seam_method> seam_registry = make_seam_registry();
  // The names asked for, once each, in the order given (default: the whole registry for a
  // disk; see surface_names() for the other meshes).
  std::vector<std::string> asked;
  for(const std::string& name : opt.methods)
    if(std::find(asked.begin(), asked.end(), name) == asked.end())
      asked.push_back(name);

  if(!opt.json_file.empty())
  {
    json_file.open(opt.json_file);
    if(!json_file)
    {
      std::cerr << "compare: cannot write " << opt.json_file << "\n";
      return 2;
    }
  }
  if(!opt.json)
  {
    std::cout << "# Parameterization comparison\n\n"
              << "Machine: " << machine_description() << "  \n"
              << "Date: " << date_now() << "  \n"
              << "Runs: "
              << (opt.runs > 0 ? std::to_string(opt.runs) + " per method (median time)"
                               : std::string("3 per method if one takes < 2 s, else 1 (median time)"))
              << "; time limit " << opt.time_limit << " s per run"
              << (opt.subdivide > 0 ? "; Loop subdivision x" + std::to_string(opt.subdivide) : std::string())
              << (opt.open ? "; closed meshes opened by removing the star of their first vertex" : std::string())
              << "\n\n";
    print_markdown_header();
  }

  int exit_status = 0;
  std::string first_mesh_path;
  for(const std::string& path : opt.meshes)
  {
    Mesh mesh;
    std::string error;
    if(!load_mesh(path, opt, mesh, error))
    {
      std::cerr << "compare: " << path << ": " << error << "\n";
      exit_status = 1;
      continue;
    }
    if(first_mesh_path.empty())
      first_mesh_path = path;
    Row base;
    base.mesh = mesh_name(path);
    base.vertices = num_vertices(mesh);
    base.faces = num_faces(mesh);

    const Topology topology = topology_of(mesh);
    if(!topology.disk())
    {
      run_surface(mesh, topology, base, opt, asked, registry, seam_registry);
      continue;
    }

    std::vector<std::string> names = asked;
    if(names.empty())
      for(const Method& m : registry)
        names.push_back(m.name);
    bool first = true;
    for(const std::string& name : names)
    {
      const auto method =
        std::find_if(registry.begin(), registry.end(), [&](const Method& m) { return m.name == name; });
      if(!opt.quiet)
        std::cerr << "compare: " << base.mesh << " (" << base.faces << " faces): " << name << " ..." << std::flush;
      Row row;
      if(method != registry.end())
      {
        row = run_method(mesh, *method, opt, base);
      }
      else if(name == "icm" || name == "icm_keep_overlaps" || exact_cone_count(name) >= 0)
      {
        Child_result result;
        row = run_job(icm_pipeline_job(mesh, name), name, opt, base, &result);
        add_icm_report(row, result);
      }
      else
      { // icm_free_boundary_opened
        row = base;
        row.method = name;
        row.status = "skipped: the mesh is not closed";
      }
      if(!opt.quiet)
        std::cerr << " " << row.status << (std::isfinite(row.seconds) ? ", " + fmt_seconds(row.seconds) + " s" : "")
                  << "\n";
      emit(row, first, opt);
      first = false;
    }
  }

  if(!opt.svg_panels.empty())
  {
    // Drawn after all timed runs, so that the parent's memory seen by later children stays small.
    if(first_mesh_path.empty())
    {
      std::cerr << "compare: --svg-panels: no readable mesh\n";
      exit_status = 1;
    }
    else if(!write_panels(first_mesh_path, opt, registry))
    {
      exit_status = 1;
    }
  }
  return exit_status;
}
