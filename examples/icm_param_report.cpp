// icm_param's JSON line, summary line and JSON error object (icm_param_report.h).

#include "icm_param_report.h"

#include <iostream>

namespace icm_param {

namespace {

Json optional_count(const std::optional<int>& n)
{
  return n ? Json(*n) : Json();
}

/// "1 chart", "3 charts": `n` and the noun, plural unless one.
std::string count_of(long long n, const std::string& noun)
{
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

} // namespace

int Failure_report::operator()(const std::string& reason, int exit_code) const
{
  std::cerr << "icm_param: " << reason << "\n";
  if(json)
  {
    Json error;
    error["error"] = reason;
    error["exit_code"] = exit_code;
    error["input"] = input;
    error["output"] = output;
    std::cout << error.dump(-1, ' ', false, Json::error_handler_t::replace) << "\n";
  }
  return exit_code;
}

Run_figures::Run_figures(const ICM::Surface_parameterization_report& report, std::size_t seam_edges_,
                         const std::string& energy_)
  : components(static_cast<int>(report.charts.size())), seam_edges(seam_edges_), seconds_index(report.seconds_index),
    seconds_cones(report.seconds_cones), seconds_optimum(report.seconds_optimum), seconds_cut(report.seconds_cut),
    seconds_layout(report.seconds_layout), seconds_parameterize(report.seconds_total), energy(energy_),
    optimized_energy(energy_ != ICM::Curvature_entropy::name)
{
  if(optimized_energy)
  {
    const ICM::Energy_summary summary = ICM::energy_summary(report);
    energy_iterations = summary.iterations;
    initial_energy = summary.initial_energy;
    final_energy = summary.final_energy;
    energy_message = summary.message;
  }
  const ICM::Surface_summary s = ICM::surface_summary(report);
  charts = s.charts;
  cones = s.cones;
  wide_cones = s.wide_cones;
  cones_given_up = s.cones_given_up;
  genus = s.genus;
  loops = s.boundary_loops;
  newton = s.newton_iterations;
  factorizations = s.factorizations;
  preconditioned_solves = s.preconditioned_solves;
  moved = s.moved_vertices;
  overlaps = s.overlapping_border_edges;
  raw_overlaps = s.raw_overlapping_border_edges;
  curvature_error = s.max_curvature_error;
  length_error = s.max_layout_length_error;
  seam_error = s.seam_length_error;
  metrics = s.metrics;
  layout = s.layouts;
  fallbacks = s.fallback_reason;
}

Run_figures::Run_figures(const ICM::Parameterization_report& report)
  : loops(report.boundary_loops), newton(report.newton_iterations), moved(report.moved_vertices),
    factorizations(report.factorizations), preconditioned_solves(report.preconditioned_solves),
    overlaps(report.overlapping_border_edges), raw_overlaps(report.overlapping_border_edges),
    curvature_error(report.max_curvature_error), length_error(report.max_layout_length_error), metrics(report.metric),
    fallbacks(report.fallback_reason), layout(report.layout), seconds_index(report.seconds_index),
    seconds_optimum(report.seconds_optimum), seconds_layout(report.seconds_layout),
    seconds_parameterize(report.seconds_total), boundary(report.border_condition),
    degenerate_faces(report.degenerate_faces), border_iterations(report.border_iterations),
    circle_deviation(report.circle_deviation)
{}

Json summary_json(const Arguments& args, const Mesh& mesh, const ICM::IO::Mesh_reading_report& read,
                  const Run_figures& t, const ICM::Distortion_measures& measures, const Timings& seconds)
{
  Json j;
  j["input"] = args.input;
  j["output"] = args.output;
  j["vertices"] = num_vertices(mesh);
  j["faces"] = num_faces(mesh);
  j["charts"] = t.charts;
  j["components"] = t.components;
  j["boundary_loops"] = t.loops;
  j["genus"] = t.genus;
  j["cones"] = t.cones;
  j["cones_above_full_turn"] = t.wide_cones;
  j["cones_given_up"] = t.cones_given_up;
  j["seam_edges"] = t.seam_edges;
  j["seam_length"] = t.seam_length;
  j["layout"] = t.layout;
  j["newton_iterations"] = t.newton;
  j["newton_factorizations"] = t.factorizations;
  j["newton_preconditioned_solves"] = t.preconditioned_solves;
  j["max_curvature_error"] = t.curvature_error;
  j["max_layout_length_error"] = t.length_error;
  j["seam_length_error"] = t.seam_error;
  j["overlapping_border_edges"] = optional_count(t.overlaps);
  j["raw_overlapping_border_edges"] = optional_count(t.raw_overlaps);
  j["moved_vertices"] = t.moved;
  j["metric"] = t.metrics;
  j["metric_fallback"] = t.fallbacks;
  j["energy"] = t.energy;
  if(t.optimized_energy)
  {
    j["energy_iterations"] = t.energy_iterations;
    j["initial_energy"] = t.initial_energy;
    j["final_energy"] = t.final_energy;
    j["energy_message"] = t.energy_message;
  }
  j["boundary"] = t.boundary;
  if(t.boundary != "free")
  {
    j["degenerate_faces"] = t.degenerate_faces;
    j["border_iterations"] = t.border_iterations;
    j["circle_deviation"] = t.circle_deviation;
  }
  if(args.atlas)
  {
    j["atlas_size"] = args.atlas->size;
    j["atlas_padding"] = args.atlas->padding;
    j["atlas_packer"] = ICM::atlas_packer_name(args.atlas->packer);
    j["atlas_charts"] = t.atlas_charts;
    j["atlas_rotated_charts"] = t.atlas_rotated_charts;
    j["atlas_utilization"] = t.atlas_utilization;
  }
  j["flipped_faces"] = measures.flipped_faces;
  j["log_area_distortion"] = measures.log_area_distortion;
  j["log_area_distortion_area_weighted"] = measures.log_area_distortion_area_weighted;
  j["area_ratio_min"] = measures.area_ratio_min;
  j["area_ratio_max"] = measures.area_ratio_max;
  j["qc_mean"] = measures.qc_mean;
  j["isolated_vertices_dropped"] = read.isolated_vertices.size();
  j["vertices_split"] = read.split_vertices.size();
  j["faces_triangulated"] = read.triangulated_faces;
  j["faces_reoriented"] = read.reoriented_faces.size();
  j["repairs"] = read.repairs();
  j["seconds_read"] = seconds.read;
  j["seconds_index"] = t.seconds_index;
  j["seconds_cones"] = t.seconds_cones;
  j["seconds_optimum"] = t.seconds_optimum;
  j["seconds_cut"] = t.seconds_cut;
  j["seconds_layout"] = t.seconds_layout;
  j["seconds_parameterize"] = t.seconds_parameterize;
  j["seconds_write"] = seconds.write;
  j["seconds_total"] = seconds.total;
  return j;
}

void print_summary_line(const Arguments& args, const Mesh& mesh, const Run_figures& t,
                        const ICM::Distortion_measures& measures)
{
  std::cerr << args.input << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces, "
            << count_of(t.components, "component") << ", " << count_of(t.charts, "chart") << ", "
            << count_of(t.cones, "cone") << ", " << count_of(static_cast<long long>(t.seam_edges), "seam edge") << ", "
            << t.newton << " Newton iterations, max |k| " << t.curvature_error << ", ";
  if(t.optimized_energy)
    std::cerr << t.energy << " energy " << t.initial_energy << " -> " << t.final_energy << " in " << t.energy_iterations
              << " steps, ";
  if(args.atlas)
    std::cerr << "atlas " << args.atlas->size << " texels, " << count_of(t.atlas_charts, "chart") << " covering "
              << 100 * t.atlas_utilization << "%, ";
  std::cerr << measures.flipped_faces << " flipped faces, log area distortion " << measures.log_area_distortion << ", "
            << t.seconds_parameterize << " s -> " << args.output << "\n";
}

} // namespace icm_param
