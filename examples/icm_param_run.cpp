// icm_param's run of one mesh (icm_param_run.h). Every energy goes through ICM::parameterize
// (every surface, cones and seams where its topology needs them): the curvature entropy (the
// default) directly, its runs instantiated here, another energy minimised over the border and
// the cones from there (icm_param_energy.h). A prescribed border (--boundary) goes through
// Inverse_curvature_map_parameterizer_3, on a disk (icm_param_border.cpp).

#include "icm_param_run.h"

#include "icm_param_energy.h"
#include "icm_param_output.h"
#include "icm_param_progress.h"
#include "icm_param_report.h"

#include <ICM/IO/read_seam_selection.h>
#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/measures/Distortion.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/parameterize.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace icm_param {

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;

/// Meshes from this size get a progress line on stderr (a run takes seconds from there).
constexpr std::size_t progress_min_faces = 100000;

// --- input -----------------------------------------------------------------------------

/// The vertices of `mesh` that each of the input file's vertex indices names (none for a
/// dropped isolated vertex, several for a split non-manifold one).
std::vector<std::vector<Mesh::Vertex_index>> vertices_by_file_index(const Mesh& mesh,
                                                                    const ICM::IO::Mesh_reading_report& read)
{
  std::vector<std::vector<Mesh::Vertex_index>> by_index(read.file_vertices);
  std::size_t i = 0;
  for(Mesh::Vertex_index v : vertices(mesh))
    by_index[read.file_vertex[i++]].push_back(v);
  return by_index;
}

/// The user's cones as curvatures at vertices of the mesh; empty `error` on success.
std::map<Mesh::Vertex_index, double>
user_cones(const Arguments& args, const std::vector<std::vector<Mesh::Vertex_index>>& by_index, std::string& error)
{
  std::map<Mesh::Vertex_index, double> cones;
  for(const auto& [vertex, degrees] : args.cones)
  {
    const std::string option = "--cone " + std::to_string(vertex) + ": ";
    if(static_cast<std::size_t>(vertex) >= by_index.size())
      error = option + "the mesh has " + std::to_string(by_index.size()) + " vertices";
    else if(by_index[vertex].empty())
      error = option + "vertex " + std::to_string(vertex) + " is in no face (it was dropped)";
    else if(by_index[vertex].size() > 1)
      error = option + "vertex " + std::to_string(vertex) + " is non-manifold and was split into " +
              std::to_string(by_index[vertex].size()) + " vertices";
    if(!error.empty())
      return {};
    cones[by_index[vertex].front()] = 2 * M_PI - degrees * M_PI / 180;
  }
  return cones;
}

/// The cones (first line) and seams (third line on) of the --seams file, as CGAL's orbifold
/// and seam examples write them: the cones join `cones` with the angle the optimum chooses (a
/// --cone at the same vertex keeps its angle); empty `error` on success.
bool read_selection_cones_and_seams(const Arguments& args, const Mesh& mesh,
                                    const std::vector<std::vector<Mesh::Vertex_index>>& by_index,
                                    std::map<Mesh::Vertex_index, double>& cones, std::vector<Mesh::Edge_index>& seams,
                                    std::string& error)
{
  std::vector<Mesh::Vertex_index> selected;
  if(!ICM::IO::read_selection(args.seams, mesh, by_index, selected, seams, error))
    return false;
  for(Mesh::Vertex_index v : selected)
    cones.emplace(v, std::nan(""));
  return true;
}

// --- the run ---------------------------------------------------------------------------

template <class Metric>
ICM::Surface_parameterization_report
run_metric(const Mesh& mesh, Mesh::Property_map<Mesh::Halfedge_index, Kernel::Point_2> uv,
           const ICM::Surface_parameterization_options& options, const std::map<Mesh::Vertex_index, double>& cones,
           std::vector<Mesh::Edge_index>& seams, const std::vector<Mesh::Edge_index>& user_seams)
{
  return ICM::parameterize<Metric>(mesh, uv, options, cones, &seams, user_seams);
}

