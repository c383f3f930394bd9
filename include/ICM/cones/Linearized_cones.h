// Step 4, the default: greedy cone placement on the linearized problem (Ben-Chen, Gotsman,
// Bunin 2008; Sawhney and Crane's BFF places its cones the same way).
//
// Linearized at the mesh's own metric u0, the curvature is K(u0 + u) ~ K0 + Delta u, so the
// entropy optimum with cones S (u_S = 0, K_N = 0 elsewhere) is the harmonic problem
// Delta_NN u_N = -K0_N. It always has a solution, where the exact optimum of a closed
// surface with few cones needs conformal factors no metric can reach; and every round of the
// greedy placement is a solve, not a Newton run.
//
// The factorization is made once. A new cone c only adds the constraint u_c = 0, so with
// x = Delta_FF^{-1} b on the vertices F free at the start, u = x + sum_t lambda_t G_t with
// G_t = Delta_FF^{-1} e_t and the lambdas from the k x k system of the cones' rows of G (the
// capacitance matrix). Per cone: one solve for its column of G; u itself is x + G lambda
// from the kept columns (single precision: the placement compares |u| between vertices, and
// a column of 64 cones at a million vertices then takes 256 MB, not 512), with a second
// solve only past `kept_columns` cones. Memory O(n k + k^2).
//
// A closed surface without a singular vertex is factorized with one vertex p pinned (the
// constant vector spans the kernel of Delta). u is then x + sum lambda_t G_t + c, and p's
// equation, which the pinned system does not hold, is the extra row sum lambda = -sum b.

#ifndef ICM_CONES_LINEARIZED_CONES_H
#define ICM_CONES_LINEARIZED_CONES_H

#include <ICM/Options.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Vector_geometry.h>

#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace ICM {
namespace internal {

/// The linearized entropy optimum for a growing cone set, on one factorization.
template <class SparseSolver, class Metric>
class Linearized_cone_problem
{
public:
  /// `is_fixed`: the border and the cones given before the placement.
  Linearized_cone_problem(const Mesh_index& index, const Metric& metric, const std::vector<char>& is_fixed)
    : index_(index), curvature_(index, metric)
  {
    const int nv = index.number_of_vertices();
    std::vector<double> w;
    if(curvature_.evaluate(metric.u0, k0_, &w) > 0)
    {
      message_ = "the mesh's own metric has faces that are not triangles";
      return;
    }
    std::vector<char> is_free(nv);
    bool any_fixed = false;
    for(int v = 0; v < nv; ++v)
    {
      is_free[v] = !is_fixed[v];
      any_fixed = any_fixed || is_fixed[v];
    }
    pinned_ = !any_fixed && nv > 0;
    if(pinned_)
      is_free[0] = 0; // vertex 0 stands for the constant
    laplacian_.emplace(curvature_.mesh_index(), is_free);
    laplacian_->assemble(w);
    if(!laplacian_->factorize())
    {
      message_ = "the Laplacian of the mesh's metric could not be factorized";
      return;
    }
    b_.resize(laplacian_->size());
    for(int i = 0; i < laplacian_->size(); ++i)
      b_[i] = -k0_[laplacian_->vertex(i)];
    sum_b_ = -k0_.sum();
    x_ = laplacian_->solve(b_);
  }

  const std::string& message() const { return message_; }
  bool ok() const { return message_.empty(); }
  /// Delta_FF at u0, factorized (when `ok()`).
  const Dynamic_laplacian<SparseSolver>& laplacian() const { return *laplacian_; }
  /// Whether the cones so far determine u (a closed surface with chi != 0 needs one).
  bool is_determined() const { return !pinned_ || !cones_.empty(); }

