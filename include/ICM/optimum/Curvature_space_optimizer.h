// Step 5 for any energy: the point of the admissible curvature space {k_N = 0,
// sum_S k = 2 pi chi} (Def. 3.1) where an energy (Energies.h) is least.
//
// Two optimizers reach it.
// - `minimize_energy_on_singular_values` (the default, fast): the admissible space is
//   parameterized by the values u_S on the singular vertices. Each u_S gives exactly one
//   admissible metric, the solution of the Dirichlet problem K(u)_N = 0 with u_S fixed, which
//   Newton solves as `free_boundary_optimum` does. Differentiating K(u)_N = 0 gives
//   du_N = Delta_NN^{-1} W_NS du_S, so dE/du_S = g_S - Delta_SN Delta_NN^{-1} g_N with
//   g = grad_u E: one more solve with the factorization Newton holds. L-BFGS on u_S then
//   needs one or two warm-started Newton steps per iteration, started from the first-order
//   prediction of u_N (the same harmonic extension). The reduced gradient is the
//   Dirichlet-to-Neumann map Sigma = Delta_SS - Delta_SN Delta_NN^{-1} Delta_NS applied to
//   (grad_k E)_S, so it vanishes exactly when the S components of grad_k E are equal:
//   Theorem 3.2.
// - `minimize_energy_by_projected_gradient` (the paper's Algorithm 4, the reference, in
//   reference/Projected_gradient.h): in
//   curvature space, grad_k E = Delta(u)^{-1} grad_u E projected onto the admissible space
//   (N components zeroed, the mean over S removed), k <- k - lambda grad_k E with a line
//   search that keeps E decreasing (Barzilai-Borwein trial steps), u = K^{-1}(k) by Newton
//   warm-started from the last u. Every step is a full inverse curvature map, so it is slow;
//   it is kept to validate the fast one.
//
// Both return u normalised so that the mean of u_S - u0_S is zero (the global scale is not
// part of a parameterization and every energy ignores it). Numbers: doc/energies.md.

#ifndef ICM_OPTIMUM_CURVATURE_SPACE_OPTIMIZER_H
#define ICM_OPTIMUM_CURVATURE_SPACE_OPTIMIZER_H

#include <ICM/Options.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Lbfgs.h>
#include <ICM/optimum/Singular_value_problem.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>
#include <ICM/internal/Option_checks.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

namespace internal {

/// The singular vertices in index order, and what the optimizers check about them.
inline std::vector<int> singular_list(const std::vector<char>& is_singular)
{
  std::vector<int> list;
  for(int v = 0; v < static_cast<int>(is_singular.size()); ++v)
    if(is_singular[v])
      list.push_back(v);
  return list;
}

/// Why the optimizers cannot run on this singular set, or an empty string.
template <class Metric>
std::string singular_set_problem(const Mesh_index& index, const Metric& metric, const std::vector<int>& singular)
{
  if(singular.empty())
    return "the singular set is empty";
  if constexpr(Energy_state<Metric>::develops_faces)
  {
    // The development is exact where it is flat off S: every interior cone must lie on a
    // seam of the cut it is developed along.
    const std::vector<int> seam_degree = seam_degrees(index, development_seams(metric, index.number_of_edges()));
    for(int v : singular)
      if(!index.is_boundary_vertex[v] && seam_degree[v] == 0)
        return "interior cone " + std::to_string(v) +
               " is on no seam: a metric that flips its own triangulation measures the mesh's faces "
               "in its development, which must be cut through every cone (give the metric the seams "
               "as fixed edges, as ICM::parameterize does, or use a metric on the mesh's triangulation)";
  }
  return "";
}

/// Why an optimizer cannot run with these options on this singular set, or an empty string.
template <class Metric>
std::string optimizer_refusal(const Curvature_space_options& options, const Mesh_index& index, const Metric& metric,
                              const std::vector<int>& singular)
{
  const std::string why = check_options(options).message;
  return why.empty() ? singular_set_problem(index, metric, singular) : why;
}

/// The global scale the optimizers return: mean over S of u - u0 is zero.
inline void normalise_scale(const std::vector<int>& singular, const Eigen::VectorXd& u0, Eigen::VectorXd& u)
{
  double mean = 0;
  for(int v : singular)
    mean += u[v] - u0[v];
  u.array() -= mean / singular.size();
}

} // namespace internal

