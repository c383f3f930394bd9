// The paper's Algorithm 4, the reference form of step 5 for any energy: projected gradient
// in curvature space. grad_k E = Delta(u)^{-1} grad_u E projected onto the admissible space
// (N components zeroed, the mean over S removed), k <- k - lambda grad_k E with a line search
// that keeps E decreasing (Barzilai-Borwein trial steps), u = K^{-1}(k) by Newton warm-started
// from the last u. Every step is a full inverse curvature map, so it is slow: it is kept,
// tested, to validate the fast `minimize_energy_on_singular_values`, which reaches the same
// optimum (optimum/Curvature_space_optimizer.h).

#ifndef ICM_REFERENCE_PROJECTED_GRADIENT_H
#define ICM_REFERENCE_PROJECTED_GRADIENT_H

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/optimum/Energies.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

/// grad_k E at u: the energy's own `gradient_k`, or Delta(u)^{-1} grad_u E with one vertex
/// pinned (the energies ignore the global scale, so grad_u E sums to zero and the pinned
/// equation holds). Defined up to a constant; returns false when Delta cannot be factorized.
template <class SparseSolver = Default_sparse_solver, class Metric, class Energy>
bool curvature_gradient(const internal::Mesh_index& index, const Metric& metric, const Energy& energy,
                        const Eigen::VectorXd& u, Eigen::VectorXd& h)
{
  Curvature_map<Metric> curvature(index, metric);
  Energy_state<Metric> state(index);
  state.update(curvature, u);
  if constexpr(has_curvature_gradient<Energy, Metric>)
  {
    energy.gradient_k(state, h);
    return true;
  }
  else
  {
    const Eigen::VectorXd g = energy_gradient(energy, state);
    std::vector<char> is_free(index.number_of_vertices(), 1);
    is_free[0] = 0;
    Dynamic_laplacian<SparseSolver> laplacian(curvature.mesh_index(), is_free);
    laplacian.assemble(state.weights());
    if(!laplacian.factorize())
      return false;
    Eigen::VectorXd b(laplacian.size());
    for(int i = 0; i < laplacian.size(); ++i)
      b[i] = g[laplacian.vertex(i)];
    const Eigen::VectorXd x = laplacian.solve(b);
    h = Eigen::VectorXd::Zero(index.number_of_vertices());
    for(int i = 0; i < laplacian.size(); ++i)
      h[laplacian.vertex(i)] = x[i];
    return h.allFinite();
  }
}

/// Theorem 3.2's figure at an optimum: the spread of the S components of grad_k E relative
/// to the spread of all of them (zero at an interior optimum).
inline double theorem_3_2_residual(const Eigen::VectorXd& h, const std::vector<char>& is_singular)
{
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for(int v = 0; v < h.size(); ++v)
    if(is_singular[v])
    {
      lo = std::min(lo, h[v]);
      hi = std::max(hi, h[v]);
    }
  const double spread = h.maxCoeff() - h.minCoeff();
  return spread > 0 ? (hi - lo) / spread : 0.0;
}

namespace internal {

/// The admissible curvature nearest K(u): flat off S, the Gauss-Bonnet defect spread over S.
template <class Metric>
Eigen::VectorXd nearest_admissible_curvature(const Mesh_index& index, Curvature_map<Metric>& curvature,
                                             const std::vector<char>& is_singular, const std::vector<int>& singular,
                                             const Eigen::VectorXd& u)
{
  Eigen::VectorXd k;
  curvature.evaluate(u, k);
  double defect = 2.0 * M_PI * index.euler_characteristic();
  for(int v : singular)
    defect -= k[v];
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(!is_singular[v])
      k[v] = 0;
  for(int v : singular)
    k[v] += defect / singular.size();
  return k;
}

/// grad_k E = Delta^{-1} grad_u E at the state (up to a constant), or the energy's own.
template <class Energy, class Metric, class SparseSolver>
bool curvature_gradient(const Energy& energy, const Energy_state<Metric>& state,
                        Dynamic_laplacian<SparseSolver>& laplacian, Eigen::VectorXd& g, Energy_gradient& partials,
                        int& factorizations, Eigen::VectorXd& h)
{
  if constexpr(has_curvature_gradient<Energy, Metric>)
  {
    energy.gradient_k(state, h);
    return true;
  }
  else
  {
    energy_gradient(energy, state, g, partials);
    Eigen::VectorXd y;
    if(!solve_on_free_vertices(laplacian, state, g, y, factorizations))
      return false;
    h = Eigen::VectorXd::Zero(state.mesh().number_of_vertices());
    for(int i = 0; i < laplacian.size(); ++i)
      h[laplacian.vertex(i)] = y[i];
    return true;
  }
}

/// A step k_S - lambda p with sufficient decrease of E, its metric and gradient measured by
/// `measure(k, u, value, h)`; false when none was found.
template <class Measure>
bool line_search_in_k(Measure& measure, const std::vector<int>& singular, const Eigen::VectorXd& k,
                      const Eigen::VectorXd& u, const Eigen::VectorXd& p, double value, bool has_value,
                      const Curvature_space_options& options, double& lambda, Eigen::VectorXd& k_trial,
                      Eigen::VectorXd& u_trial, double& value_trial, Eigen::VectorXd& h_trial)
{
  const double dphi0 = -p.squaredNorm();
  lambda = std::min(lambda, options.max_step / p.cwiseAbs().maxCoeff());
  for(int trial = 0; trial < options.max_line_search_steps; ++trial)
  {
    k_trial = k;
    for(std::size_t s = 0; s < singular.size(); ++s)
      k_trial[singular[s]] -= lambda * p[s];
    u_trial = u;
    if(!measure(k_trial, u_trial, value_trial, h_trial))
    {
      lambda *= 0.25;
      continue;
    }
    const double dphi = -h_trial.dot(Eigen::VectorXd(k - k_trial)) / lambda;
    if(sufficient_decrease(has_value, value, dphi0, value_trial, dphi, lambda, options.armijo))
      return true;
    lambda = backtrack(has_value, value, dphi0, value_trial, dphi, lambda);
  }
  return false;
}

} // namespace internal