  /// The extreme of the linearized metric of uniform curvature 2 pi chi a_v / A (a_v the
  /// vertex's share of the 3D area): Algorithm 3's strongest minimum (`maxima`: maximum),
  /// where a closed surface's first cone goes.
  int uniform_curvature_extreme(bool maxima) const
  {
    const std::vector<double> area = vertex_areas();
    double total = 0;
    for(double a : area)
      total += a;
    Eigen::VectorXd rhs(laplacian_->size());
    for(int i = 0; i < laplacian_->size(); ++i)
    {
      const int v = laplacian_->vertex(i);
      rhs[i] = 2 * M_PI * index_.euler_characteristic() * area[v] / total - k0_[v];
    }
    const Eigen::VectorXd u = laplacian_->solve(rhs);
    int best = -1;
    for(int i = 0; i < u.size(); ++i)
      if(best < 0 || (maxima ? u[i] > u[best] : u[i] < u[best]))
        best = i;
    // The pinned vertex has u = 0: it is the extreme when every free u is on the wrong side.
    if(best < 0 || (maxima ? u[best] < 0 : u[best] > 0))
      return pinned_ ? 0 : -1;
    return laplacian_->vertex(best);
  }

  /// Makes `v` (a free vertex, or the pinned one) a cone.
  void add_cone(int v)
  {
    const int k = static_cast<int>(cones_.size());
    Eigen::VectorXd column = Eigen::VectorXd::Zero(laplacian_->size());
    if(laplacian_->free_index(v) >= 0)
    {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(laplacian_->size());
      e[laplacian_->free_index(v)] = 1;
      column = laplacian_->solve(e);
    }
    if(has_every_column() && k < kept_columns)
      columns_.push_back(column.cast<float>());
    else
      columns_.clear(); // past the budget: solve() goes back to one solve per call
    cones_.push_back(v);
    capacitance_.conservativeResize(k + 1, k + 1);
    for(int t = 0; t <= k; ++t)
    {
      const double g = value_at(column, cones_[t]);
      capacitance_(t, k) = g;
      capacitance_(k, t) = g;
    }
  }

  /// Position of cone `v` among the cones, in the order they were added.
  int position_of(int v) const { return static_cast<int>(std::find(cones_.begin(), cones_.end(), v) - cones_.begin()); }

  /// Makes the `i`-th cone an ordinary vertex again.
  void remove_cone(int i)
  {
    const int k = static_cast<int>(cones_.size());
    if(has_every_column())
      columns_.erase(columns_.begin() + i);
    cones_.erase(cones_.begin() + i);
    Eigen::MatrixXd kept(k - 1, k - 1);
    for(int r = 0, rr = 0; r < k; ++r)
    {
      if(r == i)
        continue;
      for(int c = 0, cc = 0; c < k; ++c)
        if(c != i)
          kept(rr, cc++) = capacitance_(r, c);
      ++rr;
    }
    capacitance_ = std::move(kept);
  }

  /// u - u0 of the linearized optimum with the cones so far, per vertex.
  Eigen::VectorXd solve() const { return solve_with_cones(b_, sum_b_, x_, has_every_column()); }

  /// The linearized curvature 2 pi - angle of each cone, in the order added: the point
  /// source that holds u = 0 there, since K0 + Delta u vanishes at every other free vertex.
  /// They sum to 2 pi chi minus the border's share.
  Eigen::VectorXd cone_curvatures() const
  {
    Eigen::VectorXd lambda;
    cone_sources(sum_b_, x_, lambda);
    return lambda;
  }

