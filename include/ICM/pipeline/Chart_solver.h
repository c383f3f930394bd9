// Steps 5 and 7 of one chart, for both entry points: the optimum of the chart's metric (the
// entropy's, then another energy's from there), its isometric layout, the unflipping of the
// faces the mesh has and the metric's own triangulation does not, the checks, and the
// fallback to the circle packing when the chosen metric cannot get there.
//
// A chart is a surface with its singular set S (u_S = u0_S; the free vertices reach their
// target curvature) laid out either as it is (a disk: `Inverse_curvature_map_parameterizer_3`)
// or cut open along seams through its cones (`ICM::parameterize`), and the solver is the same
// for both.

#ifndef ICM_PIPELINE_CHART_SOLVER_H
#define ICM_PIPELINE_CHART_SOLVER_H

#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/Status.h>
#include <ICM/border/Border_solve.h>
#include <ICM/border/Border_target.h>
#include <ICM/border/Straight_sides.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/cut/Cut_mesh.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Unflip.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>

#include <CGAL/Surface_mesh_parameterization/Error_code.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {
namespace internal {

/// One chart's problem.
struct Chart_problem
{
  const Mesh_index* mesh = nullptr;
  /// Per vertex: 1 where K(u) = `target` is an equation, 0 where u = u0 (the singular set,
  /// or for a prescribed border the one vertex that fixes the scale).
  std::vector<char> is_free;
  Eigen::VectorXd target;
  /// Per vertex: the border and the cones. The report's cones are the interior ones, its
  /// curvature error is measured off them.
  std::vector<char> is_singular;
  /// Per edge: the seams (empty: none), kept as edges by a metric that flips its own
  /// triangulation.
  std::vector<char> seams;
  /// `mesh` cut open along `seams`, which is laid out (null: `mesh` is a disk, laid out as
  /// it is, one UV per vertex).
  const Cut_mesh* cut = nullptr;
  /// A prescribed border (null or `Border_kind::Free`: none); only on an uncut disk.
  const Border_target* border = nullptr;
  /// The first step of the entropy's Newton from u0, per vertex of `mesh` (empty: Newton's
  /// own): the cone placement's linearized optimum, which is that step without its
  /// factorization.
  Eigen::VectorXd first_step;

  bool prescribes_border() const { return border != nullptr && border->prescribes_border(); }
};

/// The disk parameterizer's choices beyond `Chart_options` (the surface pipeline keeps these
/// defaults), and its stage callback.
struct Chart_method
{
  Optimum_method optimum = Optimum_method::Newton;
  Diffusion_options diffusion;
  Layout_method layout = Layout_method::Automatic;
  int harmonic_layout_min_faces = 200000;
  std::function<void(const std::string&)> progress;

