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

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/optimum/Energies.h>
#include <ICM/internal/Mesh_index.h>
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

/// What L-BFGS on u_S takes as its initial inverse Hessian (times the usual scalar
/// s.y / y.My). Measured on the shared disks (doc/energies.md).
enum class Lbfgs_preconditioner
{
  /// The identity.
  Identity,
  /// The default: (Z^T H Z)^{-1}, H the energy's `gauss_newton` Hessian in u at the start and
  /// Z the harmonic extension, by one factorization of the KKT matrix
  /// [H + mu, Delta_N.^T; Delta_N., -delta] and one solve per application. For the angle
  /// energy on the horse: 14 steps instead of 31, to a lower E (doc/energies.md). The
  /// identity for an energy without `gauss_newton`: the area energies' Gauss-Newton
  /// Hessians at the start (their optimum lies far from it on the horse, and their faces in
  /// the development are not the metric's) took 178 (log area) and 133 (area) steps there
  /// instead of 59 and 64.
  Gauss_newton
};

/// Options of both optimizers.
struct Curvature_space_options
{
  /// Stop when the reduced gradient max_S |dE/du_S| (the singular-values optimizer) is below
  /// this times its value at the start, or (the projected gradient) when the S components
  /// of grad_k E differ by less than this times the spread of grad_k E (Theorem 3.2).
  double tolerance = 1e-6;
  /// Also stop (the singular-values optimizer, for an energy with a value) once E fell by
  /// less than this, relative, over the last `stall_window` steps. Where the metric flips its
  /// triangulation as it goes the energy is only C^1 and L-BFGS creeps: on the horse E is
  /// within 1.3% of its value after 500 steps by step 30 (doc/energies.md), and then falls
  /// by about 0.1% per 10 steps. 0 turns this off.
  double energy_tolerance = 1e-3;
  int stall_window = 10;
  int max_iterations = 500;
  /// Largest change of any u_S (or, for the projected gradient, of any k_S) in one step.
  double max_step = 5.0;
  /// Pairs kept by L-BFGS.
  int memory = 10;
  /// For a metric that flips its own triangulation (`Intrinsic_delaunay_metric`), the
  /// singular-values optimizer keeps the triangulation frozen for up to this many steps and
  /// then flips it to be Delaunay at the current metric (a *refresh*); 0 flips at every
  /// evaluation. Frozen, the metric is vertex scaling on a fixed triangulation: a smooth
  /// function of u, whose Laplacian keeps its pattern, symbolic analysis, factorization (for
  /// the refined solves) and development order from step to step. A refresh also happens
  /// when a frozen line search fails, and before the optimizer stops, so that the result is
  /// the metric with flips (flat off S on its Delaunay triangulation); when that refresh
  /// flipped edges the stopping test is taken again.
  int frozen_steps = 0;
  /// The singular-values optimizer solves the line search's trial metrics only to max |k_N|
  /// <= this times max_S |dE/du_S| at the step's start (at most 1e-4 rad, at least
  /// `newton.tolerance`), as an inexact Newton's forcing term: a trial need not be flat to
  /// round-off to be ranked, once its E is corrected to first order by the adjoint of the
  /// reduced gradient's solve (E - y . k_N). The metric where it stops (or fails) is solved
  /// to `newton.tolerance`. On the horse about half the chord steps (doc/energies.md). 0:
  /// every trial to `newton.tolerance`.
  double trial_tolerance_factor = 1.0;
  Lbfgs_preconditioner preconditioner = Lbfgs_preconditioner::Gauss_newton;
  /// Trial steps per line search before giving up.
  int max_line_search_steps = 30;
  /// Sufficient decrease of the line searches (Armijo).
  double armijo = 1e-4;
  /// The Dirichlet (or, for the projected gradient, the inverse curvature map) Newton.
  Newton_options newton;
};

/// Whether every field of `options` is in range (see `check_options(const Newton_options&)`).
inline Status check_options(const Curvature_space_options& options, const std::string& prefix = "energy.")
{
  return internal::Option_checks(prefix)
    .real("tolerance", options.tolerance, 0, true)
    .real("energy_tolerance", options.energy_tolerance, 0, true)
    .at_least("stall_window", options.stall_window, 1)
    .at_least("max_iterations", options.max_iterations, 0)
    .real("max_step", options.max_step, 0, false)
    .at_least("memory", options.memory, 1)
    .at_least("frozen_steps", options.frozen_steps, 0)
    .real("trial_tolerance_factor", options.trial_tolerance_factor, 0, true)
    .one_of("preconditioner", options.preconditioner, 2)
    .at_least("max_line_search_steps", options.max_line_search_steps, 1)
    .real("armijo", options.armijo, 0, false, 1, false)
    .nested(check_options(options.newton, prefix + "newton."))
    .status();
}

