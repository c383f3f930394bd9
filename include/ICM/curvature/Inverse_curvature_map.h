// Step 3: the inverse curvature map u = K^{-1}(k) (paper Algorithm 1), by Newton's method on
// the dynamic Laplacian.
//
// The solver is stated for a free vertex set F: find u with K(u)_F = k_F while u stays fixed
// off F. This is the gradient system of the discrete Ricci energy (eq. 4) restricted to F,
// strictly convex as soon as one vertex is fixed, with Hessian Delta_FF. Algorithm 1 is the
// case "all vertices but one", the free-boundary optimum the case F = non-singular vertices.

#ifndef ICM_CURVATURE_INVERSE_CURVATURE_MAP_H
#define ICM_CURVATURE_INVERSE_CURVATURE_MAP_H

#include <ICM/Options.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Option_checks.h>
#include <ICM/internal/Stopwatch.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

struct Newton_report
{
  bool converged = false;
  int iterations = 0;
  /// max |k_target - k| over the free vertices, before the first step and after each step.
  std::vector<double> residual_history;
  std::vector<double> step_lengths;
  double seconds_curvature = 0, seconds_factorization = 0, seconds_solve = 0;
  /// Steps whose direction came from an earlier step's factorization, by conjugate gradients
  /// on the current Laplacian, rather than from a factorization of their own.
  int refined_steps = 0;
  /// Triangular solves of those conjugate gradients, the failed attempts' included.
  int preconditioned_solves = 0;
  /// Numeric factorizations of the Laplacian, the run's main cost on a large mesh.
  int factorizations = 0;
  /// The line search stalled because every shorter step still made some face invalid.
  bool left_valid_region = false;
  std::string message;

  double final_residual() const { return residual_history.empty() ? 0.0 : residual_history.back(); }
};

/// The free set F of a singular set S: every vertex off S.
inline std::vector<char> free_vertices_off(const std::vector<char>& is_singular)
{
  std::vector<char> is_free(is_singular.size());
  for(std::size_t v = 0; v < is_singular.size(); ++v)
    is_free[v] = !is_singular[v];
  return is_free;
}

/// Newton's method for K(u)_F = k_F with u fixed off F. The Laplacian pattern is analysed
/// once at construction and every step only refactorizes numerically.
///
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"
/// \tparam Metric a model of \ref ::Metric "Metric"
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
class Inverse_curvature_map
{
public:
  Inverse_curvature_map(const internal::Mesh_index& index, const Metric& metric, const std::vector<char>& is_free)
    : index_(index), curvature_(index, metric), laplacian_(curvature_.mesh_index(), is_free),
      pattern_version_(curvature_.triangulation_version())
  {}

  Curvature_map<Metric>& curvature_map() { return curvature_; }
  /// The Laplacian, its pattern that of the metric's triangulation at the last accepted u.
  Dynamic_laplacian<SparseSolver>& laplacian()
  {
    update_pattern();
    return laplacian_;
  }
  /// Lends Newton a factorization of a nearby Laplacian on the same unknowns (the linearized
  /// cone problem's, at u0), to precondition its directions until it has one of its own.
  /// `laplacian` must outlive the solves; one with other unknowns is ignored.
  void borrow_factorization(const Dynamic_laplacian<SparseSolver>& laplacian)
  {
    borrowed_ = laplacian.has_factorization() && laplacian_.numbers_unknowns_as(laplacian) ? &laplacian : nullptr;
  }

  /// Curvature and weights at the last accepted u.
  const Eigen::VectorXd& curvature() const { return k_; }
  const std::vector<double>& weights() const { return w_; }

