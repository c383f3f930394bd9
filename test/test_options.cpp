// Every option and every descriptor argument is checked on entry: an out-of-range value, a
// non-finite number, a null or foreign descriptor is refused with ERROR_WRONG_PARAMETER and
// a message that names it. Never a crash, never silently accepted.

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/parameterize.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/io.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

const double nan_value = std::numeric_limits<double>::quiet_NaN();
const double inf_value = std::numeric_limits<double>::infinity();

Mesh read(const std::string& name)
{
  Mesh mesh;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path(name), mesh)) << name;
  return mesh;
}

/// One bad value of one option: the name the message must give, and how to set it.
template <class Options>
struct Bad_option
{
  std::string name;
  std::function<void(Options&)> set;
};

/// The bad values of every field of `Newton_options`, under `prefix`.
template <class Options>
void add_newton_cases(std::vector<Bad_option<Options>>& cases, const std::string& prefix,
                      std::function<ICM::Newton_options&(Options&)> field)
{
  auto add = [&](const std::string& name, std::function<void(ICM::Newton_options&)> set) {
    cases.push_back({prefix + name, [field, set](Options& o) { set(field(o)); }});
  };
  add("tolerance", [](ICM::Newton_options& o) { o.tolerance = nan_value; });
  add("tolerance", [](ICM::Newton_options& o) { o.tolerance = 0; });
  add("tolerance", [](ICM::Newton_options& o) { o.tolerance = inf_value; });
  add("max_iterations", [](ICM::Newton_options& o) { o.max_iterations = -1; });
  add("max_line_search_steps", [](ICM::Newton_options& o) { o.max_line_search_steps = 0; });
  add("max_step", [](ICM::Newton_options& o) { o.max_step = -1; });
  add("max_step", [](ICM::Newton_options& o) { o.max_step = nan_value; });
  add("max_blocked_steps", [](ICM::Newton_options& o) { o.max_blocked_steps = 0; });
}

/// The bad values of every field of `Curvature_space_options`, under `prefix`.
template <class Options>
void add_energy_cases(std::vector<Bad_option<Options>>& cases, const std::string& prefix,
                      std::function<ICM::Curvature_space_options&(Options&)> field)
{
  auto add = [&](const std::string& name, std::function<void(ICM::Curvature_space_options&)> set) {
    cases.push_back({prefix + name, [field, set](Options& o) { set(field(o)); }});
  };
  using E = ICM::Curvature_space_options;
  add("tolerance", [](E& o) { o.tolerance = -1; });
  add("tolerance", [](E& o) { o.tolerance = nan_value; });
  add("energy_tolerance", [](E& o) { o.energy_tolerance = nan_value; });
  add("stall_window", [](E& o) { o.stall_window = 0; });
  add("max_iterations", [](E& o) { o.max_iterations = -3; });
  add("max_step", [](E& o) { o.max_step = 0; });
  add("memory", [](E& o) { o.memory = 0; });
  add("frozen_steps", [](E& o) { o.frozen_steps = -1; });
  add("trial_tolerance_factor", [](E& o) { o.trial_tolerance_factor = -0.5; });
  add("preconditioner", [](E& o) { o.preconditioner = static_cast<ICM::Lbfgs_preconditioner>(17); });
  add("max_line_search_steps", [](E& o) { o.max_line_search_steps = 0; });
  add("armijo", [](E& o) { o.armijo = 0; });
  add("armijo", [](E& o) { o.armijo = 1; });
  add_newton_cases<Options>(cases, prefix + "newton.",
                            [field](Options& o) -> ICM::Newton_options& { return field(o).newton.emplace(); });
}

