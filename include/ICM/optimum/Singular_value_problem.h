// The singular-values optimizer's problem (Curvature_space_optimizer.h): the admissible
// metric of given values u_S (the Dirichlet problem K(u)_N = 0), the energy there and its
// reduced gradient dE/du_S = g_S - Delta_SN Delta_NN^{-1} g_N, the harmonic extension of a
// step of u_S, and the Gauss-Newton preconditioner.

#ifndef ICM_OPTIMUM_SINGULAR_VALUE_PROBLEM_H
#define ICM_OPTIMUM_SINGULAR_VALUE_PROBLEM_H

#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/optimum/Energies.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {

/// Whether a metric can freeze its triangulation (`Intrinsic_delaunay_metric`).
template <class Metric, class = void>
struct Can_freeze_triangulation : std::false_type
{};
template <class Metric>
struct Can_freeze_triangulation<Metric, std::void_t<decltype(std::declval<Metric&>().freeze_triangulation(true))>>
  : std::true_type
{};

inline void remove_mean(Eigen::VectorXd& x)
{
  if(x.size() > 0)
    x.array() -= x.mean();
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
/// (an LDL^T without pivoting exists in any order) and its pivots far from round-off (a much
/// stiffer penalty loses the direction to round-off).
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
                         const Energy& energy, const std::vector<int>& singular, Curvature_space_report& report,
                         const Eigen::VectorXd& target)
    : dirichlet_(dirichlet), index_(index), state_(index), energy_(energy), singular_(singular), report_(report),
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
  // Above this a chord step refactorizes: lower, the energies' runs factorize about twice as
  // often for as many steps (doc/energies.md).
  static constexpr double fresh_factorization_above = 1e-3; // max |k_N|, radians
  Energy_gradient partials_;
  Gauss_newton_preconditioner gauss_newton_;
  Eigen::VectorXd gradient_, reduced_;
  double value_ = 0;
  std::string message_;
};

} // namespace internal
} // namespace ICM

#endif // ICM_OPTIMUM_SINGULAR_VALUE_PROBLEM_H
