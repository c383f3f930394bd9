// Step 4: the singular (cone) vertex set S (paper Sec. III-C, Algorithm 3), on the surface as
// given (before any cut).
//
// Two ways to choose interior cones:
// - `curvature_minima` is Algorithm 3: spread the total curvature 2 pi chi uniformly over the
//   interior, solve u = K^{-1}(k), and rank the local minima of u - u0 (where the surface must
//   shrink most to become uniformly curved) deepest first;
// - `greedy_cones` (Ben-Chen, Gotsman, Bunin 2008; Springborn, Schroeder, Pinkall 2008) adds
//   cones where the current entropy optimum's |u - u0| is largest: each cone removes the
//   worst area distortion left. By default on the optimum linearized at u0, one cone per
//   round on one factorization (cones/Linearized_cones.h); with
//   `Cone_placement::Exact_optimum` on the exact optimum, re-solved by Newton warm-started
//   each round (a few far-apart cones per round once there are several), from Algorithm 3's
//   minima: its first optima of a closed surface with two cones need conformal factors of
//   e^30 that no exact metric can reach.

#ifndef ICM_CONES_SINGULAR_VERTICES_H
#define ICM_CONES_SINGULAR_VERTICES_H

#include <ICM/Options.h>
#include <ICM/cones/Linearized_cones.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Option_checks.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ICM {

/// Algorithm 3: interior vertices that are local minima of u - u0 for uniform interior
/// curvature (zero on the border), deepest first: where the surface is most positively
/// curved, the place for cones of positive curvature. With `maxima`, the local maxima,
/// highest first: the most negatively curved places, for the negative cones of genus > 1.
/// `message` is set when K^{-1} fails.
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
std::vector<int> curvature_minima(const internal::Mesh_index& index, const Metric& metric, std::string& message,
                                  bool maxima = false)
{
  const int nv = index.number_of_vertices();
  int interior = 0;
  for(int v = 0; v < nv; ++v)
    interior += !index.is_boundary_vertex[v];
  if(interior == 0)
    return {};
  Eigen::VectorXd k_target = Eigen::VectorXd::Zero(nv);
  for(int v = 0; v < nv; ++v)
    if(!index.is_boundary_vertex[v])
      k_target[v] = 2.0 * M_PI * index.euler_characteristic() / interior;
  Eigen::VectorXd u;
  const Newton_report report = inverse_curvature_map<SparseSolver>(index, metric, k_target, u);
  if(!report.converged)
  {
    message = "uniform curvature: " + report.message;
    return {};
  }
  const Eigen::VectorXd scale = maxima ? Eigen::VectorXd(metric.u0 - u) : Eigen::VectorXd(u - metric.u0);
  std::vector<char> is_minimum(nv, 0);
  for(int v = 0; v < nv; ++v)
    is_minimum[v] = !index.is_boundary_vertex[v];
  for(const auto& e : index.edges)
  {
    if(scale[e[0]] >= scale[e[1]])
      is_minimum[e[0]] = 0;
    if(scale[e[1]] >= scale[e[0]])
      is_minimum[e[1]] = 0;
  }
  std::vector<int> minima;
  for(int v = 0; v < nv; ++v)
    if(is_minimum[v])
      minima.push_back(v);
  std::sort(minima.begin(), minima.end(), [&](int a, int b) { return scale[a] < scale[b]; });
  return minima;
}

namespace internal {

/// `Cone_options::progress` of one greedy placement: the share done after each round, the
/// cones placed since `first_cones` of those up to `wanted_cones`, or the fall of the largest
/// |u - u0| from the first round's to the target in log (the distortion falls about
/// geometrically with the cones), whichever is further, never less than reported before.
class Greedy_progress
{
public:
  Greedy_progress(const Cone_options& options, int first_cones, int wanted_cones)
    : callback_(&options.progress), target_(options.max_log_scale), first_(first_cones), wanted_(wanted_cones)
  {}

  void round(int cones, double max_log_scale)
  {
    if(!*callback_)
      return;
    if(std::isnan(first_scale_))
      first_scale_ = max_log_scale;
    double done = wanted_ > first_ ? static_cast<double>(cones - first_) / (wanted_ - first_) : 0.0;
    if(target_ > 0 && first_scale_ > target_ && max_log_scale > 0)
      done = std::max(done, std::log(first_scale_ / max_log_scale) / std::log(first_scale_ / target_));
    report(done);
  }
  void finish() { report(1.0); }

private:
  void report(double done)
  {
    done_ = std::max(done_, std::clamp(done, 0.0, 1.0));
    if(*callback_)
      (*callback_)(done_);
  }