  /// Whether a chart of `faces` faces whose border is free is laid out harmonically first.
  bool harmonic_for(int faces) const
  {
    return layout == Layout_method::Harmonic ||
           (layout == Layout_method::Automatic && faces >= harmonic_layout_min_faces);
  }
};

/// The metric of class `Metric` for `index`; a metric that flips its own triangulation keeps
/// `fixed_edges` (the seams; empty: none) as edges.
template <class Metric>
Metric make_metric(const Mesh_index& index, const std::vector<char>& fixed_edges)
{
  if constexpr(std::is_constructible<Metric, const Mesh_index&, const std::vector<char>&>::value)
    return Metric(index, fixed_edges);
  else
    return Metric(index);
}

/// Max relative difference between the UV lengths of the two sides of every seam edge.
inline double seam_length_error(const Cut_mesh& cut, const std::vector<Uv>& uv)
{
  double worst = 0;
  for(const auto& sides : cut.disk_edges)
  {
    if(sides[1] < 0)
      continue;
    auto uv_length = [&](int d) {
      const Uv &a = uv[cut.disk.edges[d][0]], &b = uv[cut.disk.edges[d][1]];
      return std::hypot(a[0] - b[0], a[1] - b[1]);
    };
    const double l0 = uv_length(sides[0]), l1 = uv_length(sides[1]);
    worst = std::max(worst, std::abs(l0 - l1) / std::max(l0, l1));
  }
  return worst;
}

/// A seam vertex's two motions are one (it is no cone) when they agree to this: in angle, and
/// in where they take the twin relative to its distance from the origin. A cone's motions
/// differ by its angle defect, orders of magnitude above the layout's rounding.
constexpr double seam_twin_tolerance = 1e-6;

/// The two wedges of every flat interior vertex that a seam passes through, each with the
/// rigid motion that takes its twin's UVs into its frame (`Seam_twin`). The motion is read
/// from each of the vertex's two seam edges; where they disagree the vertex is a cone on the
/// seam (its sides turn by its angle defect) and gets no twin.
inline std::vector<Seam_twin> seam_twins(const Mesh_index& index, const Cut_mesh& cut, const std::vector<Uv>& uv)
{
  const int nw = static_cast<int>(cut.surface_vertex.size());
  std::vector<Seam_twin> twins(nw);
  std::vector<int> wedges_of(index.number_of_vertices(), 0);
  for(int v : cut.surface_vertex)
    ++wedges_of[v];
  // Per wedge, the motions found so far (at most two: one per seam edge).
  std::vector<std::array<Seam_twin, 2>> found(nw);
  std::vector<int> count(nw, 0);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const std::array<int, 2>& sides = cut.disk_edges[e];
    if(sides[1] < 0)
      continue;
    for(int end = 0; end < 2; ++end)
    {
      const int v = index.edges[e][end];
      if(wedges_of[v] != 2 || index.is_boundary_vertex[v])
        continue;
      // Side s: the wedge of v and the wedge of the other end.
      std::array<int, 2> at{}, other{};
      for(int s = 0; s < 2; ++s)
      {
        const auto& d = cut.disk.edges[sides[s]];
        const bool first_is_v = cut.surface_vertex[d[0]] == v;
        at[s] = first_is_v ? d[0] : d[1];
        other[s] = first_is_v ? d[1] : d[0];
      }
      for(int s = 0; s < 2; ++s)
      {
        const int w = at[s], t = at[1 - s];
        const double angle = std::atan2(uv[other[s]][1] - uv[w][1], uv[other[s]][0] - uv[w][0]) -
                             std::atan2(uv[other[1 - s]][1] - uv[t][1], uv[other[1 - s]][0] - uv[t][0]);
        Seam_twin m;
        m.wedge = t;
        m.c = std::cos(angle);
        m.s = std::sin(angle);
        const Uv rotated = m.to_this(uv[t]);
        m.tx = uv[w][0] - rotated[0];
        m.ty = uv[w][1] - rotated[1];
        if(count[w] < 2)
          found[w][count[w]] = m;
        ++count[w];
      }
    }
  }
  for(int w = 0; w < nw; ++w)
  {
    if(count[w] != 2)
      continue;
    // Both motions must take the twin's star to the same place: compare them at the twin.
    const Seam_twin& a = found[w][0];
    const Seam_twin& b = found[w][1];
    const Uv p = a.to_this(uv[a.wedge]), q = b.to_this(uv[b.wedge]);
    const double turn = std::abs(std::atan2(a.s * b.c - a.c * b.s, a.c * b.c + a.s * b.s));
    if(turn < seam_twin_tolerance &&
       std::hypot(p[0] - q[0], p[1] - q[1]) <= seam_twin_tolerance * std::hypot(p[0], p[1]) + 1e-300)
      twins[w] = a;
  }
  return twins;
}

/// An energy's optimizer stops at its own tolerance on the energy, where the metric is flat
/// only to about the run's Newton tolerance; these few Newton steps at a tolerance a thousand
/// times tighter make it flat with a margin before the layout.
constexpr double finishing_newton_tolerance_factor = 1e-3;
constexpr int finishing_newton_steps = 3;