/// What an optimizer did.
struct Curvature_space_report
{
  bool converged = false;
  int iterations = 0;         ///< accepted steps
  int evaluations = 0;        ///< metrics measured (line search trials included)
  int newton_iterations = 0;  ///< Newton steps over all solves (each one factorization)
  int factorizations = 0;     ///< other factorizations (the gradient's solves)
  /// Times a frozen triangulation was flipped to be Delaunay at the current metric
  /// (`Curvature_space_options::frozen_steps`).
  int refreshes = 0;
  double initial_energy = 0, final_energy = 0;  ///< NaN for an energy without a value
  /// Final stopping figure: the relative reduced gradient, or Theorem 3.2's spread.
  double final_residual = 0;
  std::vector<double> energy_history;
  double seconds = 0;
  std::string message; ///< empty when converged, else why it stopped
};

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
    const std::vector<int> seam_degree =
      seam_degrees(index, development_seams(metric, index.number_of_edges()));
    for(int v : singular)
      if(!index.is_boundary_vertex[v] && seam_degree[v] == 0)
        return "interior cone " + std::to_string(v) +
               " is on no seam: a metric that flips its own triangulation measures the mesh's faces "
               "in its development, which must be cut through every cone (give the metric the seams "
               "as fixed edges, as ICM::parameterize does, or use a metric on the mesh's triangulation)";
  }
  return "";
}

/// Whether a metric can freeze its triangulation (`Intrinsic_delaunay_metric`).
template <class Metric, class = void>
struct Can_freeze_triangulation : std::false_type
{};
template <class Metric>
struct Can_freeze_triangulation<
  Metric, std::void_t<decltype(std::declval<Metric&>().freeze_triangulation(true))>> : std::true_type
{};

inline void remove_mean(Eigen::VectorXd& x)
{
  if(x.size() > 0)
    x.array() -= x.mean();
}

/// The global scale the optimizers return: mean over S of u - u0 is zero.
inline void normalise_scale(const std::vector<int>& singular, const Eigen::VectorXd& u0, Eigen::VectorXd& u)
{
  double mean = 0;
  for(int v : singular)
    mean += u[v] - u0[v];
  u.array() -= mean / singular.size();
}

/// Limited-memory BFGS: the pairs (s, y) of the last steps and the two-loop recursion.
class Lbfgs_memory
{
public:
  explicit Lbfgs_memory(int size) : size_(size) {}

  void clear() { pairs_.clear(); }
  bool empty() const { return pairs_.empty(); }

  /// Keeps the pair when it has positive curvature (else the update would not be positive
  /// definite).
  void push(const Eigen::VectorXd& s, const Eigen::VectorXd& y)
  {
    const double sy = s.dot(y);
    if(!(sy > 1e-12 * s.norm() * y.norm()))
      return;
    if(static_cast<int>(pairs_.size()) == size_)
      pairs_.pop_front();
    pairs_.push_back({s, y, 1.0 / sy});
  }

  /// -H g, with H0 = gamma M, M applied by `apply_m`, gamma = s.y / y.M y of the last pair.
  template <class ApplyM>
  Eigen::VectorXd direction(const Eigen::VectorXd& g, ApplyM apply_m) const
  {
    Eigen::VectorXd q = g;
    std::vector<double> alpha(pairs_.size());
    for(int i = static_cast<int>(pairs_.size()) - 1; i >= 0; --i)
    {
      alpha[i] = pairs_[i].rho * pairs_[i].s.dot(q);
      q -= alpha[i] * pairs_[i].y;
    }
    Eigen::VectorXd r = apply_m(q);
    if(!pairs_.empty())
    {
      const Pair& last = pairs_.back();
      const double yMy = last.y.dot(apply_m(last.y));
      if(yMy > 0)
        r *= last.s.dot(last.y) / yMy;
    }
    for(std::size_t i = 0; i < pairs_.size(); ++i)
    {
      const double beta = pairs_[i].rho * pairs_[i].y.dot(r);
      r += (alpha[i] - beta) * pairs_[i].s;
    }
    return -r;
  }

private:
  struct Pair
  {
    Eigen::VectorXd s, y;
    double rho;
  };
  int size_;
  std::deque<Pair> pairs_;
};