std::vector<Bad_option<ICM::Surface_parameterization_options>> surface_cases()
{
  using O = ICM::Surface_parameterization_options;
  std::vector<Bad_option<O>> cases = {
    {"cones.max_log_scale", [](O& o) { o.cones.max_log_scale = -1; }},
    {"cones.placement", [](O& o) { o.cones.placement = static_cast<ICM::Cone_placement>(7); }},
    {"cones.ranked_candidates", [](O& o) { o.cones.ranked_candidates = 0; }},
    {"cones.sweeps", [](O& o) { o.cones.sweeps = -1; }},
    {"cones.angles", [](O& o) { o.cones.angles = static_cast<ICM::Cone_angles>(3); }},
    {"cones.max_log_scale", [](O& o) { o.cones.max_log_scale = nan_value; }},
    {"cones.max_cones", [](O& o) { o.cones.max_cones = -1; }},
    {"initial_cones", [](O& o) { o.initial_cones = -5; }},
    {"border_max_log_scale", [](O& o) { o.border_max_log_scale = -1; }},
    {"border_max_log_scale", [](O& o) { o.border_max_log_scale = nan_value; }},
    {"max_layout_length_error", [](O& o) { o.max_layout_length_error = 0; }},
    {"max_layout_length_error", [](O& o) { o.max_layout_length_error = nan_value; }},
  };
  add_newton_cases<O>(cases, "newton.", [](O& o) -> ICM::Newton_options& { return o.newton; });
  add_newton_cases<O>(cases, "cones.newton.", [](O& o) -> ICM::Newton_options& { return o.cones.newton.emplace(); });
  add_energy_cases<O>(cases, "energy.", [](O& o) -> ICM::Curvature_space_options& { return o.energy; });
  return cases;
}

std::vector<Bad_option<ICM::Parameterization_options>> disk_cases()
{
  using O = ICM::Parameterization_options;
  std::vector<Bad_option<O>> cases = {
    {"diffusion.tolerance", [](O& o) { o.diffusion.tolerance = nan_value; }},
    {"diffusion.max_iterations", [](O& o) { o.diffusion.max_iterations = -1; }},
    {"diffusion.step_fraction", [](O& o) { o.diffusion.step_fraction = 0; }},
    {"diffusion.step_fraction", [](O& o) { o.diffusion.step_fraction = 1.5; }},
    {"optimum", [](O& o) { o.optimum = static_cast<ICM::Optimum_method>(5); }},
    {"layout", [](O& o) { o.layout = static_cast<ICM::Layout_method>(-1); }},
    {"harmonic_layout_min_faces", [](O& o) { o.harmonic_layout_min_faces = -1; }},
    {"max_layout_length_error", [](O& o) { o.max_layout_length_error = -1e-6; }},
  };
  add_newton_cases<O>(cases, "newton.", [](O& o) -> ICM::Newton_options& { return o.newton; });
  add_energy_cases<O>(cases, "energy.", [](O& o) -> ICM::Curvature_space_options& { return o.energy; });
  return cases;
}

/// The message must name the option, as "option NAME = VALUE: why".
void expect_refused(SMP::Error_code status, const std::string& message, const std::string& name)
{
  EXPECT_EQ(status, SMP::ERROR_WRONG_PARAMETER) << name << ": " << message;
  EXPECT_NE(message.find("option " + name + " = "), std::string::npos) << name << ": " << message;
}

TEST(Options, EveryBadSurfaceOptionIsRefusedByName)
{
  Mesh mesh = read("nefertiti.off");
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  const auto cases = surface_cases();
  EXPECT_GE(cases.size(), 40u);
  for(const auto& bad : cases)
  {
    ICM::Surface_parameterization_options options;
    bad.set(options);
    const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, uv, options);
    expect_refused(report.status, report.message, bad.name);
    EXPECT_TRUE(report.charts.empty()) << bad.name << ": refused before any work";
  }
  // The same options, whole, are accepted.
  EXPECT_EQ(ICM::parameterize(mesh, uv).status, SMP::OK);
}

TEST(Options, EveryBadDiskOptionIsRefusedByName)
{
  Mesh mesh = read("nefertiti.off");
  auto uv = mesh.add_property_map<Mesh::Vertex_index, Point_2>("v:uv").first;
  const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  const auto cases = disk_cases();
  EXPECT_GE(cases.size(), 30u);
  for(const auto& bad : cases)
  {
    ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
    bad.set(parameterizer.options());
    const SMP::Error_code status = SMP::parameterize(mesh, parameterizer, bhd, uv);
    expect_refused(status, parameterizer.report().message, bad.name);
  }
}

