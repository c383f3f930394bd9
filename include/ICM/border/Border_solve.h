// The metric of a prescribed border: Algorithm 1 for given turning angles
// (`solve_prescribed_border`), and the circle condition's fixed point (`solve_circle_domain`).
//
// The circle condition, exact for any metric: a polygon with sides l_e is inscribed in a
// circle of radius R when each side subtends theta_e = 2 asin(l_e / 2R) at the centre and
// the angles close, sum_e theta_e = 2 pi. Its turning angle at the vertex between sides a
// and b is then (theta_a + theta_b) / 2, positive around the outer loop and negative around
// a hole. The targets depend on u through the lengths: `solve_circle_domain` iterates
// u <- K^{-1}(T(u)) with Anderson acceleration (doc/border_conditions.md).

#ifndef ICM_BORDER_BORDER_SOLVE_H
#define ICM_BORDER_BORDER_SOLVE_H

#include <ICM/border/Border_target.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/internal/Vector_geometry.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <string>
#include <vector>

namespace ICM {

namespace internal {

/// that subtends more than pi (the centre is beyond it), or -1.
struct Inscribed_circle
{
  double radius = 0;
  int long_side = -1;
  bool exists = false;
};

/// Sum of the angles the sides subtend at the centre of a circle of radius R, the side
/// `long_side` (if any) taken on the far arc.
inline double subtended_angle_sum(const std::vector<double>& lengths, double R, int long_side)
{
  double sum = 0;
  for(std::size_t e = 0; e < lengths.size(); ++e)
  {
    const double half = std::asin(std::min(1.0, lengths[e] / (2 * R)));
    sum += static_cast<int>(e) == long_side ? 2 * M_PI - 2 * half : 2 * half;
  }
  return sum;
}

/// Solves the closure sum_e theta_e(R) = 2 pi. With every side on its short arc the sum
/// falls with R from its value at R = l_max / 2; when even that is short of 2 pi, the longest
/// side is on its far arc (the centre lies outside the polygon, beyond that side), and the
/// root is where the other sides' angles equal the longest one's. A polygon exists (and the
/// root is unique) iff the longest side is shorter than the others together. Bisection in
/// log R: a root to the last bits in a few dozen evaluations whatever the branch.
inline Inscribed_circle inscribed_circle(const std::vector<double>& lengths)
{
  Inscribed_circle c;
  if(lengths.size() < 3)
    return c;
  const auto longest = std::max_element(lengths.begin(), lengths.end());
  double others = 0;
  for(double l : lengths)
    others += l;
  others -= *longest;
  if(!(*longest < others))
    return c;
  double low = *longest / 2;
  c.long_side = subtended_angle_sum(lengths, low, -1) >= 2 * M_PI ? -1 : static_cast<int>(longest - lengths.begin());
  // On the short branch the sum falls below 2 pi by R = sum l / 4 (asin x <= pi x / 2); on
  // the far branch it rises to 2 pi, crossing where the other sides balance the long one.
  double high = (others + *longest) / 4;
  while(c.long_side >= 0 && subtended_angle_sum(lengths, high, c.long_side) < 2 * M_PI && high < 1e300)
    high *= 2;
  const double sign = c.long_side < 0 ? 1.0 : -1.0; // sum - 2 pi has this sign below the root
  for(int i = 0; i < 200 && high - low > 4e-16 * high; ++i)
  {
    const double mid = std::sqrt(low * high);
    if(sign * (subtended_angle_sum(lengths, mid, c.long_side) - 2 * M_PI) > 0)
      low = mid;
    else
      high = mid;
  }
  c.radius = std::sqrt(low * high);
  c.exists = std::isfinite(c.radius);
  return c;
}

/// The circle-domain targets at the metric of `u`: per loop, the circle through its
/// polygon of metric lengths, and each vertex's turning angle on it (outer loop +, holes -).
/// Interior vertices 0. Returns false (with `why`) when a loop has no circumscribed circle.
template <class Metric>
bool circle_domain_targets(const Mesh_index& index, const Metric& metric, const Eigen::VectorXd& u, int outer_loop,
                           Eigen::VectorXd& target, std::vector<double>& lengths, std::vector<double>& radii,
                           std::string& why)
{
  target.setZero(index.number_of_vertices());
  radii.resize(index.number_of_boundary_loops());
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
  {
    const std::vector<int>& loop = index.boundary_loops[l];
    const std::vector<int>& loop_edges = index.boundary_loop_edges[l];
    const std::size_t n = loop.size();
    lengths.resize(n);
    // Border edges never flip, so their ids and lengths are the mesh's in every metric.
    for(std::size_t i = 0; i < n; ++i)
      lengths[i] = metric.length(loop_edges[i], std::exp(u[loop[i]]), std::exp(u[loop[(i + 1) % n]]));
    const Inscribed_circle circle = inscribed_circle(lengths);
    if(!circle.exists)
    {
      why = "border loop " + std::to_string(l) + " (" + std::to_string(n) +
            " edges) has no circumscribed circle: one edge is longer than all others together";
      return false;
    }
    radii[l] = circle.radius;
    const double sign = l == outer_loop ? 1.0 : -1.0;
    auto theta = [&](std::size_t e) {
      const double half = std::asin(std::min(1.0, lengths[e] / (2 * circle.radius)));
      return static_cast<int>(e) == circle.long_side ? 2 * M_PI - 2 * half : 2 * half;
    };
    // Vertex loop[i] lies between side i-1 (from loop[i-1]) and side i (to loop[i+1]).
    for(std::size_t i = 0; i < n; ++i)
      target[loop[i]] = sign * 0.5 * (theta((i + n - 1) % n) + theta(i));
  }
  return true;
}

/// Anderson acceleration (type II) of a fixed-point map x -> g(x): from the last `depth`
/// residuals f = g(x) - x, the combination of the g's whose residual is least in the
/// least-squares sense. Plain x <- g(x) when the history is empty.
class Anderson_mixing
{
public:
  explicit Anderson_mixing(int depth) : depth_(depth) {}