/// Sufficient decrease along a line phi(alpha) with phi'(0) < 0. With values: Armijo, or,
/// once the change of E is lost in its rounding, its form for a quadratic model,
/// phi'(alpha) <= (1 - 2 c) |phi'(0)| (Hager and Zhang's approximate Wolfe condition).
/// Without values (an energy convex in k) only the derivative test.
inline bool sufficient_decrease(bool has_value, double phi0, double dphi0, double phi, double dphi,
                                double alpha, double c)
{
  const bool derivative_test = dphi <= (1.0 - 2.0 * c) * -dphi0;
  if(!has_value)
    return derivative_test;
  if(!std::isfinite(phi))
    return false;
  if(phi <= phi0 + c * alpha * dphi0)
    return true;
  return derivative_test && phi <= phi0 + 1e-12 * std::abs(phi0);
}

/// The next trial of a backtracking line search: the minimum of the cubic through phi(0),
/// phi'(0), phi(alpha), phi'(alpha) (or of the secant of phi' without values), kept in
/// [0.1, 0.5] alpha.
inline double backtrack(bool has_value, double phi0, double dphi0, double phi, double dphi, double alpha)
{
  double next = 0.5 * alpha;
  if(has_value && std::isfinite(phi) && std::isfinite(dphi))
  {
    const double d1 = dphi0 + dphi - 3.0 * (phi0 - phi) / (0.0 - alpha);
    const double root = d1 * d1 - dphi0 * dphi;
    if(root >= 0)
    {
      const double d2 = std::sqrt(root);
      next = alpha - alpha * (dphi + d2 - d1) / (dphi - dphi0 + 2.0 * d2);
    }
  }
  else if(std::isfinite(dphi) && dphi > dphi0)
    next = alpha * -dphi0 / (dphi - dphi0);
  if(!std::isfinite(next))
    next = 0.5 * alpha;
  return std::clamp(next, 0.1 * alpha, 0.5 * alpha);
}

/// Solves Delta_FF x = b with the Laplacian as assembled now: the last factorization
/// preconditions an iterative refinement when it is of a nearby metric, else the matrix is
/// factorized. Returns false when it cannot be factorized.
template <class SparseSolver>
bool solve_with_current_weights(Dynamic_laplacian<SparseSolver>& laplacian, const Eigen::VectorXd& b,
                                Eigen::VectorXd& x, int& factorizations)
{
  if(laplacian.has_factorization() && laplacian.solve_refined(b, x))
    return true;
  ++factorizations;
  if(!laplacian.factorize())
    return false;
  x = laplacian.solve(b);
  return x.allFinite();
}

/// y = Delta_FF^{-1} g_F for the Laplacian assembled from the weights of `state`, y per free
/// unknown: the solve with which both optimizers turn grad_u E into a gradient they use.
template <class SparseSolver, class Metric>
bool solve_on_free_vertices(Dynamic_laplacian<SparseSolver>& laplacian, const Energy_state<Metric>& state,
                            const Eigen::VectorXd& g, Eigen::VectorXd& y, int& factorizations)
{
  laplacian.assemble(state.weights());
  Eigen::VectorXd b(laplacian.size());
  for(int i = 0; i < laplacian.size(); ++i)
    b[i] = g[laplacian.vertex(i)];
  return solve_with_current_weights(laplacian, b, y, factorizations);
}

/// The rows of Delta_N. (the free vertices', numbered by `free_of`, -1 off N) as entries
/// (row_offset + free_of[a], vertex) of a matrix over all vertices, from the edges of `t`
/// with Jacobian weights `w`.
inline void add_free_laplacian_rows(const Mesh_index& t, const std::vector<double>& w, const std::vector<int>& free_of,
                                    int row_offset, std::vector<Eigen::Triplet<double, int>>& entries)
{
  for(int e = 0; e < t.number_of_edges(); ++e)
  {
    const int i = t.edges[e][0], j = t.edges[e][1];
    if(i == j)
      continue;
    for(const auto& [a, b] : {std::make_pair(i, j), std::make_pair(j, i)})
      if(free_of[a] >= 0)
      {
        entries.emplace_back(row_offset + free_of[a], a, w[e]);
        entries.emplace_back(row_offset + free_of[a], b, -w[e]);
      }
  }
}

