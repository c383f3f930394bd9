// Step 4, after the greedy placement at a named count: placement moves judged on the exact
// entropy optimum (u_S = u0_S, K_N = 0) rather than on a prediction. A move takes one cone
// elsewhere, the weakest to where |u - u0| is largest or a cone to its ring neighbour of
// largest |u - u0|; it is kept only when the exact optimum it gives, by Newton warm-started
// from the one before, has less area distortion. So the sweep never leaves the greedy's
// cones worse, and it stops when no move is kept or its time budget is spent.

#ifndef ICM_CONES_EXACT_CONE_SWEEPS_H
#define ICM_CONES_EXACT_CONE_SWEEPS_H

#include <ICM/Options.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>
#include <ICM/internal/Vector_geometry.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ICM {

/// What the sweep did: moves tried and kept, and the area distortion (`mean_log_area_of_scale`)
/// of the exact optimum before and after (NaN when the first optimum failed: no move).
struct Exact_sweep_report
{
  int moves_tried = 0, moves_kept = 0;
  double initial_log_area = std::numeric_limits<double>::quiet_NaN();
  double final_log_area = std::numeric_limits<double>::quiet_NaN();
};

namespace internal {

/// The exact optimum's time the sweep may spend again, in solves: about what the rest of a
/// named count's call takes (the chart's solve and the other cone angles' warm-started ones
/// with their layouts: bull and camel at 8 cones, two to four).
constexpr double exact_sweep_budget_in_solves = 4;

/// The sweep's Newton tolerance: its optima only compare distortions of a few percent, and a
/// warm-started Newton reaches this in one or two steps.
constexpr double exact_sweep_tolerance = 1e-6;

/// The area-weighted mean of log^2 (area ratio) of the metric of log scale `log_scale`
/// (u - u0) on the faces of `index` of 3D area `face_area`: each face's log area ratio taken
/// as 2/3 of its vertices' log scales (exact where a face's scale is constant), less the log
/// of the mean ratio, since a layout is scaled to the 3D area. The report's figure at the
/// metric, before any layout.
inline double mean_log_area_of_scale(const Mesh_index& index, const std::vector<double>& face_area,
                                     const Eigen::VectorXd& log_scale)
{
  double area = 0, scaled_area = 0;
  for(std::size_t f = 0; f < index.faces.size(); ++f)
  {
    const auto& t = index.faces[f];
    area += face_area[f];
    scaled_area += face_area[f] * std::exp(2.0 / 3.0 * (log_scale[t[0]] + log_scale[t[1]] + log_scale[t[2]]));
  }
  const double shift = std::log(scaled_area / area);
  double sum = 0;
  for(std::size_t f = 0; f < index.faces.size(); ++f)
  {
    const auto& t = index.faces[f];
    const double log_ratio = 2.0 / 3.0 * (log_scale[t[0]] + log_scale[t[1]] + log_scale[t[2]]) - shift;
    sum += face_area[f] * log_ratio * log_ratio;
  }
  return sum / area;
}

/// The sweep's state: the singular set, the exact optimum u at it and the curvature there.
template <class Solver, class Metric>
class Exact_cone_sweep
{
public:
  Exact_cone_sweep(const Mesh_index& index, const Metric& metric, const Newton_options& newton)
    : index_(index), metric_(metric), newton_(newton), first_ring_(index.number_of_vertices() + 1, 0)
  {
    newton_.tolerance = std::max(newton_.tolerance, exact_sweep_tolerance);
    for(const auto& f : index.faces)
      face_area_.push_back(triangle_area(index.points[f[0]], index.points[f[1]], index.points[f[2]]));
    for(const auto& e : index.edges)
    {
      ++first_ring_[e[0] + 1];
      ++first_ring_[e[1] + 1];
    }
    for(std::size_t v = 1; v < first_ring_.size(); ++v)
      first_ring_[v] += first_ring_[v - 1];
    ring_.resize(first_ring_.back());
    std::vector<int> filled(first_ring_.begin(), first_ring_.end() - 1);
    for(const auto& e : index.edges)
    {
      ring_[filled[e[0]]++] = e[1];
      ring_[filled[e[1]]++] = e[0];
    }
  }

