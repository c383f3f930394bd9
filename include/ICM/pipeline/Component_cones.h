// The cones stage of one connected component (`Surface_component.h`): whether a surface with
// a border wants cones at all, where the greedy placement starts, and the automatic cones
// placed in the class the optimum is computed in; with the progress a component reports.

#ifndef ICM_PIPELINE_COMPONENT_CONES_H
#define ICM_PIPELINE_COMPONENT_CONES_H

#include <ICM/Status.h>
#include <ICM/Options.h>
#include <ICM/cones/Exact_cone_sweeps.h>
#include <ICM/cones/Singular_vertices.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/pipeline/Chart_solver.h>
#include <ICM/internal/Mesh_index.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ICM {
namespace internal {

/// The share of a component's progress that its cones stage reports (the cut starts there).
constexpr double cones_stage_share = 0.35;

/// The progress of one component: `start` of the whole done before it, `span` its share.
struct Stage_progress
{
  const std::function<void(const std::string&, double)>* callback = nullptr;
  double start = 0, span = 1;
  void operator()(const char* stage, double within) const
  {
    if(callback != nullptr && *callback)
      (*callback)(stage, start + span * within);
  }
};

/// Whether a surface with a border wants interior cones: when its free-boundary optimum is
/// extreme, judged in the class the optimum will be computed in (the circle packing's optimum
/// is milder than the mesh's own class on the same mesh). `linearized` (null: none), the
/// linearized problem with the same singular set, gives Newton its first step and its
/// factorization at u0; `log_scale` receives the optimum's u - u0 (empty when it failed),
/// whose chart is this problem when no cone is placed.
template <class Metric, class Solver, class Linearized>
bool border_wants_cones(const Mesh_index& index, const Metric& metric, const Circle_packing_metric& packing,
                        const std::vector<char>& is_singular, const Surface_parameterization_options& options,
                        const Linearized* linearized, Eigen::VectorXd& log_scale)
{
  Eigen::VectorXd u = metric.u0;
  Inverse_curvature_map<Solver, Metric> newton(index, metric, free_vertices_off(is_singular));
  Eigen::VectorXd first_step;
  if(linearized != nullptr)
  {
    first_step = linearized->solve();
    newton.borrow_factorization(linearized->laplacian());
  }
  Newton_report free = newton.solve(Eigen::VectorXd::Zero(u.size()), u, options.newton, &first_step);
  log_scale.resize(0);
  double depth = 0;
  if(free.converged)
  {
    log_scale = u - metric.u0;
    depth = log_scale.cwiseAbs().maxCoeff();
  }
  else if(options.fall_back_to_circle_packing)
  {
    free = free_boundary_optimum<Solver>(index, packing, is_singular, u, options.newton);
    depth = (u - packing.u0).cwiseAbs().maxCoeff();
  }
  return !free.converged || depth > options.border_max_log_scale;
}

/// The cones greedy placement starts from: the user's, then, for the exact placement,
/// Algorithm 3's strongest minima as a closed surface needs them. Genus 0 needs two cones
/// (one would carry 4 pi) but starts from the `initial_cones` strongest minima, which spare
/// the first optimum its most extreme conformal factors; genus g > 1 starts with 2g - 2
/// negative cones at the maxima, so that no single cone carries all of 2 pi chi. The
/// linearized placement is solvable from any start and finds its first cone itself.
template <class Solver>
std::vector<int> cone_seeds(const Mesh_index& index, const Circle_packing_metric& packing,
                            const std::vector<char>& is_singular, const Surface_parameterization_options& options)
{
  const int nv = index.number_of_vertices();
  const bool closed = index.number_of_boundary_loops() == 0;
  const int chi = index.euler_characteristic();
  std::vector<int> seeds;
  for(int v = 0; v < nv; ++v)
    if(is_singular[v] && !index.is_boundary_vertex[v])
      seeds.push_back(v);
  if(options.cones.placement == Cone_placement::Linearized)
    return seeds;
  const int needed = !closed ? 0 : chi > 0 ? std::max(2, options.initial_cones) : chi == 0 ? 1 : -chi;
  if(static_cast<int>(seeds.size()) >= needed)
    return seeds;
  std::string why;
  for(int v : curvature_minima<Solver>(index, packing, why, chi < 0))
    if(static_cast<int>(seeds.size()) < needed && !is_singular[v])
      seeds.push_back(v);
  const int minimum = chi > 0 ? 2 : 1;
  for(int v = 0; static_cast<int>(seeds.size()) < minimum && v < nv; ++v)
    if(std::find(seeds.begin(), seeds.end(), v) == seeds.end())
      seeds.push_back(v); // a surface with too few minima (a tiny closed mesh)
  return seeds;
}

/// The greedy placement's choice in the class of `Metric` on the linearized `problem` (built
/// with the singular set fixed; the default placement) or by `Cone_placement::Exact_optimum`.
template <class Solver, class Metric, class Problem>
Cone_selection greedy_cones_in(const Mesh_index& index, const Metric& metric, std::optional<Problem>& problem,
                               const std::vector<int>& seeds, const Cone_options& options)
{
  if(!problem)
    return greedy_cones<Solver>(index, metric, seeds, options);
  if(std::optional<Cone_selection> refused = refused_selection(options))
    return *refused;
  return linearized_greedy_cones(*problem, index, seeds, options);
}

/// The greedy's cones in `selection`, read from the linearized `problem`, moved by
/// `sweep_cones_on_the_exact_optimum` from its optimum, in `problem` as well, whose figures
/// `selection` then reads again. `Cone_options::exact_sweeps` on a closed surface at a named
/// count without user cones; any other is left as it is.
template <class Solver, class Metric, class Problem>
void sweep_on_the_exact_optimum(const Mesh_index& index, const Metric& metric, Problem& problem,
                                const Surface_parameterization_options& options, Cone_selection& selection)
{
  std::vector<char> is_singular(index.number_of_vertices(), 0);
  for(int v : selection.cones)
    is_singular[v] = 1;
  const std::vector<int> greedy = selection.cones;
  const Exact_sweep_report swept = sweep_cones_on_the_exact_optimum<Solver>(
    index, metric, is_singular, selection.cones, selection.log_scale, newton_of(options.cones.newton, options.newton));
  if(swept.moves_kept == 0)
    return;
  for(std::size_t i = 0; i < greedy.size(); ++i)
    if(selection.cones[i] != greedy[i])
    {
      problem.remove_cone(problem.position_of(greedy[i]));
      problem.add_cone(selection.cones[i]);
    }
  read_linearized_selection(problem, true, options.cones, selection);
}

/// Angles for the automatic cones other than the entropy's, to be tried on the exact map: per
/// vertex the curvature to prescribe (NaN: free), and their linearized metric's u - u0, the
/// chart's first Newton step. Empty: none.
struct Cone_angle_trial
{
  std::vector<double> prescribed;
  Eigen::VectorXd first_step;
  bool empty() const { return prescribed.empty(); }
};

/// Automatic cones, where the surface wants them: greedy placement from `cone_seeds`, in the
/// class the optimum is computed in (cones placed by the circle packing's conformal factor
/// serve the default metric worse: doc/benchmarks.md), then in the circle packing's.
/// `expected_curvature` receives, at each cone placed, the curvature the placement predicts
/// for it (NaN when it predicts none); `first_step` the chart's first Newton step from u0
/// (empty: none), the linearized optimum with the cones placed, or when a surface with a
/// border wants no cone its free-boundary optimum itself, where that Newton then ends.
/// `placed` receives the cones added, in the order the greedy placed them; `least_log_area`
/// the angles of the least linearized log^2 area where the options ask for them
/// (`Cone_angles`), empty elsewhere.
template <class Metric, class Solver>
Status place_automatic_cones(const Mesh_index& index, const Surface_parameterization_options& options,
                             std::vector<char>& is_singular, std::vector<double>& expected_curvature,
                             Eigen::VectorXd& first_step, std::vector<int>& placed, Cone_angle_trial& least_log_area,
                             const Stage_progress& progress = Stage_progress())
{
  const Circle_packing_metric packing(index);
  const Metric metric = make_metric<Metric>(index, {});
  const bool closed = index.number_of_boundary_loops() == 0;
  // One factorization at u0 serves the linearized placement and starts the free-boundary
  // Newton, whose first step it is.
  std::optional<Linearized_cone_problem<Solver, Metric>> problem;
  if(options.cones.placement == Cone_placement::Linearized)
    problem.emplace(index, metric, is_singular);
  // The greedy rounds (a solve of the whole mesh each) take the stage's time on a large mesh,
  // after the free-boundary Newton of a surface with a border, which takes about as long:
  // each reports its share of the stage, so that a progress line moves through it.
  const double rounds_start = closed ? 0.0 : 0.5;
  if(!closed)
  {
    const auto* linearized = problem && problem->ok() ? &*problem : nullptr;
    if(!border_wants_cones<Metric, Solver>(index, metric, packing, is_singular, options, linearized, first_step))
      return Status::success();
    progress("cones", cones_stage_share * rounds_start);
  }
  const std::vector<int> seeds = cone_seeds<Solver>(index, packing, is_singular, options);
  Cone_options cones = with_newton(options.cones, options.newton);
  double reported = rounds_start; // a fallback's rounds do not go back on what the first said
  cones.progress = [&](double done) {
    if(options.cones.progress)
      options.cones.progress(done);
    reported = std::max(reported, rounds_start + (1 - rounds_start) * done);
    progress("cones", cones_stage_share * reported);
  };
  Cone_selection selection = greedy_cones_in<Solver>(index, metric, problem, seeds, cones);
  if(selection.ok() && problem && closed && seeds.empty() && options.cones.exact_sweeps &&
     options.cones.max_log_scale == 0)
    sweep_on_the_exact_optimum<Solver>(index, metric, *problem, options, selection);
  if(!selection.ok() && options.fall_back_to_circle_packing)
    selection = greedy_cones<Solver>(index, packing, seeds, cones);
  if(!selection.ok())
    return Status::failure(CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, selection.message);
  for(std::size_t i = 0; i < selection.cones.size(); ++i)
  {
    const int v = selection.cones[i];
    if(!is_singular[v])
      placed.push_back(v);
    is_singular[v] = 1;
    if(i < selection.curvatures.size() && std::isnan(expected_curvature[v]))
      expected_curvature[v] = selection.curvatures[i];
  }
  if(!selection.least_log_area_curvatures.empty())
  {
    least_log_area.prescribed.assign(expected_curvature.size(), std::nan(""));
    for(std::size_t i = 0; i < selection.cones.size(); ++i)
      least_log_area.prescribed[selection.cones[i]] = selection.least_log_area_curvatures[i];
    least_log_area.first_step = std::move(selection.least_log_area_log_scale);
  }
  first_step = std::move(selection.log_scale);
  return Status::success();
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_COMPONENT_CONES_H