namespace internal {

/// The singular-values optimizer's run: L-BFGS on u_S with a line search whose trials solve
/// the Dirichlet problem, and the refreshes of a frozen triangulation
/// (`Curvature_space_options::frozen_steps`).
template <class SparseSolver, class Metric, class Energy>
class Singular_values_run
{
  using Problem = Singular_value_problem<SparseSolver, Metric, Energy>;
  static constexpr bool has_value = has_energy_value<Energy, Metric>;
  // A triangulation that keeps flipping where the optimizer would stop (a cocircular diamond
  // at the optimum) is accepted after this many refreshes.
  static constexpr int max_stopping_refreshes = 5;

public:
  Singular_values_run(Inverse_curvature_map<SparseSolver, Metric>& dirichlet, const Mesh_index& index,
                      const Metric& metric, const Energy& energy, const std::vector<char>& is_singular,
                      const std::vector<int>& singular, Eigen::VectorXd& u, const Curvature_space_options& options,
                      const Eigen::VectorXd& target, Curvature_space_report& report)
    : problem_(dirichlet, index, energy, singular, report, target), metric_(metric), is_singular_(is_singular),
      singular_(singular), u_(u), options_(options), newton_(newton_of(options.newton, Newton_options())),
      report_(report), start_(Clock::now()), freezing_(Problem::can_freeze && options.frozen_steps > 0),
      // Trials solved to less than the Newton tolerance: the result is solved again to it.
      inexact_trials_(options.trial_tolerance_factor > 0), memory_(options.memory)
  {}
  ~Singular_values_run() { problem_.freeze(false); }

  Curvature_space_report& run()
  {
    if(!problem_.solve_interior(u_, newton_))
      return fail("the Dirichlet problem at the start: " + problem_.message());
    if(!problem_.evaluate())
      return fail("at the start: " + problem_.message());
    report_.initial_energy = problem_.value();
    report_.energy_history.push_back(problem_.value());
    if(freezing_)
    {
      problem_.freeze(true); // the triangulation is Delaunay at the start
      frozen_ = true;
    }
    choose_preconditioner();
    const double initial_gradient = problem_.reduced_gradient().cwiseAbs().maxCoeff();
    for(;;)
    {
      if(frozen_ && steps_since_refresh_ >= options_.frozen_steps && !refresh_or_fail())
        return report_;
      const Eigen::VectorXd r = problem_.reduced_gradient();
      const double largest = r.cwiseAbs().maxCoeff();
      report_.final_residual = initial_gradient > 0 ? largest / initial_gradient : 0.0;
      if(should_stop(largest))
      {
        // Stop at the metric with flips: when a refresh flips edges, the test is taken again.
        if(frozen_ && steps_since_refresh_ > 0)
        {
          const long flips = refresh();
          if(flips < 0)
            return fail("the metric with flips: " + problem_.message());
          report_.energy_history.back() = problem_.value();
          if(flips > 0 && ++stopping_refreshes_ <= max_stopping_refreshes)
            continue;
        }
        if(inexact_trials_ && !(problem_.solve_interior(u_, newton_) && problem_.evaluate()))
          return fail("the metric where the optimizer stopped: " + problem_.message());
        break;
      }
      if(report_.iterations == options_.max_iterations)
        return fail("not converged in " + std::to_string(options_.max_iterations) +
                    " iterations (relative reduced gradient " + std::to_string(report_.final_residual) + ")");
      const Eigen::VectorXd d = descent_direction(r);
      if(line_search(d, r, largest))
        continue;
      if(frozen_ && steps_since_refresh_ > 0)
      {
        // Perhaps only the frozen triangulation is in the way: flip it and try again.
        const long flips = refresh();
        if(flips < 0)
          return fail("the metric with flips: " + problem_.message());
        report_.energy_history.back() = problem_.value();
        if(flips > 0)
          continue;
      }
      // Restore the last accepted metric in the solver's state before reporting.
      problem_.solve_interior(u_, newton_);
      problem_.evaluate();
      return fail("the line search found no decrease (relative reduced gradient " +
                  std::to_string(report_.final_residual) + ")");
    }
    normalise_scale(singular_, metric_.u0, u_);
    report_.final_energy = problem_.value();
    report_.converged = true;
    report_.seconds = seconds_since(start_);
    return report_;
  }

private:
  /// The metric with flips at u (the triangulation made Delaunay there), measured, then
  /// frozen again; the number of edges flipped, or -1 when that metric could not be solved.
  long refresh()
  {
    const long before = problem_.triangulation_version();
    problem_.freeze(false);
    const bool solved = problem_.solve_interior(u_, newton_) && problem_.evaluate();
    problem_.freeze(freezing_);
    frozen_ = freezing_;
    steps_since_refresh_ = 0;
    ++report_.refreshes;
    return solved ? problem_.triangulation_version() - before : -1;
  }

