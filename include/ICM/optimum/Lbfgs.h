// L-BFGS's parts for the singular-values optimizer (Curvature_space_optimizer.h): the memory of
// the last steps with its two-loop recursion, and the line search's sufficient decrease and
// backtracking, for energies with a value and for those known only by their derivatives.

#ifndef ICM_OPTIMUM_LBFGS_H
#define ICM_OPTIMUM_LBFGS_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <deque>
#include <utility>

namespace ICM {
namespace internal {

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
inline bool sufficient_decrease(bool has_value, double phi0, double dphi0, double phi, double dphi, double alpha,
                                double c)
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

} // namespace internal
} // namespace ICM

#endif // ICM_OPTIMUM_LBFGS_H