/// Step 5, the entropy: Algorithm 1 for a prescribed border (or the circle domain's fixed
/// point), the curvature diffusion when asked, else Newton on the Dirichlet problem.
template <class Metric, class Solver>
Status entropy_optimum(const Chart_problem& problem, const Chart_options& options, const Chart_method& method,
                       const Metric& metric, Inverse_curvature_map<Solver, Metric>& solver, Eigen::VectorXd& u,
                       Chart_solve_report& report)
{
  using CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
  const Mesh_index& index = *problem.mesh;
  u = metric.u0;
  if(problem.prescribes_border())
  {
    const Border_target& border = *problem.border;
    const Border_solve_report solved = border.kind == Border_kind::Circles
                                         ? solve_circle_domain(solver, index, border, u, options.newton)
                                         : solve_prescribed_border(solver, border.curvature, u, options.newton);
    report.newton_iterations = solved.newton_iterations;
    report.border_iterations = solved.outer_iterations;
    report.residual_history = solved.residual_history;
    report.max_curvature_error = solved.final_residual();
    return solved.converged ? Status::success() : Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, solved.message);
  }
  if(method.optimum == Optimum_method::Curvature_diffusion)
  {
    const Diffusion_report diffusion =
      free_boundary_curvature_diffusion(index, metric, problem.is_singular, u, method.diffusion);
    return diffusion.converged ? Status::success()
                               : Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, diffusion.message);
  }
  const Newton_report newton =
    solver.solve(problem.target, u, options.newton, problem.first_step.size() > 0 ? &problem.first_step : nullptr);
  report.newton_iterations = newton.iterations;
  report.factorizations = newton.factorizations;
  report.preconditioned_solves = newton.preconditioned_solves;
  report.residual_history = newton.residual_history;
  return newton.converged ? Status::success() : Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, newton.message);
}

/// Step 5, another energy, from the entropy optimum `u`: its minimum over the same singular
/// set, which has something to choose when S has two vertices or more (the optimizer keeps
/// the mean of u_S) and the border is free. An optimizer that stops early keeps its best
/// metric; only a failure at the start is an error. The result is flat to the Newton
/// tolerance; a step or two more take it to rounding, as the entropy's Newton ends, so that
/// a cut layout closes up as well.
template <class Metric, class Solver, class Energy>
Status energy_optimum(const Chart_problem& problem, const Chart_options& options, const Metric& metric,
                      Inverse_curvature_map<Solver, Metric>& solver, const Energy& energy, Eigen::VectorXd& u,
                      Chart_solve_report& report)
{
  using CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
  if(problem.prescribes_border() || std::count(problem.is_free.begin(), problem.is_free.end(), 0) < 2)
    return Status::success();
  const Curvature_space_report optimizer = minimize_energy_on_singular_values(
    solver, *problem.mesh, metric, energy, u, with_newton(options.energy, options.newton), problem.target);
  report.energy_iterations = optimizer.iterations;
  report.initial_energy = optimizer.initial_energy;
  report.final_energy = optimizer.final_energy;
  report.energy_message = optimizer.message;
  if(optimizer.energy_history.empty())
    return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM,
                           std::string(energy_name<Energy>()) + " energy: " + optimizer.message);
  Newton_options finish = options.newton;
  finish.tolerance = finishing_newton_tolerance_factor * options.newton.tolerance;
  finish.max_iterations = finishing_newton_steps;
  const Newton_report newton = solver.solve(problem.target, u, finish);
  report.newton_iterations += optimizer.newton_iterations + newton.iterations;
  const bool flat = !newton.residual_history.empty() && newton.residual_history.back() <= options.newton.tolerance;
  return flat ? Status::success() : Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, newton.message);
}

