// The cone angles a named count tries on the exact map (`Cone_angles`): the entropy's, the
// least linearized log^2 area's and halfway between, each cut along 3D shortest paths and,
// where its layout folds, along the flat metric's; the map that measures better is kept.

#ifndef ICM_PIPELINE_CONE_ANGLE_TRIALS_H
#define ICM_PIPELINE_CONE_ANGLE_TRIALS_H

#include <ICM/Status.h>
#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/pipeline/Component_cones.h>
#include <ICM/pipeline/Singular_set_chart.h>
#include <ICM/cut/Cut_mesh.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {

/// Whether the layout of `chart` folds: a flipped face or two border edges that cross.
inline bool folds(const Chart_report& chart)
{
  return chart.overlapping_border_edges > 0 || chart.flipped_faces > 0;
}

/// `trial` moved the fraction `t` of the way from the entropy's angles (the placement's
/// predictions `expected_curvature`) to its own. The linearized metric is affine in the
/// angles, so its first step moves the same way from the entropy's `entropy_step`.
inline Cone_angle_trial part_way(const Cone_angle_trial& trial, const std::vector<double>& expected_curvature,
                                 const Eigen::VectorXd& entropy_step, double t)
{
  Cone_angle_trial moved = trial;
  for(std::size_t v = 0; v < moved.prescribed.size(); ++v)
    if(!std::isnan(moved.prescribed[v]))
      moved.prescribed[v] = expected_curvature[v] + t * (trial.prescribed[v] - expected_curvature[v]);
  if(entropy_step.size() == trial.first_step.size())
    moved.first_step = entropy_step + t * (trial.first_step - entropy_step);
  else
    moved.first_step.resize(0);
  return moved;
}

/// Per edge, its length in the metric of log scale `log_scale` (u - u0 per vertex) by vertex
/// scaling: the flat metric's, to cut along (`Cut_graph_options::path_lengths`).
inline std::vector<double> flat_path_lengths(const Mesh_index& index, const Eigen::VectorXd& log_scale)
{
  std::vector<double> lengths(index.edges.size());
  for(int e = 0; e < index.number_of_edges(); ++e)
    lengths[e] = edge_length(index, e) * std::exp(0.5 * (log_scale[index.edges[e][0]] + log_scale[index.edges[e][1]]));
  return lengths;
}

/// `cut_and_solve` with the automatic cones at the entropy's angles and at those of `trial`
/// (the least linearized log^2 area), keeping the exact map that measures better; when the
/// trial's does not, halfway between the two as well (the extreme angles of the trial fold
/// the layout or leave Newton's reach on limb-heavy meshes, camel or bull at 8 cones). A map
/// measures better with a lower area-weighted mean log^2 area (what the report measures),
/// one that folds (the overlap removal cuts it) taken at `fewer_cones_distortion_factor`
/// times its own. A map that folds is tried again cut along its linearized flat metric's
/// shortest paths rather than the 3D ones. Only the entropy's angles,
/// the map of last resort, fall back to the circle packing: the others' maps there fold
/// or fail as well, at the time of another solve (camel, bull). With
/// `Cone_angles::Least_log_area` the trial's angles alone, unless they fail.
template <class Metric, class Solver, class Energy>
Status cut_and_solve_with_the_better_angles(
  const Mesh_index& index, const std::vector<char>& is_singular, const std::vector<double>& prescribed,
  const std::vector<double>& expected_curvature, Eigen::VectorXd first_step, const Cone_angle_trial& trial,
  const Surface_parameterization_options& options, Surface_parameterization_report& report, const Chart_report& before,
  Chart_report& chart, Cut_mesh& cut, std::vector<Uv>& uv, const Energy& energy, const Stage_progress& progress)
{
  Status first_failure; // the reason, should no map be kept
  double kept_score = 0;
  int maps_kept = 0;
  Surface_parameterization_options trial_options = options;
  trial_options.fall_back_to_circle_packing = false;
  // Solves at `angles` from `start` and keeps the map if it measures better than the one
  // kept. Returns whether the map folds but, cut
  // otherwise, might measure better: its own distortion is below the kept map's score.
  const auto consider = [&](const std::vector<double>& angles, Eigen::VectorXd start,
                            const std::vector<double>& path_lengths, bool last_resort) {
    Chart_report trial_chart;
    Cut_mesh trial_cut;
    std::vector<Uv> trial_uv;
    const Status status = cut_and_solve<Metric, Solver>(
      index, is_singular, angles, expected_curvature, {}, std::move(start), last_resort ? options : trial_options,
      report, before, trial_chart, trial_cut, trial_uv, energy, progress, path_lengths);
    if(!status.ok())
    {
      if(first_failure.ok())
        first_failure = status;
      return false;
    }
    const double log_area = mean_log_area_squared(index, trial_cut, trial_uv);
    const double score = folds(trial_chart) ? fewer_cones_distortion_factor * log_area : log_area;
    const bool promising = folds(trial_chart) && (maps_kept == 0 || log_area < kept_score);
    if(maps_kept == 0 || score < kept_score)
    {
      kept_score = score;
      ++maps_kept;
      chart = std::move(trial_chart);
      cut = std::move(trial_cut);
      uv = std::move(trial_uv);
    }
    return promising;
  };
  // The 3D cut, then where it folds and the linearized step `step` is known the flat
  // metric's. Returns whether the map kept is these angles', without a fold.
  const auto consider_both_cuts = [&](const std::vector<double>& angles, const Eigen::VectorXd& step,
                                      bool last_resort) {
    const int maps_before = maps_kept;
    if(consider(angles, step, {}, last_resort) && step.size() == index.number_of_vertices())
      consider(angles, step, flat_path_lengths(index, step), last_resort);
    return maps_kept > maps_before && !folds(chart);
  };
  if(options.cones.angles == Cone_angles::Least_log_area)
  {
    consider_both_cuts(trial.prescribed, trial.first_step, true);
    if(maps_kept == 0)
      consider_both_cuts(prescribed, first_step, true);
    return maps_kept > 0 ? Status::success() : first_failure;
  }
  consider_both_cuts(prescribed, first_step, true);
  for(const double t : {1.0, 0.5})
  {
    const Cone_angle_trial angles = t == 1 ? trial : part_way(trial, expected_curvature, first_step, t);
    if(consider_both_cuts(angles.prescribed, angles.first_step, maps_kept == 0))
      break; // kept, unfolded: a smaller step towards the trial's angles would measure worse
  }
  return maps_kept > 0 ? Status::success() : first_failure;
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_CONE_ANGLE_TRIALS_H