  bool refresh_or_fail()
  {
    if(refresh() < 0)
    {
      fail("the metric with flips: " + problem_.message());
      return false;
    }
    report_.energy_history.back() = problem_.value();
    return true;
  }

  Curvature_space_report& fail(const std::string& why)
  {
    // The result must be the metric with flips (refresh a frozen triangulation first), flat
    // to the Newton tolerance.
    if((frozen_ && steps_since_refresh_ > 0) || inexact_trials_)
    {
      frozen_ = false;
      problem_.freeze(false);
      problem_.solve_interior(u_, newton_);
      problem_.evaluate();
    }
    report_.message = why;
    report_.final_energy = problem_.value();
    report_.seconds = seconds_since(start_);
    return report_;
  }

  /// Converged, or at the start already optimal to rounding, or no longer decreasing.
  bool should_stop(double largest) const
  {
    const std::vector<double>& history = report_.energy_history;
    return report_.final_residual <= options_.tolerance ||
           largest <= 1e-13 * problem_.gradient_u().cwiseAbs().maxCoeff() ||
           (has_value && options_.energy_tolerance > 0 && report_.iterations >= options_.stall_window &&
            history[history.size() - 1 - options_.stall_window] - history.back() <=
              options_.energy_tolerance * std::abs(history.back()));
  }

  void choose_preconditioner()
  {
    preconditioner_ = options_.preconditioner;
    if(preconditioner_ == Lbfgs_preconditioner::Gauss_newton &&
       (!has_gauss_newton<Energy, Metric> || !problem_.build_gauss_newton_preconditioner(is_singular_)))
      preconditioner_ = Lbfgs_preconditioner::Identity;
  }

  Eigen::VectorXd apply_preconditioner(const Eigen::VectorXd& v) const
  {
    Eigen::VectorXd x =
      preconditioner_ == Lbfgs_preconditioner::Gauss_newton ? problem_.apply_gauss_newton_preconditioner(v) : v;
    remove_mean(x);
    return x;
  }

  /// L-BFGS's direction, or steepest descent when that does not descend.
  Eigen::VectorXd descent_direction(const Eigen::VectorXd& r)
  {
    auto apply_m = [this](const Eigen::VectorXd& v) { return apply_preconditioner(v); };
    Eigen::VectorXd d = memory_.direction(r, apply_m);
    remove_mean(d);
    if(!(d.dot(r) < 0))
    {
      memory_.clear();
      d = -apply_m(r);
    }
    return d;
  }

  /// A step along d (u_S + alpha d, its harmonic extension inside) with sufficient
  /// decrease, accepted into u and the L-BFGS memory; false when none was found.
  bool line_search(const Eigen::VectorXd& d, const Eigen::VectorXd& r, double largest)
  {
    const double dphi0 = d.dot(r);
    const double phi0 = problem_.value();
    const Eigen::VectorXd extension = problem_.harmonic_extension(d);
    // The first step has no curvature information to scale it: it moves u_S by a tenth.
    double alpha = memory_.empty() ? 0.1 / d.cwiseAbs().maxCoeff() : 1.0;
    alpha = std::min(alpha, options_.max_step / d.cwiseAbs().maxCoeff());
    Newton_options trial_newton = newton_;
    if(inexact_trials_)
      trial_newton.tolerance = std::max(newton_.tolerance, std::min(1e-4, options_.trial_tolerance_factor * largest));
    for(int trial = 0; trial < options_.max_line_search_steps; ++trial)
    {
      u_trial_ = u_ + alpha * extension;
      for(std::size_t s = 0; s < singular_.size(); ++s)
        u_trial_[singular_[s]] = u_[singular_[s]] + alpha * d[s];
      if(!problem_.solve_interior(u_trial_, trial_newton) || !problem_.evaluate())
      {
        alpha *= 0.25; // beyond the metric's valid region, or Newton could not get there
        continue;
      }
      const double phi = problem_.value(), dphi = problem_.reduced_gradient().dot(d);
      if(sufficient_decrease(has_value, phi0, dphi0, phi, dphi, alpha, options_.armijo))
      {
        memory_.push(alpha * d, problem_.reduced_gradient() - r);
        u_.swap(u_trial_);
        ++report_.iterations;
        ++steps_since_refresh_;
        report_.energy_history.push_back(problem_.value());
        return true;
      }
      alpha = backtrack(has_value, phi0, dphi0, phi, dphi, alpha);
    }
    return false;
  }