TEST(Options, LowerLayersRefuseBadOptionsToo)
{
  // The public lower layers check what they take: L-BFGS without memory used to write past
  // its ring (SIGSEGV), Newton with a NaN tolerance to run on and flip faces.
  const ICM::internal::Mesh_index index = icm_test::index_of(icm_test::data_path("nefertiti.off"));
  const ICM::Circle_packing_metric metric(index);
  Eigen::VectorXd u;
  ICM::Newton_options newton;
  newton.tolerance = nan_value;
  const ICM::Newton_report solved =
    ICM::free_boundary_optimum(index, metric, ICM::boundary_singular_set(index), u, newton);
  EXPECT_FALSE(solved.converged);
  EXPECT_NE(solved.message.find("option newton.tolerance = nan"), std::string::npos) << solved.message;

  ICM::Curvature_space_options energy;
  energy.memory = 0;
  u = metric.u0;
  const ICM::Curvature_space_report optimized = ICM::minimize_energy_on_singular_values(
    index, metric, ICM::boundary_singular_set(index), ICM::Log_area_distortion(), u, energy);
  EXPECT_TRUE(optimized.energy_history.empty());
  EXPECT_NE(optimized.message.find("option energy.memory = 0"), std::string::npos) << optimized.message;

  ICM::Cone_options cones;
  cones.max_cones = -2;
  const ICM::Cone_selection selection = ICM::greedy_cones(index, metric, {}, cones);
  EXPECT_FALSE(selection.ok());
  EXPECT_NE(selection.message.find("option cones.max_cones = -2"), std::string::npos) << selection.message;

  ICM::Diffusion_options diffusion;
  diffusion.step_fraction = nan_value;
  const ICM::Diffusion_report diffused =
    ICM::free_boundary_curvature_diffusion(index, metric, ICM::boundary_singular_set(index), u, diffusion);
  EXPECT_FALSE(diffused.converged);
  EXPECT_NE(diffused.message.find("option diffusion.step_fraction = nan"), std::string::npos) << diffused.message;
}

TEST(Options, OneNewtonOptionsServeEveryStageUnlessOneSetsItsOwn)
{
  ICM::Surface_parameterization_options options;
  options.newton.tolerance = 1e-7;
  options.newton.max_iterations = 7;
  // Unset, the cones' and the energy's Newton are the run's.
  EXPECT_FALSE(options.cones.newton.has_value());
  EXPECT_FALSE(options.energy.newton.has_value());
  EXPECT_EQ(ICM::with_newton(options.cones, options.newton).newton->tolerance, 1e-7);
  EXPECT_EQ(ICM::with_newton(options.energy, options.newton).newton->max_iterations, 7);
  // Set on purpose, a stage keeps its own.
  options.cones.newton.emplace().tolerance = 1e-12;
  EXPECT_EQ(ICM::with_newton(options.cones, options.newton).newton->tolerance, 1e-12);
  EXPECT_EQ(ICM::with_newton(options.cones, options.newton).newton->max_iterations, 100);

  // And the run's Newton reaches the cone placement on the exact optimum (the linearized
  // one runs no Newton): with one Newton step allowed, placing cones on a closed surface
  // cannot converge, which the run reports from that stage.
  Mesh sphere = read("sphere966.off");
  auto uv = sphere.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  ICM::Surface_parameterization_options starved;
  starved.cones.placement = ICM::Cone_placement::Exact_optimum;
  starved.newton.max_iterations = 1;
  const ICM::Surface_parameterization_report report = ICM::parameterize(sphere, uv, starved);
  EXPECT_EQ(report.status, SMP::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM) << report.message;
  starved.cones.newton = ICM::Newton_options();
  const ICM::Surface_parameterization_report own = ICM::parameterize(sphere, uv, starved);
  EXPECT_NE(own.message, report.message) << "the cones' own Newton options must take the cone placement further";
}