/// A prescribed border by name; the parameterizer is instantiated for each in
/// icm_param_border.cpp.
ICM::Parameterization_report run_border(const Arguments& args, Mesh& mesh, Corner_uv_map uvmap)
{
  if(args.boundary == "circle")
    return parameterize_disk<ICM::Circular_border<Mesh>>(mesh, args.metric, uvmap);
  if(args.boundary == "square")
    return parameterize_disk<ICM::Square_border<Mesh>>(mesh, args.metric, uvmap);
  return parameterize_disk<ICM::Circle_domain>(mesh, args.metric, uvmap);
}

/// Why the map of a prescribed border is not written, or empty: it folds over itself, and
/// one chart with a UV per vertex cannot be cut apart where it does, as the free border's
/// charts are.
std::string why_an_overlap_is_refused(const Arguments& args, const ICM::Parameterization_report& report)
{
  if(args.keep_overlaps || report.overlapping_border_edges == 0)
    return {};
  return std::string(ICM::error_message(SMP::ERROR_NO_1_TO_1_MAPPING)) + ": the map with the " + args.boundary +
         " border folds over itself (" + std::to_string(report.overlapping_border_edges) +
         " pairs of border edges cross) and is one chart, not cut where it overlaps (with a free border it "
         "is); --keep-overlaps writes it anyway";
}