  Problem problem_;
  const Metric& metric_;
  const std::vector<char>& is_singular_;
  const std::vector<int>& singular_;
  Eigen::VectorXd& u_;
  const Curvature_space_options& options_;
  const Newton_options newton_;
  Curvature_space_report& report_;
  const Clock::time_point start_;
  const bool freezing_, inexact_trials_;
  bool frozen_ = false;
  int steps_since_refresh_ = 0, stopping_refreshes_ = 0;
  Lbfgs_preconditioner preconditioner_ = Lbfgs_preconditioner::Identity;
  Lbfgs_memory memory_;
  Eigen::VectorXd u_trial_;
};

} // namespace internal

/// The minimum of `energy` over the admissible metrics with singular set S = the fixed
/// vertices of `dirichlet` (built with F = N, as for `free_boundary_optimum`), by L-BFGS on
/// u_S. `u` is the start (its u_S; u_N is solved for, warm-started from the u_N given) and
/// receives the optimum, normalised so that mean_S(u - u0) = 0. Starting from the entropy
/// optimum (`free_boundary_optimum`) is natural: every energy is measured against it.
/// `target` is the curvature the free vertices keep (per vertex; empty: zero, flat), nonzero
/// at cones whose angle the user fixed.
///
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"
/// \tparam Metric a model of \ref ::Metric "Metric"
/// \tparam Energy a model of \ref ::Energy "Energy"
template <class SparseSolver, class Metric, class Energy>
Curvature_space_report minimize_energy_on_singular_values(
  Inverse_curvature_map<SparseSolver, Metric>& dirichlet, const internal::Mesh_index& index, const Metric& metric,
  const Energy& energy, Eigen::VectorXd& u, const Curvature_space_options& options = Curvature_space_options(),
  const Eigen::VectorXd& target = Eigen::VectorXd())
{
  Curvature_space_report report;
  const int nv = index.number_of_vertices();
  std::vector<char> is_singular(nv, 0);
  for(int v = 0; v < nv; ++v)
    is_singular[v] = dirichlet.laplacian().free_index(v) < 0;
  const std::vector<int> singular = internal::singular_list(is_singular);
  report.message = internal::optimizer_refusal(options, index, metric, singular);
  if(!report.message.empty())
    return report;
  if(u.size() != nv)
    u = metric.u0;
  internal::Singular_values_run<SparseSolver, Metric, Energy> run(dirichlet, index, metric, energy, is_singular,
                                                                  singular, u, options, target, report);
  return run.run();
}

/// Convenience form: builds the Dirichlet solver for `is_singular`, starts from the entropy
/// optimum (u_S = u0_S) when `u` is empty.
template <class SparseSolver = Default_sparse_solver, class Metric, class Energy>
Curvature_space_report
minimize_energy_on_singular_values(const internal::Mesh_index& index, const Metric& metric,
                                   const std::vector<char>& is_singular, const Energy& energy, Eigen::VectorXd& u,
                                   const Curvature_space_options& options = Curvature_space_options())
{
  Inverse_curvature_map<SparseSolver, Metric> dirichlet(index, metric, free_vertices_off(is_singular));
  return minimize_energy_on_singular_values(dirichlet, index, metric, energy, u, options);
}

} // namespace ICM

#endif // ICM_OPTIMUM_CURVATURE_SPACE_OPTIMIZER_H