  /// Moves the cones `movable` (in `is_singular`) while moves lower the exact optimum's area
  /// distortion, from `start_step` (u - u0, the linearized optimum; empty: u0).
  Exact_sweep_report run(std::vector<char>& is_singular, std::vector<int>& movable, const Eigen::VectorXd& start_step)
  {
    Exact_sweep_report report;
    u_ = metric_.u0;
    if(start_step.size() == u_.size())
      u_ += start_step;
    Stopwatch clock;
    if(!solve(is_singular, u_, k_))
      return report;
    const double budget = exact_sweep_budget_in_solves * clock.total();
    log_area_ = report.initial_log_area = mean_log_area_of_scale(index_, face_area_, u_ - metric_.u0);
    for(bool moved = true; moved && clock.total() < budget;)
    {
      moved = try_move(is_singular, movable, weakest(movable), largest_scale(is_singular), report);
      for(std::size_t i = 0; i < movable.size() && clock.total() < budget; ++i)
        moved = try_move(is_singular, movable, i, largest_scale_among_ring(is_singular, movable[i]), report) || moved;
    }
    report.final_log_area = log_area_;
    return report;
  }

  /// u - u0 of the exact optimum at the cones the sweep left.
  Eigen::VectorXd log_scale() const { return u_ - metric_.u0; }

private:
  /// The exact entropy optimum u_S = u0_S, K_N = 0 at `is_singular`, from `u`; `k` its curvature.
  bool solve(const std::vector<char>& is_singular, Eigen::VectorXd& u, Eigen::VectorXd& k) const
  {
    Inverse_curvature_map<Solver, Metric> newton(index_, metric_, free_vertices_off(is_singular));
    for(int v = 0; v < index_.number_of_vertices(); ++v)
      if(is_singular[v])
        u[v] = metric_.u0[v];
    if(!newton.solve(Eigen::VectorXd::Zero(u.size()), u, newton_).converged)
      return false;
    k = newton.curvature();
    return true;
  }

  double scale_at(int v) const { return std::abs(u_[v] - metric_.u0[v]); }

  /// The non-singular ring neighbour of `cone` with the largest |u - u0| (-1: none).
  int largest_scale_among_ring(const std::vector<char>& is_singular, int cone) const
  {
    int best = -1;
    for(int i = first_ring_[cone]; i < first_ring_[cone + 1]; ++i)
      if(!is_singular[ring_[i]] && (best < 0 || scale_at(ring_[i]) > scale_at(best)))
        best = ring_[i];
    return best;
  }

  /// The non-singular vertex with the largest |u - u0| (-1: none).
  int largest_scale(const std::vector<char>& is_singular) const
  {
    int best = -1;
    for(int v = 0; v < index_.number_of_vertices(); ++v)
      if(!is_singular[v] && (best < 0 || scale_at(v) > scale_at(best)))
        best = v;
    return best;
  }

  /// The position in `movable` of the cone carrying the least |curvature|.
  std::size_t weakest(const std::vector<int>& movable) const
  {
    std::size_t weakest = 0;
    for(std::size_t i = 1; i < movable.size(); ++i)
      if(std::abs(k_[movable[i]]) < std::abs(k_[movable[weakest]]))
        weakest = i;
    return weakest;
  }

  /// Moves cone `movable[i]` to vertex `to` if the exact optimum there has less distortion.
  bool try_move(std::vector<char>& is_singular, std::vector<int>& movable, std::size_t i, int to,
                Exact_sweep_report& report)
  {
    if(to < 0 || i >= movable.size())
      return false;
    ++report.moves_tried;
    const int from = movable[i];
    is_singular[from] = 0;
    is_singular[to] = 1;
    Eigen::VectorXd u = u_, k;
    if(solve(is_singular, u, k))
    {
      const double log_area = mean_log_area_of_scale(index_, face_area_, u - metric_.u0);
      if(log_area < log_area_)
      {
        u_ = std::move(u);
        k_ = std::move(k);
        log_area_ = log_area;
        movable[i] = to;
        ++report.moves_kept;
        return true;
      }
    }
    is_singular[to] = 0;
    is_singular[from] = 1;
    return false;
  }

  const Mesh_index& index_;
  const Metric& metric_;
  Newton_options newton_;
  std::vector<double> face_area_;
  std::vector<int> first_ring_, ring_; // the vertices around each vertex (CSR)
  Eigen::VectorXd u_, k_;
  double log_area_ = 0;
};

} // namespace internal

/// Placement moves of the cones `movable` (in `is_singular`) judged on the exact entropy
/// optimum in the class of `metric` (see above), from the linearized optimum `start_step`.
template <class Solver, class Metric>
Exact_sweep_report sweep_cones_on_the_exact_optimum(const internal::Mesh_index& index, const Metric& metric,
                                                    std::vector<char>& is_singular, std::vector<int>& movable,
                                                    const Eigen::VectorXd& start_step, const Newton_options& newton)
{
  internal::Exact_cone_sweep<Solver, Metric> sweep(index, metric, newton);
  return sweep.run(is_singular, movable, start_step);
}

} // namespace ICM

#endif // ICM_CONES_EXACT_CONE_SWEEPS_H