/// The preconditioner (Z^T H Z)^{-1} of the reduced problem for a Hessian H in u (the
/// energy's Gauss-Newton one) and Z the harmonic extension: x = (Z^T H Z)^{-1} r minimises
/// (1/2) h^T H h - r . h_S over h with Delta_N. h = 0, whose KKT system
/// [H + mu, Delta_N.^T; Delta_N., -delta] [h; lambda] = [r on S; 0] is factorized once. mu (a
/// millionth of H's mean diagonal) fixes the global scale H ignores; delta turns the
/// constraint into a penalty 1e8 times stiffer than H, which keeps the matrix quasi-definite
/// (an LDL^T without pivoting exists in any order) and its pivots far from round-off (a
/// penalty 1e12 times stiffer lost the direction on the horse).
class Gauss_newton_preconditioner
{
public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// `hessian`: lower-triangle entries of H over the `nv` vertices; `t` and `w` the
  /// triangulation and Jacobian weights of Delta. Returns false when the KKT matrix cannot
  /// be factorized.
  bool build(std::vector<Eigen::Triplet<double, int>> hessian, int nv, const Mesh_index& t,
             const std::vector<double>& w, const std::vector<char>& is_singular)
  {
    std::vector<int> free_of(nv, -1);
    int n = 0;
    for(int v = 0; v < nv; ++v)
      if(!is_singular[v])
        free_of[v] = n++;
    double trace = 0;
    for(const Eigen::Triplet<double, int>& entry : hessian)
      if(entry.row() == entry.col())
        trace += entry.value();
    if(!(trace > 0))
      return false;
    const double mu = 1e-6 * trace / nv;
    for(int v = 0; v < nv; ++v)
      hessian.emplace_back(v, v, mu);
    // The rows of Delta_N. below H; delta from their mean squared norm (duplicates summed).
    const std::size_t first_row_entry = hessian.size();
    add_free_laplacian_rows(t, w, free_of, nv, hessian);
    double squares = 0;
    for(std::size_t i = first_row_entry; i < hessian.size(); ++i)
      squares += hessian[i].value() * hessian[i].value();
    const double delta = squares / std::max(n, 1) / (1e8 * trace / nv);
    if(!std::isfinite(delta))
      return false;
    for(int i = 0; i < n; ++i)
      hessian.emplace_back(nv + i, nv + i, -delta);
    size_ = nv + n;
    Matrix k(size_, size_);
    k.setFromTriplets(hessian.begin(), hessian.end());
    solver_.compute(k);
    return solver_.info() == Eigen::Success;
  }

  /// x for r given per singular vertex, in the order of `singular`.
  Eigen::VectorXd apply(const Eigen::VectorXd& r, const std::vector<int>& singular) const
  {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(size_);
    for(std::size_t s = 0; s < singular.size(); ++s)
      b[singular[s]] = r[s];
    const Eigen::VectorXd hl = solver_.solve(b);
    Eigen::VectorXd x(singular.size());
    for(std::size_t s = 0; s < singular.size(); ++s)
      x[s] = hl[singular[s]];
    return x;
  }

private:
  int size_ = 0;
  Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> solver_;
};

/// The reduced problem of the singular-values optimizer: E as a function of u_S through
/// the Dirichlet problem, its gradient, the harmonic extension and the Dirichlet-to-Neumann
/// map, all with the Dirichlet Newton's factorization.
template <class SparseSolver, class Metric, class Energy>
class Singular_value_problem
{
public:
  /// `target`: the curvature of the free vertices (zero, or a user cone's fixed angle
  /// defect), per vertex; empty for zero.
  Singular_value_problem(Inverse_curvature_map<SparseSolver, Metric>& dirichlet, const Mesh_index& index,
                         const Energy& energy, const std::vector<int>& singular,
                         Curvature_space_report& report, const Eigen::VectorXd& target)
    : dirichlet_(dirichlet), index_(index), state_(index), energy_(energy), singular_(singular),
      report_(report),
      target_(target.size() == index.number_of_vertices() ? target : Eigen::VectorXd::Zero(index.number_of_vertices()))
  {}