  void reset()
  {
    x_.clear();
    f_.clear();
  }

  /// The next iterate from the current x and g(x).
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& gx)
  {
    Eigen::VectorXd f = gx - x;
    x_.push_back(x);
    f_.push_back(f);
    if(static_cast<int>(x_.size()) > depth_ + 1)
    {
      x_.pop_front();
      f_.pop_front();
    }
    const int m = static_cast<int>(x_.size()) - 1;
    if(m == 0)
      return gx;
    // Minimise |f - dF gamma| over gamma, dF's columns the differences of successive f.
    Eigen::MatrixXd dF(f.size(), m), dX(f.size(), m);
    for(int j = 0; j < m; ++j)
    {
      dF.col(j) = f_[j + 1] - f_[j];
      dX.col(j) = x_[j + 1] - x_[j];
    }
    const Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(f);
    if(!gamma.allFinite())
    {
      reset();
      return gx;
    }
    return gx - (dX + dF) * gamma;
  }

private:
  int depth_;
  std::deque<Eigen::VectorXd> x_, f_;
};

} // namespace internal

/// What a border solve did (`solve_prescribed_border`, `solve_circle_domain`).
struct Border_solve_report
{
  bool converged = false;
  std::string message;
  int newton_iterations = 0; ///< Newton steps of every inverse curvature map solved
  int outer_iterations = 0;  ///< circle domain: evaluations of u <- K^{-1}(T(u))
  /// max |K(u) - target| over all vertices (circle domains: the targets at the final u) at
  /// the start of each outer iteration, and at the end.
  std::vector<double> residual_history;
  double final_residual() const { return residual_history.empty() ? 0.0 : residual_history.back(); }
};

namespace internal {

/// Where a prescribed curvature was missed most, and how far it was from the start: "...
/// is at border vertex 2, where the target turns 1.571 rad and the mesh turns -2.747 rad". A
/// target far from the mesh's own curvature at a few vertices (a square's corner put where
/// the border is concave) is the usual reason Newton cannot reach it.
template <class Metric>
std::string largest_curvature_miss(Curvature_map<Metric>& curvature, const Eigen::VectorXd& target,
                                   const Eigen::VectorXd& start_curvature, const Eigen::VectorXd& u)
{
  Eigen::VectorXd k;
  if(curvature.evaluate(u, k) > 0 || !k.allFinite())
    k = start_curvature;
  Eigen::Index v = 0;
  (k - target).cwiseAbs().maxCoeff(&v);
  const bool border = curvature.mesh_index().is_boundary_vertex[v];
  std::ostringstream out;
  out.precision(4);
  out << "; the largest curvature error (" << std::abs(k[v] - target[v]) << " rad) is at "
      << (border ? "border vertex " : "vertex ") << v << ", where the target " << (border ? "turns" : "has curvature")
      << " " << target[v] << " rad and the mesh " << (border ? "turns" : "has") << " " << start_curvature[v] << " rad";
  return out.str();
}

} // namespace internal

