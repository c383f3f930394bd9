// compare's registry of the methods run on a disk (methods.h), and the names of the rows of a
// surface that is not a disk.

#include "methods.h"

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/parameterize.h>

#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>

#include <algorithm>

namespace compare {

namespace {

// A CGAL parameterizer, default constructed.
template <class Parameterizer>
Method cgal_method(std::string name)
{
  return {std::move(name), [](Mesh& mesh, halfedge_descriptor bhd, UV_map uvmap) {
            return timed_parameterize(mesh, Parameterizer(), bhd, uvmap);
          }};
}

// The named numbers of an ICM parameterizer's report: its times and, for an energy other
// than the entropy or for the circle domain, its optimizer's steps and values.
template <class Parameterizer>
std::vector<std::pair<std::string, double>> report_numbers(const ICM::Parameterization_report& report)
{
  std::vector<std::pair<std::string, double>> numbers = {
    {"seconds_index", report.seconds_index},     {"seconds_metric", report.seconds_metric},
    {"seconds_optimum", report.seconds_optimum}, {"seconds_layout", report.seconds_layout},
    {"seconds_total", report.seconds_total},     {"border_crossings", report.overlapping_border_edges}};
  if(Parameterizer::optimizes_energy)
    numbers.insert(numbers.end(), {{"energy_iterations", report.energy_iterations},
                                   {"initial_energy", report.initial_energy},
                                   {"final_energy", report.final_energy}});
  if(report.border_condition == ICM::Circle_domain().name())
    numbers.insert(numbers.end(),
                   {{"border_iterations", report.border_iterations}, {"circle_deviation", report.circle_deviation}});
  return numbers;
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
            r.report_numbers = report_numbers<Parameterizer>(report);
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

} // namespace

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

const Method* find_method(const std::vector<Method>& registry, const std::string& name)
{
  const auto it = std::find_if(registry.begin(), registry.end(), [&](const Method& m) { return m.name == name; });
  return it == registry.end() ? nullptr : &*it;
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

int exact_cone_count(const std::string& name)
{
  for(const std::string& prefix : {std::string("icm_cones_"), u_square_cones_prefix})
    if(name.rfind(prefix, 0) == 0)
      return std::stoi(name.substr(prefix.size()));
  return -1;
}

const std::vector<std::string> panel_methods = {"icm_free_boundary", "lscm", "arap"};

} // namespace compare