  /// Moves u_N until K(u)_N = 0 for the u_S of `u`, from the u_N given, and leaves the
  /// state measured at the result. Started from the harmonic extension the residual is of
  /// second order in the step, so a few chord steps with the factorization at hand (an
  /// iterative refinement against the current Laplacian) reach the tolerance without a new
  /// factorization; Newton with its line search takes over when they do not.
  bool solve_interior(Eigen::VectorXd& u, const Newton_options& options)
  {
    // The chord steps need the metric's curvature and weights only: the mesh's faces (for
    // a metric with its own triangulation, a development whose order is found again after
    // every flip) are measured once, at the solution.
    double last = HUGE_VAL;
    for(int step = 0; step <= max_chord_steps; ++step)
    {
      if(!state_.update(dirichlet_.curvature_map(), u, false))
        break;
      Dynamic_laplacian<SparseSolver>& laplacian = dirichlet_.laplacian();
      Eigen::VectorXd residual(laplacian.size());
      for(int i = 0; i < laplacian.size(); ++i)
        residual[i] = target_[laplacian.vertex(i)] - state_.curvature()[laplacian.vertex(i)];
      const double largest = residual.size() ? residual.cwiseAbs().maxCoeff() : 0.0;
      if(largest <= options.tolerance)
      {
        if constexpr(reads_faces<Energy>)
          state_.measure_faces();
        return true;
      }
      if(step == max_chord_steps || !(largest < 0.5 * last))
        break;
      last = largest;
      laplacian.assemble(state_.weights());
      // Far from the solution a fresh factorization (a Newton step, quadratic) pays; near it
      // the one at hand contracts the residual by the small relative change of the weights.
      if(largest > fresh_factorization_above)
      {
        ++report_.factorizations;
        if(!laplacian.factorize())
          break;
      }
      Eigen::VectorXd du;
      if(!solve_with_current_weights(laplacian, residual, du, report_.factorizations))
        break;
      for(int i = 0; i < laplacian.size(); ++i)
        u[laplacian.vertex(i)] += du[i];
      ++report_.newton_iterations;
    }
    const Newton_report newton = dirichlet_.solve(target_, u, options);
    report_.newton_iterations += newton.iterations;
    message_ = newton.message;
    return newton.converged && state_.update(dirichlet_.curvature_map(), u, reads_faces<Energy>);
  }

  /// Measures E, grad_u E and the reduced gradient at the metric `solve_interior` reached.
  bool evaluate()
  {
    ++report_.evaluations;
    value_ = energy_value(energy_, state_);
    energy_gradient(energy_, state_, gradient_, partials_);
    Dynamic_laplacian<SparseSolver>& laplacian = dirichlet_.laplacian();
    // dE/du_S = g_S + W_SN Delta_NN^{-1} g_N.
    Eigen::VectorXd y;
    if(!solve_on_free_vertices(laplacian, state_, gradient_, y, report_.factorizations))
    {
      message_ = "the Laplacian of the interior could not be factorized";
      return false;
    }
    // A trial metric solved only to a tolerance (`trial_tolerance_factor`) is off the flat
    // one by du_N = Delta_NN^{-1} (target_N - k_N): E there is E - y . (k_N - target_N) to
    // first order, so that the line search ranks trials by the flat metrics' values, not by
    // their residuals.
    for(int i = 0; i < laplacian.size(); ++i)
      value_ -= y[i] * (state_.curvature()[laplacian.vertex(i)] - target_[laplacian.vertex(i)]);
    Eigen::VectorXd full = gradient_;
    add_coupling(laplacian, y, full);
    reduced_.resize(singular_.size());
    for(std::size_t s = 0; s < singular_.size(); ++s)
      reduced_[s] = full[singular_[s]];
    remove_mean(reduced_);
    return reduced_.allFinite() && gradient_.allFinite();
  }

  /// The Gauss-Newton preconditioner at the metric of the last `evaluate`.
  bool build_gauss_newton_preconditioner(const std::vector<char>& is_singular)
  {
    std::vector<Eigen::Triplet<double, int>> hessian;
    if constexpr(has_gauss_newton<Energy, Metric>)
      energy_.gauss_newton(state_, hessian);
    ++report_.factorizations;
    return gauss_newton_.build(std::move(hessian), index_.number_of_vertices(), state_.triangulation(),
                               state_.weights(), is_singular);
  }
  Eigen::VectorXd apply_gauss_newton_preconditioner(const Eigen::VectorXd& r) const
  {
    return gauss_newton_.apply(r, singular_);
  }

  static constexpr bool can_freeze = Can_freeze_triangulation<Metric>::value;
  /// Freezes (or thaws) the metric's triangulation, when it has one that flips.
  void freeze(bool frozen)
  {
    if constexpr(can_freeze)
      dirichlet_.curvature_map().metric().freeze_triangulation(frozen);
  }
  long triangulation_version() const { return dirichlet_.curvature_map().triangulation_version(); }