TEST(Options, ForeignAndNullDescriptorsAreRefused)
{
  Mesh mesh = read("nefertiti.off");
  Mesh bigger = read("three_peaks.off"); // its descriptors are out of nefertiti's range
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  auto last = [](const auto& range) {
    auto it = range.begin();
    std::advance(it, std::distance(range.begin(), range.end()) - 1);
    return *it;
  };

  auto refused = [&](const std::map<Mesh::Vertex_index, double>& cones, const std::vector<Mesh::Edge_index>& seams,
                     const std::string& why) {
    const auto report = ICM::parameterize(mesh, uv, {}, cones, nullptr, seams);
    EXPECT_EQ(report.status, SMP::ERROR_WRONG_PARAMETER) << why << ": " << report.message;
    EXPECT_NE(report.message.find(why), std::string::npos) << report.message;
  };
  refused({{Mesh::Vertex_index(), NAN}}, {}, "a user cone is the null vertex");
  refused({{last(vertices(bigger)), NAN}}, {}, "a user cone is not a vertex of this mesh");
  refused({}, {Mesh::Edge_index()}, "a user seam is not an edge of this mesh");
  refused({}, {last(edges(bigger))}, "a user seam is not an edge of this mesh");

  // The disk parameterizer's border halfedge, given to its own parameterize() (CGAL's
  // wrapper walks the halfedge's component before it calls the parameterizer).
  auto vertex_uv = mesh.add_property_map<Mesh::Vertex_index, Point_2>("v:uv").first;
  auto vertex_index = mesh.add_property_map<Mesh::Vertex_index, int>("v:index").first;
  auto parameterized = mesh.add_property_map<Mesh::Vertex_index, bool>("v:parameterized").first;
  ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
  EXPECT_EQ(parameterizer.parameterize(mesh, last(halfedges(bigger)), vertex_uv, vertex_index, parameterized),
            SMP::ERROR_WRONG_PARAMETER);
  EXPECT_EQ(parameterizer.report().message, "the border halfedge given is not a halfedge of this mesh");
}

TEST(Options, ForeignPolyhedronDescriptorsAreRefused)
{
  // A Polyhedron_3's descriptors are handles: one of another polyhedron is a valid pointer,
  // told apart by comparison only.
  using Polyhedron = CGAL::Polyhedron_3<Kernel>;
  Polyhedron mesh, other;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("nefertiti.off"), mesh));
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("nefertiti.off"), other));
  std::map<Polyhedron::Halfedge_handle, Point_2> corners;
  auto uv = boost::make_assoc_property_map(corners);
  std::map<boost::graph_traits<Polyhedron>::vertex_descriptor, double> cones;
  for(auto v : vertices(other))
    if(!is_border(v, other))
    {
      cones[v] = NAN;
      break;
    }
  EXPECT_EQ(ICM::parameterize(mesh, uv, {}, cones).status, SMP::ERROR_WRONG_PARAMETER);
  std::vector<boost::graph_traits<Polyhedron>::edge_descriptor> seams;
  for(auto e : edges(other))
    if(!is_border(e, other))
    {
      seams.push_back(e);
      break;
    }
  const auto report = ICM::parameterize(mesh, uv, {}, {}, nullptr, seams);
  EXPECT_EQ(report.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_EQ(report.message, "a user seam is not an edge of this mesh (or is the null edge)");
}

TEST(Options, GaussBonnetViolationIsAWrongParameter)
{
  // Every angle of a closed surface prescribed, summing to less than 2 pi chi.
  Mesh mesh = read("sphere966.off");
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  std::map<Mesh::Vertex_index, double> cones;
  auto v = vertices(mesh).begin();
  cones[*v++] = M_PI;
  cones[*v++] = M_PI / 2;
  const auto report = ICM::parameterize(mesh, uv, {}, cones);
  EXPECT_EQ(report.status, SMP::ERROR_WRONG_PARAMETER) << report.message;
  EXPECT_NE(report.message.find("Gauss-Bonnet"), std::string::npos) << report.message;
}

} // namespace