/// The chart's cones and its curvature error at the result's curvature `k`.
inline void report_curvature(const Chart_problem& problem, const Eigen::VectorXd& k, Chart_solve_report& report)
{
  const Mesh_index& index = *problem.mesh;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(problem.is_singular[v] && !index.is_boundary_vertex[v])
    {
      report.cones.push_back(v);
      report.cone_curvatures.push_back(k[v]);
    }
  if(problem.prescribes_border())
    return; // measured against the border's target by its solve
  report.max_curvature_error = 0;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    if(!problem.is_singular[v])
      report.max_curvature_error = std::max(report.max_curvature_error, std::abs(k[v]));
}

/// Step 7 on an uncut disk: the metric's triangulation (the mesh's, or its intrinsic one,
/// which has the mesh's vertices) laid out, harmonically when asked and the border is free
/// (its Laplacian is the Newton system's), one UV per vertex.
template <class Metric, class Solver>
Status lay_out_disk(const Chart_problem& problem, const Chart_method& method,
                    Inverse_curvature_map<Solver, Metric>& solver, const Eigen::VectorXd& k,
                    const std::vector<double>& weights, Chart_solve_report& report, std::vector<Uv>& uv,
                    Layout_check& check)
{
  const Mesh_index& index = *problem.mesh;
  Curvature_map<Metric>& curvature = solver.curvature_map();
  const Mesh_index& triangulation = curvature.mesh_index();
  const std::vector<double>& lengths = curvature.lengths();
  const bool harmonic = !problem.prescribes_border() && method.harmonic_for(index.number_of_faces());
  report.layout = harmonic ? "harmonic" : "propagation";
  if(harmonic)
  {
    std::string why;
    if(!layout_harmonic(triangulation, lengths, k, weights, solver.laplacian(), uv, why))
      return Status::failure(CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, why);
  }
  else
    uv = layout_by_propagation(triangulation, lengths, curvature.face_angles());
  check = check_layout(triangulation, lengths, uv);
  if(&triangulation != &index && check.flipped_faces == 0)
  {
    // A prescribed border stays where the metric put it (a moved border vertex would leave
    // its circle or its rectangle's side): only interior vertices move.
    std::vector<char> is_movable(index.number_of_vertices(), 1);
    if(problem.prescribes_border())
      for(int v = 0; v < index.number_of_vertices(); ++v)
        is_movable[v] = !index.is_boundary_vertex[v];
    report.moved_vertices = unflip_by_moving_vertices(index, uv, is_movable);
  }
  return Status::success();
}

/// The harmonic layout of a cut disk (`layout_harmonic`): its border, seams included, walked
/// with the metric's lengths and turning angles, its interior the solution of the metric's
/// Laplacian on the disk, whose every edge takes the weights of its own faces (a seam's two
/// sides one face each). It reproduces the metric to the solver's precision wherever the
/// metric is flat inside, where the propagation's error grows with the number of faces
/// between an edge and the root (lion-head refined to 1.07M faces: 1.2e-4). `newton`, when
/// given, is the optimum's Laplacian on the same vertices, edges and free vertices: its last
/// factorization then solves the layout by refinement.
template <class Solver, class Metric>
bool lay_out_cut_harmonically(const Mesh_index& disk, const std::vector<double>& disk_lengths,
                              const Curvature_map<Metric>& curvature, std::vector<Uv>& uv, std::string& why,
                              Dynamic_laplacian<Solver>* newton = nullptr)
{
  Eigen::VectorXd k(disk.number_of_vertices());
  for(int w = 0; w < disk.number_of_vertices(); ++w)
    k[w] = disk.is_boundary_vertex[w] ? M_PI : 2.0 * M_PI;
  std::vector<double> weights(disk.number_of_edges(), 0.0);
  for(int f = 0; f < disk.number_of_faces(); ++f)
  {
    const Face_geometry face = curvature.face_geometry(f); // the disk's faces are the metric's
    for(int c = 0; c < 3; ++c)
    {
      k[disk.faces[f][c]] -= face.angles.angle[c];
      weights[disk.face_edges[f][c]] += face.weight[c];
    }
  }
  if(newton != nullptr)
    return layout_harmonic(disk, disk_lengths, k, weights, *newton, uv, why);
  std::vector<char> is_interior(disk.number_of_vertices());
  for(int w = 0; w < disk.number_of_vertices(); ++w)
    is_interior[w] = !disk.is_boundary_vertex[w];
  Dynamic_laplacian<Solver> laplacian(disk, is_interior);
  return layout_harmonic(disk, disk_lengths, k, weights, laplacian, uv, why);
}