  double value() const { return value_; }
  const Eigen::VectorXd& gradient_u() const { return gradient_; }
  const Eigen::VectorXd& reduced_gradient() const { return reduced_; }
  const std::string& message() const { return message_; }

  /// du_N of the admissible metrics along du_S = d: Delta_NN^{-1} W_NS d (the harmonic
  /// extension of d), per vertex, zero on S.
  Eigen::VectorXd harmonic_extension(const Eigen::VectorXd& d)
  {
    Dynamic_laplacian<SparseSolver>& laplacian = dirichlet_.laplacian();
    Eigen::VectorXd on_s = Eigen::VectorXd::Zero(index_.number_of_vertices());
    for(std::size_t s = 0; s < singular_.size(); ++s)
      on_s[singular_[s]] = d[s];
    Eigen::VectorXd b = Eigen::VectorXd::Zero(laplacian.size());
    const Mesh_index& t = state_.triangulation();
    for(int e = 0; e < t.number_of_edges(); ++e)
    {
      const int i = t.edges[e][0], j = t.edges[e][1];
      const int fi = laplacian.free_index(i), fj = laplacian.free_index(j);
      if(fi >= 0 && fj < 0)
        b[fi] += state_.weights()[e] * on_s[j];
      else if(fj >= 0 && fi < 0)
        b[fj] += state_.weights()[e] * on_s[i];
    }
    Eigen::VectorXd x, result = Eigen::VectorXd::Zero(index_.number_of_vertices());
    if(!solve_with_current_weights(laplacian, b, x, report_.factorizations))
      return result;
    for(int i = 0; i < laplacian.size(); ++i)
      result[laplacian.vertex(i)] = x[i];
    return result;
  }

private:
  /// full_S += W_SN y for y given per free unknown.
  void add_coupling(const Dynamic_laplacian<SparseSolver>& laplacian, const Eigen::VectorXd& y,
                    Eigen::VectorXd& full) const
  {
    const Mesh_index& t = state_.triangulation();
    for(int e = 0; e < t.number_of_edges(); ++e)
    {
      const int i = t.edges[e][0], j = t.edges[e][1];
      const int fi = laplacian.free_index(i), fj = laplacian.free_index(j);
      if(fi < 0 && fj >= 0)
        full[i] += state_.weights()[e] * y[fj];
      else if(fj < 0 && fi >= 0)
        full[j] += state_.weights()[e] * y[fi];
    }
  }

  Inverse_curvature_map<SparseSolver, Metric>& dirichlet_;
  const Mesh_index& index_;
  Energy_state<Metric> state_;
  const Energy& energy_;
  const std::vector<int>& singular_;
  Curvature_space_report& report_;
  const Eigen::VectorXd target_;
  static constexpr int max_chord_steps = 6;
  // Measured on the horse's energies (doc/energies.md): 1e-6 factorized 158 times for
  // log area, 1e-3 86 times, in as many steps.
  static constexpr double fresh_factorization_above = 1e-3; // max |k_N|, radians
  Energy_gradient partials_;
  Gauss_newton_preconditioner gauss_newton_;
  Eigen::VectorXd gradient_, reduced_;
  double value_ = 0;
  std::string message_;
};

inline double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace internal