/// Algorithm 1 for a prescribed curvature `target` (Gauss-Bonnet already checked): u moves
/// from its value until K(u) = target. `solver` must have been built with every vertex free
/// but one (the scale). When Newton fails, the message also names the vertex whose target
/// was missed most and its curvature at the start.
template <class SparseSolver, class Metric>
Border_solve_report solve_prescribed_border(Inverse_curvature_map<SparseSolver, Metric>& solver,
                                            const Eigen::VectorXd& target, Eigen::VectorXd& u,
                                            const Newton_options& options)
{
  Border_solve_report report;
  Eigen::VectorXd start_curvature;
  solver.curvature_map().evaluate(u, start_curvature);
  const Newton_report newton = solver.solve(target, u, options);
  report.newton_iterations = newton.iterations;
  report.residual_history = newton.residual_history;
  report.converged = newton.converged;
  report.message = newton.message;
  if(!newton.converged)
    report.message += internal::largest_curvature_miss(solver.curvature_map(), target, start_curvature, u);
  return report;
}

/// The circle domain metric: the fixed point u = K^{-1}(T(u)) of the circle targets T
/// (`internal::circle_domain_targets`), Anderson-accelerated, each K^{-1} a Newton solve
/// warm-started from the current u. Converged when max |K(u) - T(u)| <= options.tolerance.
/// `solver` must have been built with every vertex free but one (the scale).
template <class SparseSolver, class Metric>
Border_solve_report solve_circle_domain(Inverse_curvature_map<SparseSolver, Metric>& solver,
                                        const internal::Mesh_index& index, const Border_target& circles,
                                        Eigen::VectorXd& u, const Newton_options& options)
{
  Border_solve_report report;
  Eigen::VectorXd target, gu, last_gu;
  std::vector<double> lengths, radii;
  internal::Anderson_mixing anderson(circles.anderson_depth);
  // Each inner solve goes a decade below the outer tolerance, so that the fixed point is
  // not limited by it.
  Newton_options inner = options;
  inner.tolerance = options.tolerance / 10;
  for(;; ++report.outer_iterations)
  {
    const Metric& metric = solver.curvature_map().metric();
    if(!internal::circle_domain_targets(index, metric, u, circles.outer_loop, target, lengths, radii, report.message))
      return report;
    gu = u;
    Newton_report newton = solver.solve(target, gu, inner);
    if(newton.residual_history.empty() && report.outer_iterations > 0)
    {
      // The extrapolated u left the metric's valid region: restart plain from the last g.
      anderson.reset();
      u = last_gu;
      continue;
    }
    report.newton_iterations += newton.iterations;
    const double residual = newton.residual_history.empty() ? HUGE_VAL : newton.residual_history.front();
    report.residual_history.push_back(residual);
    if(!newton.converged)
    {
      report.message =
        "circle domain, outer iteration " + std::to_string(report.outer_iterations) + ": " + newton.message;
      return report;
    }
    if(residual <= options.tolerance)
    {
      u = gu;
      // The pinned vertex is outside Newton's residual: measure every vertex at the end.
      if(!internal::circle_domain_targets(index, metric, u, circles.outer_loop, target, lengths, radii, report.message))
        return report;
      Eigen::VectorXd k;
      solver.curvature_map().evaluate(u, k);
      const double final_residual = (k - target).cwiseAbs().maxCoeff();
      report.residual_history.push_back(final_residual);
      report.converged = true;
      return report;
    }
    if(report.outer_iterations == circles.max_iterations)
    {
      report.message = "the circle domain did not converge in " + std::to_string(circles.max_iterations) +
                       " outer iterations (curvature error " + std::to_string(residual) + ")";
      return report;
    }
    last_gu = gu;
    u = anderson.next(u, gu);
  }
}

/// How far the layout of each border loop is from a circle: per loop, the circle fitted to
/// its vertices by least squares (Kasa's algebraic fit, exact for points on a circle), and
/// max |distance to its centre - radius| / radius; the largest over the loops.
inline double max_circle_deviation(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  double worst = 0;
  for(const std::vector<int>& loop : index.boundary_loops)
  {
    // Centred at the mean first, so that the normal equations keep their digits.
    double mx = 0, my = 0;
    for(int v : loop)
    {
      mx += uv[v][0];
      my += uv[v][1];
    }
    mx /= loop.size();
    my /= loop.size();
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for(int v : loop)
    {
      const Eigen::Vector3d row(uv[v][0] - mx, uv[v][1] - my, 1.0);
      const double rhs = -(row[0] * row[0] + row[1] * row[1]);
      a += row * row.transpose();
      b += rhs * row;
    }
    const Eigen::Vector3d def = a.ldlt().solve(b); // x^2 + y^2 + D x + E y + F = 0
    const double cx = -def[0] / 2, cy = -def[1] / 2;
    const double radius = std::sqrt(cx * cx + cy * cy - def[2]);
    for(int v : loop)
      worst = std::max(worst, std::abs(std::hypot(uv[v][0] - mx - cx, uv[v][1] - my - cy) - radius) / radius);
  }
  return worst;
}

/// \brief The free boundary (default): every border vertex singular, the border curvature

} // namespace ICM

#endif // ICM_BORDER_BORDER_SOLVE_H