  /// The cone curvatures (in the order added) whose linearized metric has the least
  /// area-weighted variance of u - u0 (the linearized area-weighted mean log^2 area, over 4),
  /// rather than u = 0 at the cones; `log_scale` receives that metric's u - u0 per vertex. A
  /// closed surface's only (the curvatures sum to 2 pi chi, the constant is free); false
  /// elsewhere, or past the kept columns.
  bool least_log_area_curvatures(Eigen::VectorXd& curvatures, Eigen::VectorXd& log_scale) const
  {
    // Unbounded, the linearized angles of a limb-heavy mesh leave the cone angles' range
    // (cow, camel, armadillo at 8 cones: curvatures above 2 pi, below -15). One radian is the
    // sharpest the exact optimum reached on the shared meshes; 4 pi the widest.
    constexpr double min_angle = 1.0, max_angle = 4 * M_PI;
    const int k = static_cast<int>(cones_.size());
    if(!pinned_ || k == 0 || !has_every_column())
      return false;
    // u = x + G lambda + c per vertex (the pinned vertex at c, 0 in x and G), centred by the
    // area-weighted mean: the k x k Gram matrix of G's centred columns, read column by column
    // (no nv x k copy of G).
    const std::vector<double> area = vertex_areas();
    const double total_area = std::accumulate(area.begin(), area.end(), 0.0);
    const int n = laplacian_->size();
    Eigen::VectorXd weight(n);
    for(int i = 0; i < n; ++i)
      weight[i] = area[laplacian_->vertex(i)] / total_area;
    const auto column = [this](int t) { return columns_[t].cast<double>(); };
    Eigen::VectorXd mean(k);
    for(int t = 0; t < k; ++t)
      mean[t] = weight.dot(column(t));
    const double mean_x = weight.dot(x_);
    Eigen::MatrixXd gram(k, k);
    Eigen::VectorXd gx(k);
    for(int t = 0; t < k; ++t)
    {
      const Eigen::VectorXd weighted = weight.cwiseProduct(column(t));
      for(int r = 0; r <= t; ++r)
        gram(t, r) = gram(r, t) = weighted.dot(column(r)) - mean[t] * mean[r];
      gx[t] = -(weighted.dot(x_) - mean[t] * mean_x);
    }
    // Active set: a cone whose angle would fall below `min_angle` (or rise above
    // `max_angle`) is held there, and the others solved again, until none does.
    const double upper = 2 * M_PI - min_angle, lower = 2 * M_PI - max_angle;
    std::vector<double> held(k, std::nan(""));
    for(int round = 0; round <= k; ++round)
    {
      Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(k + 1, k + 1);
      Eigen::VectorXd rhs(k + 1);
      kkt.topLeftCorner(k, k) = gram;
      kkt.block(0, k, k, 1).setOnes();
      kkt.block(k, 0, 1, k).setOnes();
      rhs.head(k) = gx;
      rhs[k] = -sum_b_;
      for(int t = 0; t < k; ++t)
        if(!std::isnan(held[t]))
        {
          kkt.row(t).setZero();
          kkt(t, t) = 1;
          rhs[t] = held[t];
        }
      curvatures = kkt.fullPivLu().solve(rhs).head(k);
      bool changed = false;
      for(int t = 0; t < k; ++t)
        if(std::isnan(held[t]) && (curvatures[t] > upper || curvatures[t] < lower))
        {
          held[t] = curvatures[t] > upper ? upper : lower;
          changed = true;
        }
      if(!changed)
        break;
    }
    log_scale = Eigen::VectorXd::Constant(index_.number_of_vertices(), -mean_x - mean.dot(curvatures));
    for(int i = 0; i < n; ++i)
    {
      double u = x_[i];
      for(int t = 0; t < k; ++t)
        u += columns_[t][i] * curvatures[t];
      log_scale[laplacian_->vertex(i)] += u;
    }
    return curvatures.allFinite() && log_scale.allFinite();
  }

  /// The change of the optimum per unit of curvature taken out at vertex `v` with the cones
  /// so far held at u = 0: a new cone at v moves u by -u_v / h_v(v) times this h.
  Eigen::VectorXd unit_response(int v) const
  {
    Eigen::VectorXd source = Eigen::VectorXd::Zero(laplacian_->size());
    if(laplacian_->free_index(v) >= 0)
      source[laplacian_->free_index(v)] = 1;
    return solve_with_cones(source, 1.0, laplacian_->solve(source), false);
  }