/// The paper's Algorithm 4: projected gradient in curvature space for the singular set
/// `is_singular`, from the admissible curvature nearest K(u) (k_N = 0, the Gauss-Bonnet
/// defect spread over S); `u` (u0 when empty) receives the optimum, normalised so that
/// mean_S(u - u0) = 0. Stops when Theorem 3.2's residual is below `options.tolerance`.
template <class SparseSolver = Default_sparse_solver, class Metric, class Energy>
Curvature_space_report
minimize_energy_by_projected_gradient(const internal::Mesh_index& index, const Metric& metric,
                                      const std::vector<char>& is_singular, const Energy& energy, Eigen::VectorXd& u,
                                      const Curvature_space_options& options = Curvature_space_options())
{
  const auto start = internal::Clock::now();
  Curvature_space_report report;
  constexpr bool has_value = has_energy_value<Energy, Metric>;
  const int nv = index.number_of_vertices();
  const std::vector<int> singular = internal::singular_list(is_singular);
  report.message = internal::optimizer_refusal(options, index, metric, singular);
  if(!report.message.empty())
    return report;
  double value = 0;
  auto fail = [&](const std::string& why) {
    report.message = why;
    report.final_energy = value;
    report.seconds = internal::seconds_since(start);
    return report;
  };
  if(u.size() != nv)
    u = metric.u0;

  // Algorithm 1's solver: every vertex free but one (the constant is Delta's kernel).
  std::vector<char> is_free(nv, 1);
  is_free[singular.front()] = 0;
  Inverse_curvature_map<SparseSolver, Metric> icm(index, metric, is_free);
  Curvature_map<Metric>& curvature = icm.curvature_map();
  Energy_state<Metric> state(index);
  Energy_gradient partials;
  Eigen::VectorXd g;

  Eigen::VectorXd k = internal::nearest_admissible_curvature(index, curvature, is_singular, singular, u);

  // u = K^{-1}(k), then E and the projected grad_k E there.
  // The inner K^{-1} is solved to a thousandth of the outer tolerance: Theorem 3.2's figure
  // is a spread of grad_k E, which errors of k move. On nefertiti (circle packing, u-square)
  // an inner tolerance only a hundredth of the outer one made Algorithm 4 stall (a line search
  // without decrease, E equal to the optimum's to round-off, u still away from it); a
  // thousandth converges (doc/energies.md, Why Algorithm 4 is only the reference).
  Newton_options inner = newton_of(options.newton, Newton_options());
  inner.tolerance = std::min(inner.tolerance, 1e-3 * options.tolerance);
  auto measure = [&](const Eigen::VectorXd& target, Eigen::VectorXd& x, double& value, Eigen::VectorXd& h) {
    const Newton_report newton = icm.solve(target, x, inner);
    report.newton_iterations += newton.iterations;
    if(!newton.converged)
      return false;
    ++report.evaluations;
    if(!state.update(curvature, x))
      return false;
    value = energy_value(energy, state);
    return internal::curvature_gradient(energy, state, icm.laplacian(), g, partials, report.factorizations, h) &&
           h.allFinite();
  };
  auto projected = [&](const Eigen::VectorXd& h) {
    Eigen::VectorXd p(singular.size());
    for(std::size_t s = 0; s < singular.size(); ++s)
      p[s] = h[singular[s]];
    internal::remove_mean(p);
    return p;
  };

  Eigen::VectorXd h;
  if(!measure(k, u, value, h))
    return fail("the start could not be reached: u = K^{-1}(k) failed");
  report.initial_energy = value;
  report.energy_history.push_back(value);
  Eigen::VectorXd p = projected(h);
  double lambda = options.max_step / std::max(p.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  lambda = std::min(lambda, 0.1 / std::max(p.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min()));

  Eigen::VectorXd k_trial, u_trial, h_trial;
  for(;;)
  {
    report.final_residual = theorem_3_2_residual(h, is_singular);
    if(report.final_residual <= options.tolerance)
      break;
    if(report.iterations == options.max_iterations)
      return fail("not converged in " + std::to_string(options.max_iterations) + " iterations (Theorem 3.2 residual " +
                  std::to_string(report.final_residual) + ")");
    double value_trial = 0;
    if(!internal::line_search_in_k(measure, singular, k, u, p, value, has_value, options, lambda, k_trial, u_trial,
                                   value_trial, h_trial))
      return fail("the line search found no decrease (Theorem 3.2 residual " + std::to_string(report.final_residual) +
                  ")");
    // Barzilai-Borwein: the next trial step from the change of the projected gradient.
    const Eigen::VectorXd p_trial = projected(h_trial);
    const Eigen::VectorXd step = -lambda * p, change = p_trial - p;
    const double sy = step.dot(change);
    lambda = sy > 0 ? step.squaredNorm() / sy : 2.0 * lambda;
    k.swap(k_trial);
    u.swap(u_trial);
    h.swap(h_trial);
    p = p_trial;
    value = value_trial;
    ++report.iterations;
    report.energy_history.push_back(value);
  }
  internal::normalise_scale(singular, metric.u0, u);
  report.final_energy = value;
  report.converged = true;
  report.seconds = internal::seconds_since(start);
  return report;
}

} // namespace ICM

#endif // ICM_REFERENCE_PROJECTED_GRADIENT_H