  /// Moves `u` (free entries only) until K(u)_F = k_target_F. `first_step`, when given (per
  /// vertex, its free entries read), is tried as the first direction, line search included:
  /// the linearized solution, known from elsewhere (the cone placement), is Newton's first
  /// step and spares its factorization. When a short search does not accept it, Newton
  /// begins with its own step.
  Newton_report solve(const Eigen::VectorXd& k_target, Eigen::VectorXd& u,
                      const Newton_options& options = Newton_options(), const Eigen::VectorXd* first_step = nullptr)
  {
    Newton_report report;
    if(const Status checked = check_options(options); !checked.ok())
    {
      report.message = checked.message;
      return report;
    }
    const int n = laplacian_.size();
    Eigen::VectorXd residual(n), du(n);
    const internal::Clock::time_point t = internal::Clock::now();
    const int invalid_at_start = curvature_.evaluate(u, k_, &w_);
    free_residual(k_target, k_, residual);
    report.seconds_curvature += internal::seconds_since(t);
    if(invalid_at_start > 0)
    {
      report.message = std::to_string(invalid_at_start) + " faces are not triangles at the starting metric";
      return report;
    }
    report.residual_history.push_back(max_norm(residual));
    if(first_step != nullptr && first_step->size() == u.size() && report.residual_history.back() > options.tolerance)
      try_first_step(k_target, options, *first_step, u, residual, report);
    int blocked_steps = 0;
    while(report.residual_history.back() > options.tolerance)
    {
      if(report.iterations == options.max_iterations)
      {
        report.message = "Newton did not converge in " + std::to_string(options.max_iterations) +
                         " iterations (curvature error " + std::to_string(report.residual_history.back()) + ")";
        return report;
      }
      bool blocked = false;
      if(!newton_direction(k_target, options.tolerance, residual, du, report) ||
         !line_search(k_target, options, du, u, residual, blocked, report))
        return report;
      blocked_steps = blocked && report.step_lengths.back() < 1.0 / 32 ? blocked_steps + 1 : 0;
      if(blocked_steps == options.max_blocked_steps && report.residual_history.back() > options.tolerance)
      {
        report.left_valid_region = true;
        report.message = "Newton is blocked by faces that would stop being triangles (curvature error " +
                         std::to_string(report.residual_history.back()) + " after " +
                         std::to_string(report.iterations) + " steps): the target is outside the metric's valid region";
        return report;
      }
    }
    report.converged = true;
    return report;
  }

private:
  /// `step` (per vertex) as the first direction, with at most `first_step_halvings` halvings:
  /// a rejected guess costs a few curvature evaluations, not a factorization.
  void try_first_step(const Eigen::VectorXd& k_target, const Newton_options& options, const Eigen::VectorXd& step,
                      Eigen::VectorXd& u, Eigen::VectorXd& residual, Newton_report& report)
  {
    constexpr int first_step_halvings = 4;
    Eigen::VectorXd du(laplacian_.size());
    for(int i = 0; i < laplacian_.size(); ++i)
      du[i] = step[laplacian_.vertex(i)];
    if(!du.allFinite())
      return;
    Newton_options short_search = options;
    short_search.max_line_search_steps = std::min(options.max_line_search_steps, first_step_halvings);
    bool blocked = false;
    if(line_search(k_target, short_search, du, u, residual, blocked, report))
      return;
    report.message.clear(); // not Newton's failure: its own first step follows
    report.left_valid_region = false;
  }

  /// The Newton step du = Delta_FF^{-1} residual at the current metric, as accurate as a run
  /// to `tolerance` needs.
  bool newton_direction(const Eigen::VectorXd& k_target, double tolerance, Eigen::VectorXd& residual,
                        Eigen::VectorXd& du, Newton_report& report)
  {
    internal::Clock::time_point t = internal::Clock::now();
    if(update_pattern())
    {
      free_residual(k_target, k_, residual); // the unknowns were numbered again
      borrowed_ = nullptr;                   // in another order than the lender's
    }
    laplacian_.assemble(w_);
    if(direction_from_last_factorization(residual, tolerance, du, report))
    {
      ++report.refined_steps;
      report.seconds_solve += internal::seconds_since(t);
      return true;
    }
    if(!laplacian_.factorize())
    {
      report.message = "the dynamic Laplacian could not be factorized (not positive definite)";
      return false;
    }
    ++report.factorizations;
    report.seconds_factorization += internal::seconds_since(t);
    t = internal::Clock::now();
    du = laplacian_.solve(residual);
    report.seconds_solve += internal::seconds_since(t);
    if(!du.allFinite())
    {
      report.message = "the Newton step is not finite";
      return false;
    }
    return true;
  }

  /// Newton's direction needs only the accuracy of an inexact Newton method: solved to a
  /// relative residual eta = min(0.1, |residual|_max), the step's residual is eta times the
  /// one before plus Newton's own quadratic term, so convergence stays quadratic. Near the end
  /// eta need not be tighter than what lands the step `final_margin` below the tolerance: a
  /// cut chart's seams close to the metric's flatness, which full Newton steps took far below
  /// the tolerance, and conjugate gradients on a factorization a few steps old may not reach
  /// eta = 1e-9 in their budget. They reach the rest in a few triangular solves once the
  /// weights move by a few percent per step (lion-head Loop x3: 0.07 s a solve, 1.3 s a
  /// factorization). When `max_preconditioned_solves` do not, the step factorizes.
  bool direction_from_last_factorization(const Eigen::VectorXd& residual, double tolerance, Eigen::VectorXd& du,
                                         Newton_report& report) const
  {
    constexpr double max_forcing = 0.1, final_margin = 1e-3;
    constexpr int max_preconditioned_solves = 8;
    const bool own = laplacian_.has_factorization();
    if(!own && borrowed_ == nullptr)
      return false;
    int solves = 0;
    const double size = max_norm(residual);
    const double forcing = std::min(max_forcing, std::max(size, final_margin * tolerance / size));
    const bool solved = laplacian_.solve_preconditioned(residual, du, forcing, max_preconditioned_solves, solves,
                                                        own ? nullptr : borrowed_);
    report.preconditioned_solves += solves;
    return solved;
  }

