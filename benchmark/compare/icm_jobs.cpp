// The jobs of ICM's whole pipeline, ICM::parameterize() (jobs.h): the rows icm,
// icm_keep_overlaps, icm_cones_N, icm_u_square_cones_N and, on a surface that is not a disk,
// the energies' rows.

#include "jobs.h"

#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <child_process.h>

#include <chrono>
#include <type_traits>

namespace compare {

namespace {

// The report's charts summed: the Newton steps, the metric(s) and the counts as extras, then
// the report's stage times.
void add_report(const ICM::Surface_parameterization_report& report, std::size_t seam_edges, Child_result& r)
{
  int newton = 0, cones = 0, given_up = 0, pieces = 0, raw_crossings = 0, crossings = 0, overlap_cuts = 0;
  double seam_length = 0; // over the square root of the area; one component's, else summed
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
    seam_length += c.seam_length;
    if(metric.find(c.metric) == std::string::npos)
      metric += (metric.empty() ? "" : "/") + c.metric;
    if(!c.fallback_reason.empty() && fallback.empty())
      fallback = c.fallback_reason;
  }
  r.newton_iterations = newton;
  r.metric = metric + (fallback.empty() ? "" : ", fallback");
  r.extra = {{"cones", cones},
             {"cones_given_up", given_up},
             {"seam_edges", static_cast<double>(seam_edges)},
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
}

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
    r.peak_rss_mb = icm_tools::peak_rss_mb();
    r.code = static_cast<int>(report.status);
    r.seconds = std::chrono::duration<double>(t1 - t0).count();
    r.message = report.message;
    add_report(report, seams.size(), r);
    if constexpr(!std::is_same<Energy, CGAL::Default>::value)
    {
      const ICM::Energy_summary energy = ICM::energy_summary(report);
      r.extra.push_back({"energy_iterations", static_cast<double>(energy.iterations)});
      r.extra.push_back({"initial_energy", energy.initial_energy});
      r.extra.push_back({"final_energy", energy.final_energy});
    }
    // Only a successful call writes UVs (a failing component returns before the layout is
    // written), so nothing is measured otherwise.
    if(report.status != SMP::OK)
      return;
    for(edge_descriptor e : seams)
      r.seams.push_back(static_cast<std::size_t>(e));
    if(measure)
    {
      r.m = to_measures(ICM::measure_distortion_corner_uv(mesh, uvmap));
      r.has_measures = true;
    }
  };
}

} // namespace

Job icm_pipeline_job(const Mesh& mesh, const std::string& name)
{
  if(name.rfind(u_square_cones_prefix, 0) == 0)
    return icm_job<ICM::U_square>(mesh, true, exact_cone_count(name));
  return icm_job(mesh, name != "icm_keep_overlaps", exact_cone_count(name));
}

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

} // namespace compare