/// Whether `laplacian` (of the triangulation `disk` was cut from) is the harmonic layout's
/// of `disk`: a cut without seams keeps the numbers of vertices and edges, and the free
/// vertices must be the interior ones (a free border, not a prescribed one).
template <class Solver>
bool is_layout_laplacian_of(const Dynamic_laplacian<Solver>& laplacian, const Mesh_index& triangulation,
                            const Mesh_index& disk)
{
  if(disk.number_of_vertices() != triangulation.number_of_vertices() ||
     disk.number_of_edges() != triangulation.number_of_edges())
    return false;
  for(int v = 0; v < disk.number_of_vertices(); ++v)
    if((laplacian.free_index(v) >= 0) == static_cast<bool>(disk.is_boundary_vertex[v]))
      return false;
  return true;
}

/// Step 7 on a cut surface: the metric laid out on the cut, both sides of a seam one length.
/// An intrinsic triangulation is cut along the same seams and laid out, and each wedge of the
/// mesh's cut takes the UV of the same wedge there; a face of the mesh that lands flipped is
/// unflipped by moving wedges that may move: a vertex on no seam, or a wedge with its twin
/// across a seam through a flat vertex (not the one wedge of a cone where a seam ends: both
/// sides of its seam edge start there, and moving it would give them different lengths).
template <class Solver, class Metric>
Status lay_out_cut(const Chart_problem& problem, const Chart_options& options, const Chart_method& method,
                   Inverse_curvature_map<Solver, Metric>& solver, Chart_solve_report& report, std::vector<Uv>& uv,
                   Layout_check& check)
{
  Curvature_map<Metric>& curvature = solver.curvature_map();
  using CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
  const Mesh_index& index = *problem.mesh;
  const Cut_mesh& cut = *problem.cut;
  const Mesh_index& triangulation = curvature.mesh_index();
  const bool intrinsic = &triangulation != &index;
  Cut_mesh intrinsic_cut;
  if(intrinsic)
  {
    intrinsic_cut = cut_mesh(triangulation, problem.seams);
    if(!intrinsic_cut.ok())
      return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM,
                             "the intrinsic triangulation: " + intrinsic_cut.status.message);
  }
  const Cut_mesh& laid = intrinsic ? intrinsic_cut : cut;
  std::vector<double> disk_lengths(laid.disk.number_of_edges());
  for(int d = 0; d < laid.disk.number_of_edges(); ++d)
    disk_lengths[d] = curvature.lengths()[laid.surface_edge[d]];
  // Harmonic first on a large chart; by propagation first otherwise, and harmonic after all
  // when the propagation misses the metric's lengths: the better of the two is kept.
  const bool harmonic_first = method.harmonic_for(laid.disk.number_of_faces());
  uv.clear(); // it may hold the layout of a metric that failed
  for(int attempt = 0; attempt < 2; ++attempt)
  {
    const bool harmonic = harmonic_first == (attempt == 0);
    std::vector<Uv> candidate;
    std::string why;
    // Newton's Laplacian, only asked for here: it brings its pattern up to date with flips.
    Dynamic_laplacian<Solver>* newton = nullptr;
    if(harmonic && is_layout_laplacian_of(solver.laplacian(), triangulation, laid.disk))
      newton = &solver.laplacian();
    if(harmonic && !lay_out_cut_harmonically<Solver>(laid.disk, disk_lengths, curvature, candidate, why, newton))
      continue; // the propagation is always possible
    if(!harmonic)
      candidate = layout_by_propagation(laid.disk, disk_lengths, curvature.face_angles());
    const Layout_check candidate_check = check_layout(laid.disk, disk_lengths, candidate);
    if(uv.empty() || candidate_check.flipped_faces < check.flipped_faces ||
       (candidate_check.flipped_faces == check.flipped_faces &&
        candidate_check.max_relative_length_error < check.max_relative_length_error))
    {
      uv.swap(candidate);
      check = candidate_check;
      report.layout = harmonic ? "harmonic" : "propagation";
    }
    if(check.flipped_faces == 0 && check.max_relative_length_error <= options.max_layout_length_error)
      break;
  }
  if(intrinsic)
  {
    const std::vector<int> match = match_wedges(index, cut, triangulation, intrinsic_cut, problem.seams);
    if(match.empty())
      return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM,
                             "the wedges of the intrinsic triangulation do not match the mesh's");
    std::vector<Uv> intrinsic_uv;
    intrinsic_uv.swap(uv);
    uv.resize(match.size());
    for(std::size_t w = 0; w < match.size(); ++w)
      uv[w] = intrinsic_uv[match[w]];
    if(check.flipped_faces == 0 && count_flipped_faces(cut.disk, uv) > 0)
    {
      const std::vector<int> seam_degree = seam_degrees(index, problem.seams);
      const std::vector<Seam_twin> twins = seam_twins(index, cut, uv);
      std::vector<char> is_movable(cut.surface_vertex.size());
      for(std::size_t w = 0; w < is_movable.size(); ++w)
        is_movable[w] = seam_degree[cut.surface_vertex[w]] == 0 || twins[w].wedge >= 0;
      report.moved_vertices = unflip_by_moving_vertices(cut.disk, uv, is_movable, twins);
    }
  }
  report.seam_length_error = seam_length_error(cut, uv);
  return Status::success();
}