  /// Line search on the Ricci energy E, convex along the line, whose derivative in the step
  /// direction is g(alpha) = -residual(alpha) . du. A step is accepted when the residual
  /// shrinks, or when g is still <= 0 (E decreased all the way): either way E went down,
  /// which is what guarantees convergence to the unique solution. A metric whose valid
  /// region is not all of u-space (vertex scaling, inversive distance) also steps back from
  /// any trial where a face stops being a triangle (`blocked`). The accepted step moves u,
  /// the curvature and the residual.
  bool line_search(const Eigen::VectorXd& k_target, const Newton_options& options, const Eigen::VectorXd& du,
                   Eigen::VectorXd& u, Eigen::VectorXd& residual, bool& blocked, Newton_report& report)
  {
    const internal::Clock::time_point t = internal::Clock::now();
    const int n = laplacian_.size();
    const double norm = residual.norm();
    const double largest = du.size() ? du.cwiseAbs().maxCoeff() : 0.0;
    double alpha = largest > options.max_step ? options.max_step / largest : 1.0;
    for(int halvings = 0;; ++halvings)
    {
      u_trial_ = u;
      for(int i = 0; i < n; ++i)
        u_trial_[laplacian_.vertex(i)] += alpha * du[i];
      const int invalid = curvature_.evaluate(u_trial_, k_trial_, &w_trial_);
      free_residual(k_target, k_trial_, trial_residual_);
      blocked = blocked || invalid > 0;
      const bool finite = invalid == 0 && trial_residual_.allFinite();
      if(finite && (trial_residual_.norm() < norm || trial_residual_.dot(du) >= 0.0))
        break;
      if(halvings == options.max_line_search_steps)
      {
        report.seconds_curvature += internal::seconds_since(t);
        report.left_valid_region = invalid > 0;
        report.message = "the Newton line search stalled (curvature error " +
                         std::to_string(report.residual_history.back()) + "): " +
                         (invalid > 0 ? "a face would stop being a triangle, the target is outside the metric's "
                                        "valid region"
                                      : "the target curvature may be outside the image of K");
        return false;
      }
      alpha *= 0.5;
    }
    report.seconds_curvature += internal::seconds_since(t);
    u.swap(u_trial_);
    k_.swap(k_trial_);
    w_.swap(w_trial_);
    residual.swap(trial_residual_);
    ++report.iterations;
    report.step_lengths.push_back(alpha);
    report.residual_history.push_back(max_norm(residual));
    return true;
  }
  /// A metric that flips its triangulation changes the Laplacian's pattern. Returns whether
  /// the unknowns were numbered again.
  bool update_pattern()
  {
    if(curvature_.triangulation_version() == pattern_version_)
      return false;
    pattern_version_ = curvature_.triangulation_version();
    return laplacian_.rebuild_pattern();
  }

  void free_residual(const Eigen::VectorXd& k_target, const Eigen::VectorXd& k, Eigen::VectorXd& residual) const
  {
    residual.resize(laplacian_.size());
    for(int i = 0; i < laplacian_.size(); ++i)
    {
      const int v = laplacian_.vertex(i);
      residual[i] = k_target[v] - k[v];
    }
  }

  static double max_norm(const Eigen::VectorXd& x) { return x.size() == 0 ? 0.0 : x.cwiseAbs().maxCoeff(); }

  const internal::Mesh_index& index_;
  Curvature_map<Metric> curvature_;
  Dynamic_laplacian<SparseSolver> laplacian_;
  long pattern_version_;
  Eigen::VectorXd k_, k_trial_, u_trial_, trial_residual_; // the last two: scratch of the line search
  std::vector<double> w_, w_trial_;
  const Dynamic_laplacian<SparseSolver>* borrowed_ = nullptr; // see borrow_factorization()
};

/// Algorithm 1: the metric of the conformal class whose curvature is `k_target` everywhere.
/// `k_target` must satisfy Gauss-Bonnet (sum = 2 pi chi). `u` starts at `metric.u0` when
/// empty; on return it is normalised so that sum(u - u0) = 0.
///
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"
/// \tparam Metric a model of \ref ::Metric "Metric"
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
Newton_report inverse_curvature_map(const internal::Mesh_index& index, const Metric& metric,
                                    const Eigen::VectorXd& k_target, Eigen::VectorXd& u,
                                    const Newton_options& options = Newton_options())
{
  Newton_report report;
  const int nv = index.number_of_vertices();
  if(k_target.size() != nv)
  {
    report.message = "the target curvature has " + std::to_string(k_target.size()) + " entries for " +
                     std::to_string(nv) + " vertices";
    return report;
  }
  const double defect = gauss_bonnet_defect(index, k_target);
  if(!meets_gauss_bonnet(defect, nv))
  {
    report.message =
      "the target curvature violates Gauss-Bonnet: its sum differs from 2 pi chi by " + std::to_string(defect);
    return report;
  }
  if(u.size() != nv)
    u = metric.u0;
  // The constant vector spans the kernel of Delta: pinning one vertex removes it, and the
  // pinned equation then holds by Gauss-Bonnet.
  std::vector<char> is_free(nv, 1);
  is_free[0] = 0;
  Inverse_curvature_map<SparseSolver, Metric> solver(index, metric, is_free);
  report = solver.solve(k_target, u, options);
  u.array() -= (u - metric.u0).mean();
  return report;
}

} // namespace ICM

#endif // ICM_CURVATURE_INVERSE_CURVATURE_MAP_H
