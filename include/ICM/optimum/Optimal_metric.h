// Step 5: the optimal metric in the admissible curvature space (paper Sec. III-D/E).
//
// The curvature entropy E_EN (Def. 3.3) is convex with gradient u - u0 (Thm 3.5); its unique
// minimum over {k_N = 0, sum_S k = 2 pi chi} has u_S - u0_S constant. Up to the irrelevant
// global scale this is the Dirichlet problem u_S = u0_S, K(u)_N = 0, which Newton solves in a
// handful of factorizations (the default). The paper's curvature diffusion (Algorithm 5)
// reaches the same metric by many explicit steps and is kept to validate it.

#ifndef ICM_OPTIMUM_OPTIMAL_METRIC_H
#define ICM_OPTIMUM_OPTIMAL_METRIC_H

#include <ICM/Options.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Option_checks.h>

#include <Eigen/Core>

#include <algorithm>
#include <string>
#include <vector>

namespace ICM {

/// The free-boundary singular set: every boundary vertex.
inline std::vector<char> boundary_singular_set(const internal::Mesh_index& index)
{
  return std::vector<char>(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
}

/// Minimum of the curvature entropy for the singular set S, by Newton on the Dirichlet
/// problem u_S = u0_S, K(u)_N = 0. `solver` must have been built with F = not S; it keeps
/// its factorization pattern for later use (the harmonic layout reuses it).
///
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"
/// \tparam Metric a model of \ref ::Metric "Metric"
template <class SparseSolver, class Metric>
Newton_report free_boundary_optimum(Inverse_curvature_map<SparseSolver, Metric>& solver, const Metric& metric,
                                    Eigen::VectorXd& u, const Newton_options& options = Newton_options())
{
  u = metric.u0;
  const Eigen::VectorXd flat = Eigen::VectorXd::Zero(u.size());
  return solver.solve(flat, u, options);
}

/// Convenience form that builds the solver for `is_singular`.
template <class SparseSolver = Default_sparse_solver, class Metric = Circle_packing_metric>
Newton_report free_boundary_optimum(const internal::Mesh_index& index, const Metric& metric,
                                    const std::vector<char>& is_singular, Eigen::VectorXd& u,
                                    const Newton_options& options = Newton_options())
{
  Inverse_curvature_map<SparseSolver, Metric> solver(index, metric, free_vertices_off(is_singular));
  return free_boundary_optimum(solver, metric, u, options);
}

struct Diffusion_report
{
  bool converged = false;
  int iterations = 0;
  double final_residual = 0;
  std::string message;
};

/// Algorithm 5, free boundary curvature diffusion: du_N = -lambda k_N, then the mean of
/// u - u0 is removed. Every step shifts u_S by one constant, so u_S - u0_S stays uniform
/// (Lemma 3.4) and the limit is the entropy minimum.
template <class Metric = Circle_packing_metric>
Diffusion_report free_boundary_curvature_diffusion(const internal::Mesh_index& index, const Metric& metric,
                                                   const std::vector<char>& is_singular, Eigen::VectorXd& u,
                                                   const Diffusion_options& options = Diffusion_options())
{
  Diffusion_report report;
  if(const Status checked = check_options(options); !checked.ok())
  {
    report.message = checked.message;
    return report;
  }
  Curvature_map<Metric> curvature(index, metric);
  const int nv = index.number_of_vertices();
  u = metric.u0;
  Eigen::VectorXd k;
  std::vector<double> w;
  std::vector<double> diagonal(nv);
  for(;; ++report.iterations)
  {
    curvature.evaluate(u, k, &w);
    report.final_residual = 0;
    for(int v = 0; v < nv; ++v)
      if(!is_singular[v])
        report.final_residual = std::max(report.final_residual, std::abs(k[v]));
    if(report.final_residual <= options.tolerance)
      break;
    if(report.iterations == options.max_iterations || !std::isfinite(report.final_residual))
    {
      report.message =
        "curvature diffusion did not converge (curvature error " + std::to_string(report.final_residual) + ")";
      return report;
    }
    std::fill(diagonal.begin(), diagonal.end(), 0.0);
    const internal::Mesh_index& t = curvature.mesh_index();
    for(int e = 0; e < t.number_of_edges(); ++e)
      for(int v : t.edges[e])
        diagonal[v] += w[e];
    double largest = 0;
    for(int v = 0; v < nv; ++v)
      if(!is_singular[v])
        largest = std::max(largest, diagonal[v]);
    const double lambda = options.step_fraction / largest;
    for(int v = 0; v < nv; ++v)
      if(!is_singular[v])
        u[v] -= lambda * k[v];
    u.array() -= (u - metric.u0).mean();
  }
  report.converged = true;
  return report;
}

} // namespace ICM

#endif // ICM_OPTIMUM_OPTIMAL_METRIC_H