/// What a prescribed border asks of the finished layout: its 3D scale; a circle border's
/// deviation from its circles; a rectangle's sides made exactly straight, the faces held on one
/// side (segments in any layout) counted apart rather than as flipped.
inline void finish_prescribed_border(const Chart_problem& problem, std::vector<Uv>& uv, Chart_solve_report& report)
{
  const Mesh_index& index = *problem.mesh;
  const Border_target& border = *problem.border;
  // The border's shape is prescribed, its size is not: the vertex pinned for the scale keeps
  // u0 wherever it falls, which left a circle's disk hundreds of times the 3D area. Scaled to
  // the 3D area, as every chart of `parameterize` is. A uniform scale keeps equal coordinates
  // equal, so the rectangle's sides stay exactly straight. No CGAL semantics are lost: CGAL's
  // border parameterizers put the border on [0, 1]^2, but this map only takes their angles and
  // was never there.
  scale_to_3d_area(index, uv);
  if(border.kind == Border_kind::Circles)
    report.circle_deviation = max_circle_deviation(index, uv);
  if(border.kind != Border_kind::Prescribed_curvature)
    return;
  const std::vector<std::array<int, 2>> stretches = straight_stretches(index, border.curvature);
  make_rectangle_sides_exact(index, border.curvature, stretches, uv);
  const std::vector<int> flat = faces_on_a_straight_stretch(index, stretches);
  report.degenerate_faces = static_cast<int>(flat.size());
  report.flipped_faces = count_flipped_faces(index, uv) - count_flipped_faces_among(index, uv, flat);
}