  const std::function<void(double)>* callback_;
  double target_;
  int first_, wanted_;
  double first_scale_ = std::nan(""), done_ = 0;
};

} // namespace internal

/// What `greedy_cones` chose and how the distortion fell.
struct Cone_selection
{
  std::vector<int> cones;            ///< interior cone vertices, in the order added
  std::vector<double> max_log_scale; ///< max_N |u - u0| before each cone and at the end
  /// The linearized placement's prediction of each cone's curvature 2 pi - angle, same order
  /// as `cones` (empty from the exact placement). A negative one is a cone of angle above
  /// 2 pi, which the cut should pass through rather than end at (`Cut_graph_options`).
  std::vector<double> curvatures;
  /// The linearized optimum's u - u0 per vertex with these cones (empty from the exact
  /// placement): the first step of the chart's Newton from u0, without its factorization.
  Eigen::VectorXd log_scale;
  /// The cones' curvatures (in the order of `cones`) whose linearized metric has the least
  /// log^2 area (`Cone_angles`), and that metric's u - u0 per vertex; empty when not asked
  /// for or out of the linearized placement's reach.
  std::vector<double> least_log_area_curvatures;
  Eigen::VectorXd least_log_area_log_scale;
  std::string message; ///< empty, or why a solve failed
  bool ok() const { return message.empty(); }
};

/// Whether the automatic cones try the least log area's angles (`Cone_angles`).
inline bool tries_least_log_area_angles(const Cone_options& options)
{
  return options.angles == Cone_angles::Least_log_area ||
         (options.angles == Cone_angles::Automatic && options.max_log_scale == 0);
}

/// The `count` non-singular vertices with the largest |u| among those where |u| is a local
/// maximum over the ring (the largest of all comes first), largest first.
inline std::vector<int> largest_peaks(const internal::Mesh_index& index, const Eigen::VectorXd& u,
                                      const std::vector<char>& is_singular, int count)
{
  const int nv = index.number_of_vertices();
  std::vector<char> is_peak(nv);
  for(int v = 0; v < nv; ++v)
    is_peak[v] = !is_singular[v];
  for(const auto& e : index.edges)
  {
    const double a = std::abs(u[e[0]]), b = std::abs(u[e[1]]);
    if(a < b || (a == b && e[0] < e[1]))
      is_peak[e[0]] = 0;
    else
      is_peak[e[1]] = 0;
  }
  std::vector<int> peaks;
  for(int v = 0; v < nv; ++v)
    if(is_peak[v])
      peaks.push_back(v);
  const auto larger = [&](int a, int b) { return std::abs(u[a]) > std::abs(u[b]); };
  const std::size_t kept = std::min<std::size_t>(std::max(count, 1), peaks.size());
  std::partial_sort(peaks.begin(), peaks.begin() + kept, peaks.end(), larger);
  peaks.resize(kept);
  return peaks;
}

/// sum_v a_v (u_v - mean)^2 / sum_v a_v, the mean weighted by a.
inline double area_weighted_variance(const Eigen::VectorXd& u, const std::vector<double>& area)
{
  double total = 0, mean = 0;
  for(int v = 0; v < u.size(); ++v)
  {
    total += area[v];
    mean += area[v] * u[v];
  }
  mean /= total;
  double spread = 0;
  for(int v = 0; v < u.size(); ++v)
    spread += area[v] * (u[v] - mean) * (u[v] - mean);
  return spread / total;
}

/// Improvement sweeps of the linearized placement: each automatic cone in turn is taken out
/// and put back where the linearized |u - u0| is then largest, which moves it when a later
/// cone took over its part (the first cones were placed before the others existed); up to
/// `sweeps` times over all, until none moves. The greedy's own rule, so every move keeps the
/// cone where the greedy would place it given all the others.
template <class Problem>
void move_cones_to_the_largest_scale(Problem& problem, const internal::Mesh_index& index, std::size_t fixed, int sweeps,
                                     std::vector<char>& is_singular, Cone_selection& selection)
{
  const int nv = index.number_of_vertices();
  for(int sweep = 0; sweep < sweeps; ++sweep)
  {
    bool moved = false;
    for(std::size_t i = fixed; i < selection.cones.size(); ++i)
    {
      const int old = selection.cones[i];
      // The problem numbers its cones in the order added: removing and adding puts this one
      // last there, so position i is looked up by vertex.
      problem.remove_cone(problem.position_of(old));
      is_singular[old] = 0;
      const Eigen::VectorXd u = problem.solve();
      int best = old;
      for(int v = 0; v < nv; ++v)
        if(!is_singular[v] && std::abs(u[v]) > std::abs(u[best]))
          best = v;
      is_singular[best] = 1;
      problem.add_cone(best);
      selection.cones[i] = best;
      moved = moved || best != old;
    }
    if(!moved)
      return;
  }
}