/// Any energy on any surface, by `ICM::parameterize` (cones and seams where needed): the
/// figures of its run into `figures`, or the reason it failed. The entropy's runs are
/// instantiated here, the other energies' each in its own file (icm_param_energy.h).
std::string run_surface(const Arguments& args, const Mesh& mesh, const std::map<Mesh::Vertex_index, double>& cones,
                        const std::vector<Mesh::Edge_index>& user_seams, Corner_uv_map uvmap,
                        std::optional<Run_figures>& figures)
{
  ICM::Surface_parameterization_options options;
  options.remove_overlaps = !args.keep_overlaps;
  options.atlas = args.atlas;
  if(args.max_cones >= 0)
  {
    options.automatic_cones = args.max_cones > 0;
    options.cones.max_cones = args.max_cones;
    options.initial_cones = std::min(options.initial_cones, args.max_cones);
    // A count is exact: no stop on distortion, and a disk gets its cones too.
    options.cones.max_log_scale = 0;
    options.border_max_log_scale = 0;
  }
  if(args.cone_target > 0)
    options.cones.max_log_scale = args.cone_target;
  if(args.cone_placement == "exact")
    options.cones.placement = ICM::Cone_placement::Exact_optimum;
  options.cones.exact_sweeps = !args.no_cone_sweeps;
  if(args.cone_angles != "auto")
    options.cones.angles = args.cone_angles == "entropy" ? ICM::Cone_angles::Entropy : ICM::Cone_angles::Least_log_area;
  // A selection file's cones and seams are the singular set, as in CGAL's orbifold examples
  // (its seams alone turn automatic cones off in the library): --cones adds to them.
  if(!args.seams.empty() && !args.cones_asked)
    options.automatic_cones = false;
  Progress_line progress(!args.quiet && num_faces(mesh) >= progress_min_faces);
  options.progress = [&progress](const std::string& stage, double fraction) { progress(stage, fraction); };

  std::vector<Mesh::Edge_index> seams;
  const ICM::Surface_parameterization_report report =
    args.energy == ICM::U_square::name
      ? parameterize_surface<ICM::U_square>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Area_distortion::name
      ? parameterize_surface<ICM::Area_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Angle_distortion::name
      ? parameterize_surface<ICM::Angle_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Log_area_distortion::name
      ? parameterize_surface<ICM::Log_area_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Circle_packing_metric::name
      ? run_metric<ICM::Circle_packing_metric>(mesh, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Inversive_distance_metric::name
      ? run_metric<ICM::Inversive_distance_metric>(mesh, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Vertex_scaling_metric::name
      ? run_metric<ICM::Vertex_scaling_metric>(mesh, uvmap, options, cones, seams, user_seams)
      : run_metric<ICM::Intrinsic_delaunay_metric>(mesh, uvmap, options, cones, seams, user_seams);
  progress.finish();
  if(report.status != SMP::OK)
    return std::string(ICM::error_message(report.status)) + ": " + report.message;
  figures.emplace(report, seams.size(), args.energy);
  figures->atlas_charts = report.atlas_charts;
  figures->atlas_rotated_charts = report.atlas_rotated_charts;
  figures->atlas_utilization = report.atlas_utilization;
  figures->seam_length = ICM::seam_length_over_root_area(mesh, seams);
  return {};
}

} // namespace

int run(const Arguments& args, const Failure_report& fail)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  Timings seconds;

  const std::string bad_output = check_output_paths(args);
  if(!bad_output.empty())
    return fail(bad_output);

  Clock::time_point t = Clock::now();
  Mesh mesh;
  ICM::IO::Mesh_reading_options reading;
  reading.triangulate = args.triangulate;
  ICM::IO::Mesh_reading_report read;
  if(!ICM::IO::read_triangle_mesh(args.input, mesh, read, reading))
    return fail(read.message +
                (read.non_triangle_faces > 0 && !args.triangulate ? " (--triangulate splits them)" : ""));
  seconds.read = since(t);
  // From here on a failure also says what was repaired: it may be why (a dropped vertex).
  std::string repairs;
  for(const std::string& repair : read.repairs())
    repairs += (repairs.empty() ? " (the input was repaired: " : "; ") + repair;
  if(!repairs.empty())
    repairs += ")";
  auto fail_after_reading = [&](const std::string& reason) { return fail(reason + repairs); };

  const std::vector<std::vector<Mesh::Vertex_index>> by_index = vertices_by_file_index(mesh, read);
  std::string error;
  std::map<Mesh::Vertex_index, double> cones = user_cones(args, by_index, error);
  if(!error.empty())
    return fail_after_reading(error);
  std::vector<Mesh::Edge_index> user_seams;
  if(!args.seams.empty() && !read_selection_cones_and_seams(args, mesh, by_index, cones, user_seams, error))
    return fail_after_reading(error);

  auto uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  std::optional<Run_figures> figures;
  if(prescribes_border(args))
  {
    if(const std::string refused = why_the_border_is_refused("--boundary " + args.boundary, args.boundary, mesh);
       !refused.empty())
      return fail_after_reading(refused);
    const ICM::Parameterization_report report = run_border(args, mesh, uvmap);
    if(report.status != SMP::OK)
      return fail_after_reading(std::string(ICM::error_message(report.status)) + ": " + report.message);
    if(const std::string overlap = why_an_overlap_is_refused(args, report); !overlap.empty())
      return fail_after_reading(overlap);
    figures.emplace(report);
  }
  else
  {
    const std::string reason = run_surface(args, mesh, cones, user_seams, uvmap, figures);
    if(!reason.empty())
      return fail_after_reading(reason);
  }

  t = Clock::now();
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);
  ICM::IO::Mesh_writing_options mesh_options;
  mesh_options.binary_ply = args.ply_binary;
  if(!ICM::IO::write_uv_files(args.output, pictures_of(args), uv_mesh, error, mesh_options))
    return fail_after_reading(error);
  seconds.write = since(t);
  const ICM::Distortion_measures measures = ICM::measure_distortion_corner_uv(mesh, uvmap);
  seconds.total = since(start);

  if(args.json)
    std::cout << summary_json(args, mesh, read, *figures, measures, seconds)
                   .dump(-1, ' ', false, Json::error_handler_t::replace)
              << "\n";
  else
  {
    for(const std::string& repair : read.repairs())
      std::cerr << "icm_param: " << args.input << ": " << repair << "\n";
    print_summary_line(args, mesh, *figures, measures);
  }
  return 0;
}

} // namespace icm_param