/// Steps 1, 5 and 7 in the conformal class of `Metric`: its initial metric, the optimum, the
/// checked layout into `uv` (per vertex of an uncut disk, else per wedge of the cut).
template <class Metric, class Solver, class Energy>
Status solve_chart_in(const Chart_problem& problem, const Chart_options& options, const Chart_method& method,
                      const Energy& energy, Chart_solve_report& report, std::vector<Uv>& uv)
{
  using namespace CGAL::Surface_mesh_parameterization;
  auto stage = [&](const char* name) {
    if(method.progress)
      method.progress(name);
  };
  Stopwatch stopwatch;
  auto lap = [&stopwatch] { return stopwatch.lap(); };
  const Mesh_index& index = *problem.mesh;
  stage("metric");
  const Metric metric = make_metric<Metric>(index, problem.seams);
  report.metric = Metric::name;
  report.metric_summary = metric.summary();
  report.seconds_metric += lap();

  stage("optimum");
  Inverse_curvature_map<Solver, Metric> solver(index, metric, problem.is_free);
  Eigen::VectorXd u;
  Status status = entropy_optimum(problem, options, method, metric, solver, u, report);
  if constexpr(!std::is_same<Energy, Curvature_entropy>::value)
    if(status.ok())
      status = energy_optimum(problem, options, metric, solver, energy, u, report);
  report.seconds_optimum += lap();
  if(!status.ok())
    return status;

  stage("layout");
  Eigen::VectorXd k;
  std::vector<double> weights;
  Curvature_map<Metric>& curvature = solver.curvature_map();
  curvature.evaluate(u, k, &weights);
  report.metric_summary = curvature.metric().summary(); // with the flips made on the way
  report_curvature(problem, k, report);
  Layout_check check;
  status = problem.cut != nullptr ? lay_out_cut(problem, options, method, solver, report, uv, check)
                                  : lay_out_disk(problem, method, solver, k, weights, report, uv, check);
  if(!status.ok())
    return status;
  const Mesh_index& chart = problem.cut != nullptr ? problem.cut->disk : index;
  report.flipped_faces = std::max(check.flipped_faces, count_flipped_faces(chart, uv));
  if(problem.prescribes_border())
    finish_prescribed_border(problem, uv, report);
  report.max_layout_length_error = check.max_relative_length_error;
  const bool finite =
    std::all_of(uv.begin(), uv.end(), [](const Uv& p) { return std::isfinite(p[0]) && std::isfinite(p[1]); });
  if(finite)
    report.overlapping_border_edges = count_border_overlaps(chart, uv).crossing_pairs;
  report.seconds_layout += lap();
  if(!finite || report.flipped_faces > 0)
    return Status::failure(ERROR_NO_1_TO_1_MAPPING,
                           std::to_string(report.flipped_faces) + " faces are flipped in the layout");
  if(!(check.max_relative_length_error <= options.max_layout_length_error))
    return Status::failure(ERROR_NO_1_TO_1_MAPPING,
                           "the layout does not reproduce the metric (relative edge length error " +
                             std::to_string(check.max_relative_length_error) + ")");
  return Status::success();
}

/// Steps 5 and 7 of one chart: in the class of `Metric`, then, if that fails and the options
/// allow it, in the circle packing's, whose every u is valid, from a fresh report (the
/// seconds add up). When both fail, the first metric's reason is the one to act on and the
/// circle packing's follows it.
template <class Metric, class Solver, class Energy>
Status solve_chart(const Chart_problem& problem, const Chart_options& options, const Chart_method& method,
                   const Energy& energy, Chart_solve_report& report, std::vector<Uv>& uv)
{
  Status status = solve_chart_in<Metric, Solver>(problem, options, method, energy, report, uv);
  if constexpr(!std::is_same<Metric, Circle_packing_metric>::value)
  {
    if(status.ok() || !options.fall_back_to_circle_packing)
      return status;
    Chart_solve_report fresh;
    fresh.fallback_reason = std::string(Metric::name) + ": " + status.message;
    fresh.seconds_metric = report.seconds_metric;
    fresh.seconds_optimum = report.seconds_optimum;
    fresh.seconds_layout = report.seconds_layout;
    report = fresh;
    status = solve_chart_in<Circle_packing_metric, Solver>(problem, options, method, energy, report, uv);
    if(!status.ok())
      status.message = report.fallback_reason + "; then " + Circle_packing_metric::name + ": " + status.message;
  }
  return status;
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_CHART_SOLVER_H