/// The linearized figures of the cones `selection.cones` (those of `problem`, the seeds
/// fixed in it from the start): their predicted curvatures (NaN for a seed), the optimum's
/// u - u0 and, where `options` ask for them and there are no seeds, the least log^2 area's
/// angles with their u - u0.
template <class Problem>
void read_linearized_selection(const Problem& problem, bool no_seeds, const Cone_options& options,
                               Cone_selection& selection)
{
  const Eigen::VectorXd k = problem.cone_curvatures();
  selection.curvatures.clear();
  for(int v : selection.cones)
    selection.curvatures.push_back(problem.position_of(v) < k.size() ? k[problem.position_of(v)] : std::nan(""));
  selection.log_scale = problem.solve();
  selection.least_log_area_curvatures.clear();
  selection.least_log_area_log_scale.resize(0);
  Eigen::VectorXd least;
  if(no_seeds && tries_least_log_area_angles(options) &&
     problem.least_log_area_curvatures(least, selection.least_log_area_log_scale))
    for(int v : selection.cones)
      selection.least_log_area_curvatures.push_back(
        problem.position_of(v) < least.size() ? least[problem.position_of(v)] : std::nan(""));
}

/// Greedy cone placement on the linearized optimum (cones/Linearized_cones.h): the singular
/// set starts as the border plus `seeds` (plus, on a closed surface without one, the extreme
/// of the linearized uniform-curvature metric); each round makes a cone of the non-singular
/// vertex with the largest linearized |u - u0|, or, with `ranked_candidates` > 1, of the one
/// among that many peaks of |u - u0| whose cone leaves the least area-weighted variance of the
/// linearized u (one more solve per candidate), until `max_log_scale` (unless 0) or
/// `max_cones`. `problem` was built with the border and `seeds` fixed, and no cone added.
template <class Problem>
Cone_selection linearized_greedy_cones(Problem& problem, const internal::Mesh_index& index,
                                       const std::vector<int>& seeds, const Cone_options& options = Cone_options())
{
  Cone_selection selection;
  std::vector<char> is_singular(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  for(int v : seeds)
    if(!is_singular[v])
    {
      is_singular[v] = 1;
      selection.cones.push_back(v);
    }
  const std::size_t user_cones = selection.cones.size();
  if(!problem.ok())
  {
    selection.message = problem.message();
    return selection;
  }
  const bool closed = index.number_of_boundary_loops() == 0;
  const int chi = index.euler_characteristic();
  // Whatever the limit: one cone of a closed genus-0 surface would carry 4 pi, so it needs
  // two; a closed surface of genus g > 1 needs 2g - 2, about -2 pi each (angle 4 pi), since
  // fewer cones of many turns each leave the exact optimum out of the metrics' reach (genus
  // 100 with 32 cones: test_surfaces, HighGenusSlabsMapWithoutFlipsOrOverlaps).
  const int least = !closed ? 0 : chi > 0 ? 2 : std::max(0, -chi);
  const int wanted = std::max(least, options.max_cones);
  const auto make_cone = [&](int v) {
    is_singular[v] = 1;
    selection.cones.push_back(v);
    problem.add_cone(v);
  };
  if(!problem.is_determined() && wanted > 0)
    make_cone(problem.uniform_curvature_extreme(chi < 0));
  const std::vector<double> area = problem.vertex_areas();
  internal::Greedy_progress progress(options, static_cast<int>(selection.cones.size()), wanted);
  for(;;)
  {
    const Eigen::VectorXd u = problem.solve();
    const std::vector<int> peaks = largest_peaks(index, u, is_singular, options.ranked_candidates);
    selection.max_log_scale.push_back(peaks.empty() ? 0.0 : std::abs(u[peaks[0]]));
    const bool small_enough = options.max_log_scale > 0 && selection.max_log_scale.back() <= options.max_log_scale &&
                              static_cast<int>(selection.cones.size()) >= least;
    if(peaks.empty() || static_cast<int>(selection.cones.size()) >= wanted || small_enough)
    {
      move_cones_to_the_largest_scale(problem, index, user_cones, options.sweeps, is_singular, selection);
      read_linearized_selection(problem, user_cones == 0, options, selection);
      progress.finish();
      return selection;
    }
    progress.round(static_cast<int>(selection.cones.size()), selection.max_log_scale.back());
    int best = peaks[0];
    double least_spread = HUGE_VAL;
    for(std::size_t i = 0; peaks.size() > 1 && i < peaks.size(); ++i)
    {
      const Eigen::VectorXd h = problem.unit_response(peaks[i]);
      const double spread = area_weighted_variance(u - (u[peaks[i]] / h[peaks[i]]) * h, area);
      if(spread < least_spread)
      {
        least_spread = spread;
        best = peaks[i];
      }
    }
    make_cone(best);
  }
}

/// The same on the linearized problem of `metric` with the border and `seeds` fixed.
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
Cone_selection linearized_greedy_cones(const internal::Mesh_index& index, const Metric& metric,
                                       const std::vector<int>& seeds, const Cone_options& options = Cone_options())
{
  std::vector<char> is_fixed(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  for(int v : seeds)
    is_fixed[v] = 1;
  internal::Linearized_cone_problem<SparseSolver, Metric> problem(index, metric, is_fixed);
  return linearized_greedy_cones(problem, index, seeds, options);
}

/// Greedy cone placement on the exact entropy optimum. The singular set starts as the border
/// plus `seeds`; each round solves the entropy optimum u_S = u0_S, K_N = 0 (warm-started) and
/// makes the non-singular vertex with the largest |u - u0| a cone, until `max_log_scale` or
/// `max_cones` is reached. A closed genus-0 surface needs two seeds (one cone would carry
/// curvature 4 pi); other surfaces need one when they have no border.
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
Cone_selection exact_greedy_cones(const internal::Mesh_index& index, const Metric& metric,
                                  const std::vector<int>& seeds, const Cone_options& options = Cone_options())
{
  const int nv = index.number_of_vertices();
  Cone_selection selection;
  std::vector<char> is_singular(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  for(int v : seeds)
    if(!is_singular[v])
    {
      is_singular[v] = 1;
      selection.cones.push_back(v);
    }
  const Newton_options newton = newton_of(options.newton, Newton_options());
  Eigen::VectorXd u = metric.u0;
  internal::Greedy_progress progress(options, static_cast<int>(selection.cones.size()), options.max_cones);
  for(;;)
  {
    Inverse_curvature_map<SparseSolver, Metric> solver(index, metric, free_vertices_off(is_singular));
    for(int v = 0; v < nv; ++v)
      if(is_singular[v])
        u[v] = metric.u0[v];
    const Newton_report report = solver.solve(Eigen::VectorXd::Zero(nv), u, newton);
    if(!report.converged)
    {
      selection.message =
        "entropy optimum with " + std::to_string(selection.cones.size()) + " cones: " + report.message;
      return selection;
    }
    // Candidates: non-singular vertices whose |u - u0| is a local maximum over their ring
    // (so that one round never puts two cones side by side), largest first.
    const Eigen::VectorXd scale = (u - metric.u0).cwiseAbs();
    std::vector<int> peaks = largest_peaks(index, scale, is_singular, nv);
    peaks.erase(std::find_if(peaks.begin(), peaks.end(), [&](int v) { return !(scale[v] > options.max_log_scale); }),
                peaks.end());
    double largest = 0;
    for(int v = 0; v < nv; ++v)
      if(!is_singular[v])
        largest = std::max(largest, scale[v]);
    selection.max_log_scale.push_back(largest);
    const int room = options.max_cones - static_cast<int>(selection.cones.size());
    if(peaks.empty() || room <= 0)
    {
      progress.finish();
      return selection;
    }
    progress.round(static_cast<int>(selection.cones.size()), largest);
    // Up to half as many new cones as there are, at least one: a cone changes the optimum
    // mostly near itself, so far-apart peaks of one round are nearly the peaks the next
    // rounds would find one by one, at a fraction of the rounds.
    const int batch =
      std::min({room, static_cast<int>(peaks.size()), std::max(1, static_cast<int>(selection.cones.size()) / 2)});
    for(int i = 0; i < batch; ++i)
    {
      is_singular[peaks[i]] = 1;
      selection.cones.push_back(peaks[i]);
    }
  }
}

/// A selection that placed nothing, naming the first field of `options` out of range; none
/// when every field is in range.
inline std::optional<Cone_selection> refused_selection(const Cone_options& options)
{
  const Status checked = check_options(options);
  if(checked.ok())
    return std::nullopt;
  Cone_selection refused;
  refused.message = checked.message;
  return refused;
}

/// Greedy cone placement by `options.placement` (see above).
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
Cone_selection greedy_cones(const internal::Mesh_index& index, const Metric& metric, const std::vector<int>& seeds,
                            const Cone_options& options = Cone_options())
{
  if(std::optional<Cone_selection> refused = refused_selection(options))
    return *refused;
  return options.placement == Cone_placement::Linearized
           ? linearized_greedy_cones<SparseSolver>(index, metric, seeds, options)
           : exact_greedy_cones<SparseSolver>(index, metric, seeds, options);
}

} // namespace ICM

#endif // ICM_CONES_SINGULAR_VERTICES_H