/// The minimum of `energy` over the admissible metrics with singular set S = the fixed
/// vertices of `dirichlet` (built with F = N, as for `free_boundary_optimum`), by L-BFGS on
/// u_S. `u` is the start (its u_S; u_N is solved for, warm-started from the u_N given) and
/// receives the optimum, normalised so that mean_S(u - u0) = 0. Starting from the entropy
/// optimum (`free_boundary_optimum`) is natural: every energy is measured against it.
/// `target` is the curvature the free vertices keep (per vertex; empty: zero, flat), nonzero
/// at cones whose angle the user fixed.
template <class SparseSolver, class Metric, class Energy>
Curvature_space_report minimize_energy_on_singular_values(
  Inverse_curvature_map<SparseSolver, Metric>& dirichlet, const internal::Mesh_index& index,
  const Metric& metric, const Energy& energy, Eigen::VectorXd& u,
  const Curvature_space_options& options = Curvature_space_options(),
  const Eigen::VectorXd& target = Eigen::VectorXd())
{
  const auto start = std::chrono::steady_clock::now();
  Curvature_space_report report;
  constexpr bool has_value = has_energy_value<Energy, Metric>;
  const int nv = index.number_of_vertices();
  std::vector<char> is_singular(nv, 0);
  {
    Dynamic_laplacian<SparseSolver>& laplacian = dirichlet.laplacian();
    for(int v = 0; v < nv; ++v)
      is_singular[v] = laplacian.free_index(v) < 0;
  }
  const std::vector<int> singular = internal::singular_list(is_singular);
  report.message = check_options(options).message;
  if(report.message.empty())
    report.message = internal::singular_set_problem(index, metric, singular);
  if(!report.message.empty())
    return report;
  if(u.size() != nv)
    u = metric.u0;

  using Problem = internal::Singular_value_problem<SparseSolver, Metric, Energy>;
  Problem problem(dirichlet, index, energy, singular, report, target);
  // Frozen between refreshes (see `Curvature_space_options::frozen_steps`); thawed on return.
  const bool freezing = Problem::can_freeze && options.frozen_steps > 0;
  struct Thaw
  {
    Problem& problem;
    ~Thaw() { problem.freeze(false); }
  } thaw{problem};
  bool frozen = false;
  int steps_since_refresh = 0;
  // The metric with flips at u (the triangulation made Delaunay there), measured, then frozen
  // again; the number of edges flipped, or -1 when that metric could not be solved for.
  auto refresh = [&]() -> long {
    const long before = problem.triangulation_version();
    problem.freeze(false);
    const bool solved = problem.solve_interior(u, options.newton) && problem.evaluate();
    problem.freeze(freezing);
    frozen = freezing;
    steps_since_refresh = 0;
    ++report.refreshes;
    return solved ? problem.triangulation_version() - before : -1;
  };
  // Trials solved to less than the Newton tolerance (`trial_tolerance_factor`): the result
  // is solved again to it.
  const bool inexact_trials = options.trial_tolerance_factor > 0;
  auto fail = [&](const std::string& why) {
    // The result must be the metric with flips (refresh a frozen triangulation first), flat
    // to the Newton tolerance.
    if((frozen && steps_since_refresh > 0) || inexact_trials)
    {
      frozen = false;
      problem.freeze(false);
      problem.solve_interior(u, options.newton);
      problem.evaluate();
    }
    report.message = why;
    report.final_energy = problem.value();
    report.seconds = internal::seconds_since(start);
    return report;
  };
  if(!problem.solve_interior(u, options.newton))
    return fail("the Dirichlet problem at the start: " + problem.message());
  if(!problem.evaluate())
    return fail("at the start: " + problem.message());
  report.initial_energy = problem.value();
  report.energy_history.push_back(problem.value());
  if(freezing)
  {
    problem.freeze(true); // the triangulation is Delaunay at the start
    frozen = true;
  }
  // A triangulation that keeps flipping where the optimizer would stop (a cocircular diamond
  // at the optimum) is accepted after this many refreshes.
  constexpr int max_stopping_refreshes = 5;
  int stopping_refreshes = 0;

  Lbfgs_preconditioner preconditioner = options.preconditioner;
  if(preconditioner == Lbfgs_preconditioner::Gauss_newton &&
     (!has_gauss_newton<Energy, Metric> || !problem.build_gauss_newton_preconditioner(is_singular)))
    preconditioner = Lbfgs_preconditioner::Identity;
  auto apply_m = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::VectorXd x =
      preconditioner == Lbfgs_preconditioner::Gauss_newton ? problem.apply_gauss_newton_preconditioner(v) : v;
    internal::remove_mean(x);
    return x;
  };

  internal::Lbfgs_memory memory(options.memory);
  Eigen::VectorXd u_trial;
  const double initial_gradient = problem.reduced_gradient().cwiseAbs().maxCoeff();
  for(;;)
  {
    if(frozen && steps_since_refresh >= options.frozen_steps)
    {
      if(refresh() < 0)
        return fail("the metric with flips: " + problem.message());
      report.energy_history.back() = problem.value();
    }
    const Eigen::VectorXd r = problem.reduced_gradient();
    const double largest = r.cwiseAbs().maxCoeff();
    report.final_residual = initial_gradient > 0 ? largest / initial_gradient : 0.0;
    // Converged, or at the start already optimal to rounding, or no longer decreasing.
    const std::vector<double>& history = report.energy_history;
    const bool stop =
      report.final_residual <= options.tolerance || largest <= 1e-13 * problem.gradient_u().cwiseAbs().maxCoeff() ||
      (has_value && options.energy_tolerance > 0 && report.iterations >= options.stall_window &&
       history[history.size() - 1 - options.stall_window] - history.back() <=
         options.energy_tolerance * std::abs(history.back()));
    if(stop)
    {
      // Stop at the metric with flips: when a refresh flips edges, the test is taken again.
      if(frozen && steps_since_refresh > 0)
      {
        const long flips = refresh();
        if(flips < 0)
          return fail("the metric with flips: " + problem.message());
        report.energy_history.back() = problem.value();
        if(flips > 0 && ++stopping_refreshes <= max_stopping_refreshes)
          continue;
      }
      if(inexact_trials && !(problem.solve_interior(u, options.newton) && problem.evaluate()))
        return fail("the metric where the optimizer stopped: " + problem.message());
      break;
    }
    if(report.iterations == options.max_iterations)
      return fail("not converged in " + std::to_string(options.max_iterations) +
                  " iterations (relative reduced gradient " + std::to_string(report.final_residual) + ")");

    Eigen::VectorXd d = memory.direction(r, apply_m);
    internal::remove_mean(d);
    if(!(d.dot(r) < 0))
    {
      memory.clear();
      d = -apply_m(r);
    }
    const double dphi0 = d.dot(r);
    const double phi0 = problem.value();
    const Eigen::VectorXd extension = problem.harmonic_extension(d);
    // The first step has no curvature information to scale it: it moves u_S by a tenth.
    double alpha = memory.empty() ? 0.1 / d.cwiseAbs().maxCoeff() : 1.0;
    alpha = std::min(alpha, options.max_step / d.cwiseAbs().maxCoeff());

    Newton_options trial_newton = options.newton;
    if(inexact_trials)
      trial_newton.tolerance =
        std::max(options.newton.tolerance, std::min(1e-4, options.trial_tolerance_factor * largest));
    bool accepted = false;
    for(int trial = 0; trial < options.max_line_search_steps; ++trial)
    {
      u_trial = u + alpha * extension;
      for(std::size_t s = 0; s < singular.size(); ++s)
        u_trial[singular[s]] = u[singular[s]] + alpha * d[s];
      if(!problem.solve_interior(u_trial, trial_newton) || !problem.evaluate())
      {
        alpha *= 0.25; // beyond the metric's valid region, or Newton could not get there
        continue;
      }
      const double phi = problem.value(), dphi = problem.reduced_gradient().dot(d);
      if(internal::sufficient_decrease(has_value, phi0, dphi0, phi, dphi, alpha, options.armijo))
      {
        accepted = true;
        break;
      }
      alpha = internal::backtrack(has_value, phi0, dphi0, phi, dphi, alpha);
    }
    if(!accepted && frozen && steps_since_refresh > 0)
    {
      // Perhaps only the frozen triangulation is in the way: flip it and try again.
      const long flips = refresh();
      if(flips < 0)
        return fail("the metric with flips: " + problem.message());
      report.energy_history.back() = problem.value();
      if(flips > 0)
        continue;
    }
    if(!accepted)
    {
      // Restore the last accepted metric in the solver's state before reporting.
      problem.solve_interior(u, options.newton);
      problem.evaluate();
      return fail("the line search found no decrease (relative reduced gradient " +
                  std::to_string(report.final_residual) + ")");
    }
    memory.push(alpha * d, problem.reduced_gradient() - r);
    u.swap(u_trial);
    ++report.iterations;
    ++steps_since_refresh;
    report.energy_history.push_back(problem.value());
  }
  internal::normalise_scale(singular, metric.u0, u);
  report.final_energy = problem.value();
  report.converged = true;
  report.seconds = internal::seconds_since(start);
  return report;
}

/// Convenience form: builds the Dirichlet solver for `is_singular`, starts from the entropy
/// optimum (u_S = u0_S) when `u` is empty.
template <class SparseSolver = Default_sparse_solver, class Metric, class Energy>
Curvature_space_report minimize_energy_on_singular_values(
  const internal::Mesh_index& index, const Metric& metric, const std::vector<char>& is_singular,
  const Energy& energy, Eigen::VectorXd& u, const Curvature_space_options& options = Curvature_space_options())
{
  std::vector<char> is_free(is_singular.size());
  for(std::size_t v = 0; v < is_singular.size(); ++v)
    is_free[v] = !is_singular[v];
  Inverse_curvature_map<SparseSolver, Metric> dirichlet(index, metric, is_free);
  return minimize_energy_on_singular_values(dirichlet, index, metric, energy, u, options);
}

} // namespace ICM

#endif // ICM_OPTIMUM_CURVATURE_SPACE_OPTIMIZER_H
