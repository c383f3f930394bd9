// The runs of `icm.parameterize` (icm_module_run.h).

#include "icm_module_run.h"

#include <ICM/border/Border_conditions.h>

namespace icm_module {

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;

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
  s.factorizations = r.factorizations;
  s.preconditioned_solves = r.preconditioned_solves;
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

} // namespace

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

} // namespace icm_module