  /// The vertices' shares of the 3D area.
  std::vector<double> vertex_areas() const
  {
    std::vector<double> area(index_.number_of_vertices(), 0.0);
    for(const auto& f : index_.faces)
    {
      const double a = triangle_area(index_.points[f[0]], index_.points[f[1]], index_.points[f[2]]);
      for(int v : f)
        area[v] += a / 3;
    }
    return area;
  }

private:
  /// Delta u = b off the cones (b given per free unknown, `b_sum` its sum over every
  /// vertex), u = 0 at the cones; `x` = Delta_FF^{-1} b. `from_columns`: u = x + G lambda
  /// from the kept columns (only for b = b_), else one more solve.
  Eigen::VectorXd solve_with_cones(const Eigen::VectorXd& b, double b_sum, const Eigen::VectorXd& x,
                                   bool from_columns) const
  {
    const int k = static_cast<int>(cones_.size());
    Eigen::VectorXd lambda;
    const double constant = cone_sources(b_sum, x, lambda);
    Eigen::VectorXd free_u = x;
    if(from_columns)
      for(int t = 0; t < k; ++t)
        free_u += lambda[t] * columns_[t].cast<double>();
    else if(k > 0)
    {
      Eigen::VectorXd source = b;
      for(int t = 0; t < k; ++t)
        if(laplacian_->free_index(cones_[t]) >= 0)
          source[laplacian_->free_index(cones_[t])] += lambda[t];
      free_u = laplacian_->solve(source);
    }
    Eigen::VectorXd u = Eigen::VectorXd::Constant(index_.number_of_vertices(), constant);
    for(int i = 0; i < laplacian_->size(); ++i)
      u[laplacian_->vertex(i)] += free_u[i];
    for(int v : cones_)
      u[v] = 0; // exactly, not to the solve's rounding
    return u;
  }

  /// The point sources `lambda` at the cones that hold u = 0 there (and, pinned, the
  /// constant, returned).
  double cone_sources(double b_sum, const Eigen::VectorXd& x, Eigen::VectorXd& lambda) const
  {
    const int k = static_cast<int>(cones_.size());
    lambda = Eigen::VectorXd::Zero(k);
    double constant = 0;
    if(!pinned_ && k > 0)
    {
      Eigen::VectorXd rhs(k);
      for(int t = 0; t < k; ++t)
        rhs[t] = -value_at(x, cones_[t]);
      lambda = capacitance_.ldlt().solve(rhs);
    }
    else if(pinned_ && k > 0)
    {
      Eigen::MatrixXd saddle = Eigen::MatrixXd::Zero(k + 1, k + 1);
      Eigen::VectorXd rhs(k + 1);
      saddle.topLeftCorner(k, k) = capacitance_;
      for(int t = 0; t < k; ++t)
      {
        saddle(t, k) = 1;
        saddle(k, t) = 1;
        rhs[t] = -value_at(x, cones_[t]);
      }
      rhs[k] = -b_sum;
      const Eigen::VectorXd solution = saddle.fullPivLu().solve(rhs);
      lambda = solution.head(k);
      constant = solution[k];
    }
    return constant;
  }

  bool has_every_column() const { return columns_.size() == cones_.size(); }

  double value_at(const Eigen::VectorXd& free_values, int v) const
  {
    const int i = laplacian_->free_index(v);
    return i >= 0 ? free_values[i] : 0.0;
  }

  const Mesh_index& index_;
  Curvature_map<Metric> curvature_;
  std::optional<Dynamic_laplacian<SparseSolver>> laplacian_;
  Eigen::VectorXd k0_, b_, x_;
  double sum_b_ = 0;
  bool pinned_ = false;
  static constexpr int kept_columns = 64;
  std::vector<int> cones_;
  std::vector<Eigen::VectorXf> columns_; // G's columns, one per cone, while within the budget
  Eigen::MatrixXd capacitance_;
  std::string message_;
};

} // namespace internal
} // namespace ICM

#endif // ICM_CONES_LINEARIZED_CONES_H
