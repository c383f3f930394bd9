// One connected component through `ICM::parameterize` (parameterize.h): on the surface as
// given its cones and the optimum of its metric, on the surface cut open the layout of that
// metric and its checks, then the overlap removal; and the charts packed side by side.

#ifndef ICM_INTERNAL_SURFACE_COMPONENT_H
#define ICM_INTERNAL_SURFACE_COMPONENT_H

#include <ICM/Status.h>
#include <ICM/Surface_parameterization_options.h>
#include <ICM/cones/Singular_vertices.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/cut/Cut_graph.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Chart_packing.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Overlap_removal.h>
#include <ICM/layout/Unflip.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {
namespace internal {

/// The progress of one component: `start` of the whole done before it, `span` its share.
struct Stage_progress
{
  const std::function<void(const std::string&, double)>* callback = nullptr;
  double start = 0, span = 1;
  void operator()(const char* stage, double within) const
  {
    if(callback != nullptr && *callback)
      (*callback)(stage, start + span * within);
  }
};

/// Whether the user's cones are interior vertices of `mesh` with a positive angle (or a free
/// one), and the user's seams edges of `mesh` off its border. Membership is found by
/// comparison only: a null, foreign or stale descriptor is refused, never dereferenced.
template <class TriangleMesh>
Status check_user_cones_and_seams(
  const TriangleMesh& mesh,
  const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones,
  const std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& user_seams)
{
  std::size_t cones_in_mesh = 0;
  for(auto v : vertices(mesh))
    cones_in_mesh += user_cones.count(v);
  if(cones_in_mesh != user_cones.size())
    return Status::wrong_parameter(user_cones.count(boost::graph_traits<TriangleMesh>::null_vertex())
                                     ? "a user cone is the null vertex"
                                     : "a user cone is not a vertex of this mesh");
  for(const auto& [v, curvature] : user_cones)
  {
    if(is_border(v, mesh))
      return Status::wrong_parameter("a user cone is a boundary vertex (border vertices are singular already; "
                                     "prescribe interior cones only)");
    if(!std::isnan(curvature) && !(curvature < 2 * M_PI))
      return Status::wrong_parameter("a user cone angle must be positive (curvature " + std::to_string(curvature) +
                                     " >= 2 pi)");
  }
  if(user_seams.empty())
    return Status::success();
  const auto mesh_halfedges = sorted_halfedges(mesh);
  for(auto e : user_seams)
  {
    if(!std::binary_search(mesh_halfedges.begin(), mesh_halfedges.end(), halfedge(e, mesh)))
      return Status::wrong_parameter("a user seam is not an edge of this mesh (or is the null edge)");
    if(is_border(e, mesh))
      return Status::wrong_parameter("a user seam is a border edge (the border is cut already)");
  }
  return Status::success();
}

/// The metric of class `Metric` for `index`; a metric that flips its own triangulation keeps
/// `fixed_edges` (the seams) as edges.
template <class Metric>
Metric make_metric(const Mesh_index& index, const std::vector<char>& fixed_edges)
{
  if constexpr(std::is_constructible<Metric, const Mesh_index&, const std::vector<char>&>::value)
    return Metric(index, fixed_edges);
  else
    return Metric(index);
}

/// The entropy optimum for the singular set S (u_S = u0_S, K_N = 0) in the class of `Metric`,
/// then, for another energy, its minimum over the same S from there; with the lengths and
/// angles at the result on the metric's triangulation: the mesh's, or (`has_triangulation`)
/// the metric's own intrinsic one, whose seam edges are the mesh's. `prescribed` (curvature
/// per vertex, NaN where none) are user cones with a fixed angle: they join the unknowns
/// with their target curvature.
template <class Metric, class Solver>
struct Surface_optimum
{
  static constexpr bool has_triangulation = Curvature_map<Metric>::has_intrinsic_triangulation;
  Eigen::VectorXd u, k;
  std::vector<double> lengths;
  std::vector<Triangle_angles> angles;
  Mesh_index triangulation; ///< only when `has_triangulation`
  Newton_report newton;
  Curvature_space_report energy; ///< empty when the energy is the entropy

  template <class Energy>
  Surface_optimum(const Mesh_index& index, const std::vector<char>& is_seam,
                  const std::vector<char>& is_singular, const std::vector<double>& prescribed,
                  const Surface_parameterization_options& options, const Energy& energy_policy)
  {
    const int nv = index.number_of_vertices();
    std::vector<char> is_free(nv);
    Eigen::VectorXd target = Eigen::VectorXd::Zero(nv);
    bool any_fixed = false;
    for(int v = 0; v < nv; ++v)
    {
      const bool fixed_angle = !std::isnan(prescribed[v]);
      is_free[v] = !is_singular[v] || fixed_angle;
      if(fixed_angle)
        target[v] = prescribed[v];
      any_fixed = any_fixed || !is_free[v];
    }
    // Every singular angle prescribed: the kernel of Delta is pinned at vertex 0, whose
    // equation then holds by Gauss-Bonnet (checked by the caller).
    if(!any_fixed && nv > 0)
      is_free[0] = 0;
    const Metric metric = make_metric<Metric>(index, is_seam);
    Inverse_curvature_map<Solver, Metric> solver(index, metric, is_free);
    u = metric.u0;
    newton = solver.solve(target, u, options.newton);
    // Another energy has something to choose when S has two vertices or more (the optimizer
    // keeps the mean of u_S). It keeps its best metric when it stops early.
    if constexpr(!std::is_same<Energy, Curvature_entropy>::value)
    {
      if(newton.converged && std::count(is_free.begin(), is_free.end(), 0) >= 2)
      {
        energy = minimize_energy_on_singular_values(solver, index, metric, energy_policy, u, options.energy, target);
        if(energy.energy_history.empty())
        {
          newton.converged = false;
          newton.message = std::string(energy_name<Energy>()) + " energy: " + energy.message;
          return;
        }
        // The solver's state at the result, which the optimizer moved by a constant. That
        // result is flat to the Newton tolerance; a step or two more take it to rounding, as
        // the entropy's Newton ends, so that the cut layout closes up as well (sphere966,
        // log area: seam sides 2.4e-9 apart at 5e-11 rad, 1e-13 after one more step).
        const int before = newton.iterations + energy.newton_iterations;
        Newton_options finish = options.newton;
        finish.tolerance = 1e-3 * options.newton.tolerance;
        finish.max_iterations = 3;
        newton = solver.solve(target, u, finish);
        newton.iterations += before;
        newton.converged =
          !newton.residual_history.empty() && newton.residual_history.back() <= options.newton.tolerance;
      }
    }
    // The solver holds the curvature, lengths and radii of its last accepted u.
    k = solver.curvature();
    lengths = solver.curvature_map().lengths();
    angles = solver.curvature_map().face_angles();
    if constexpr(has_triangulation)
      triangulation = solver.curvature_map().mesh_index();
  }
};

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
    if(turn < 1e-6 && std::hypot(p[0] - q[0], p[1] - q[1]) <= 1e-6 * std::hypot(p[0], p[1]) + 1e-300)
      twins[w] = a;
  }
  return twins;
}

/// The optimum in the class of `Metric` for the singular set and its layout on `cut`,
/// checked: steps 5 and 7 of one component.
template <class Metric, class Solver, class Energy>
Status optimum_and_layout(const Mesh_index& index, const std::vector<char>& is_seam,
                               const std::vector<char>& is_singular, const std::vector<double>& prescribed,
                               const Cut_mesh& cut, const Surface_parameterization_options& options,
                               Surface_parameterization_report& report, Chart_report& chart,
                               std::vector<Uv>& uv, const Energy& energy)
{
  using namespace CGAL::Surface_mesh_parameterization;
  using Clock = std::chrono::steady_clock;
  const int nv = index.number_of_vertices();
  Clock::time_point t = Clock::now();
  Surface_optimum<Metric, Solver> optimum(index, is_seam, is_singular, prescribed, options, energy);
  chart.metric = Metric::name;
  chart.newton_iterations = optimum.newton.iterations;
  chart.energy_iterations = optimum.energy.iterations;
  chart.initial_energy = optimum.energy.initial_energy;
  chart.final_energy = optimum.energy.final_energy;
  chart.energy_message = optimum.energy.message;
  report.seconds_optimum += seconds_since(t);
  if(!optimum.newton.converged)
    return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, optimum.newton.message);
  const Eigen::VectorXd& k = optimum.k;
  for(int v = 0; v < nv; ++v)
    if(is_singular[v] && !index.is_boundary_vertex[v])
    {
      chart.cones.push_back(v);
      chart.cone_curvatures.push_back(k[v]);
    }
    else if(!is_singular[v])
      chart.max_curvature_error = std::max(chart.max_curvature_error, std::abs(k[v]));

  // On the cut: the surface's flat metric laid out, both sides of a seam one length. An
  // intrinsic triangulation is cut along the same seams and laid out, and each wedge of the
  // mesh's cut takes the UV of the same wedge there.
  t = Clock::now();
  Cut_mesh intrinsic_cut;
  if(optimum.has_triangulation)
  {
    intrinsic_cut = cut_mesh(optimum.triangulation, is_seam);
    if(!intrinsic_cut.ok())
      return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, "the intrinsic triangulation: " + intrinsic_cut.status.message);
  }
  const Cut_mesh& laid = optimum.has_triangulation ? intrinsic_cut : cut;
  std::vector<double> disk_lengths(laid.disk.number_of_edges());
  for(int d = 0; d < laid.disk.number_of_edges(); ++d)
    disk_lengths[d] = optimum.lengths[laid.surface_edge[d]];
  uv = layout_by_propagation(laid.disk, disk_lengths, optimum.angles);
  const Layout_check check = check_layout(laid.disk, disk_lengths, uv);
  chart.flipped_faces = check.flipped_faces;
  if(optimum.has_triangulation)
  {
    const std::vector<int> match = match_wedges(index, cut, optimum.triangulation, intrinsic_cut, is_seam);
    if(match.empty())
      return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, "the wedges of the intrinsic triangulation do not match the mesh's");
    std::vector<Uv> intrinsic_uv;
    intrinsic_uv.swap(uv);
    uv.resize(match.size());
    for(std::size_t w = 0; w < match.size(); ++w)
      uv[w] = intrinsic_uv[match[w]];
    if(check.flipped_faces == 0 && count_flipped_faces(cut.disk, uv) > 0)
    {
      // A wedge may move when its vertex is on no seam, or with its twin across a seam
      // through a flat vertex. Not the one wedge of a cone where a seam ends: both sides of
      // its seam edge start there, and moving it would give them different lengths.
      const std::vector<int> seam_degree = seam_degrees(index, is_seam);
      const std::vector<Seam_twin> twins = seam_twins(index, cut, uv);
      std::vector<char> is_movable(cut.surface_vertex.size());
      for(std::size_t w = 0; w < is_movable.size(); ++w)
        is_movable[w] = seam_degree[cut.surface_vertex[w]] == 0 || twins[w].wedge >= 0;
      chart.moved_vertices = unflip_by_moving_vertices(cut.disk, uv, is_movable, twins);
    }
    chart.flipped_faces = std::max(check.flipped_faces, count_flipped_faces(cut.disk, uv));
  }
  chart.max_layout_length_error = check.max_relative_length_error;
  chart.seam_length_error = seam_length_error(cut, uv);
  bool finite = true;
  for(const Uv& p : uv)
    finite = finite && std::isfinite(p[0]) && std::isfinite(p[1]);
  if(finite)
    chart.overlapping_border_edges = count_border_overlaps(cut.disk, uv).crossing_pairs;
  report.seconds_layout += seconds_since(t);
  if(!finite || chart.flipped_faces > 0)
    return Status::failure(ERROR_NO_1_TO_1_MAPPING, std::to_string(chart.flipped_faces) + " faces are flipped in the layout");
  if(!(check.max_relative_length_error <= options.max_layout_length_error))
    return Status::failure(ERROR_NO_1_TO_1_MAPPING, "the layout does not reproduce the metric (relative edge length error " +
                                                      std::to_string(check.max_relative_length_error) + ")");
  return Status::success();
}

/// One component: cones, optimum, cut, layout, checks. `uv` receives one UV per wedge of
/// `cut.disk`. `user_seams` (per edge; empty: none) are taken as the cut as given, their ends
/// and branch points singular with a free angle, and no cone is added.
template <class Metric, class Solver, class Energy>
Status parameterize_component(const Mesh_index& index, const std::vector<char>& is_user_cone,
                                   const std::vector<double>& prescribed, const std::vector<char>& user_seams,
                                   const Surface_parameterization_options& options,
                                   Surface_parameterization_report& report, Chart_report& chart,
                                   Cut_mesh& cut, std::vector<Uv>& uv, const Energy& energy,
                                   const Stage_progress& progress = Stage_progress())
{
  using namespace CGAL::Surface_mesh_parameterization;
  using Clock = std::chrono::steady_clock;
  const int nv = index.number_of_vertices();
  const bool closed = index.number_of_boundary_loops() == 0;
  const int chi = index.euler_characteristic();

  // On the surface: the singular set.
  progress("cones", 0.0);
  Clock::time_point t = Clock::now();
  std::vector<char> is_singular(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  int user_cones = 0, free_user_cones = 0;
  for(int v = 0; v < nv; ++v)
    if(is_user_cone[v])
    {
      is_singular[v] = 1;
      ++user_cones;
      free_user_cones += std::isnan(prescribed[v]);
    }
  if(closed && user_cones > 0 && free_user_cones == 0)
  {
    double sum = 0;
    for(int v = 0; v < nv; ++v)
      if(is_user_cone[v])
        sum += prescribed[v];
    if(std::abs(sum - 2 * M_PI * chi) > 1e-6)
      return Status::wrong_parameter("the cone curvatures sum to " + std::to_string(sum) + ", Gauss-Bonnet needs 2 pi chi = " +
             std::to_string(2 * M_PI * chi) + " (chi = " + std::to_string(chi) + ")");
  }
  const bool has_user_seams = !user_seams.empty();
  if(has_user_seams)
  {
    // A seam through a flat vertex passes it (two seam edges); anywhere else the two sides
    // meet at an angle the flat metric cannot have, so the vertex must be singular.
    const std::vector<int> seam_degree = seam_degrees(index, user_seams);
    for(int v = 0; v < nv; ++v)
      if(seam_degree[v] != 0 && seam_degree[v] != 2)
        is_singular[v] = 1;
  }
  if(options.automatic_cones && options.cones.max_cones > 0 && !has_user_seams)
  {
    const Circle_packing_metric packing(index);
    const Metric metric = make_metric<Metric>(index, std::vector<char>(index.number_of_edges(), 0));
    bool wants_cones = closed;
    if(!closed)
    {
      // A border: cones only when the free-boundary optimum is extreme, judged in the
      // class the optimum will be computed in (the circle packing's optimum is milder:
      // three_peaks reaches u - u0 = -5.0 in the mesh's class, -2.6 in the packing's).
      Eigen::VectorXd u;
      Newton_report free = free_boundary_optimum<Solver>(index, metric, is_singular, u, options.newton);
      double depth = free.converged ? (u - metric.u0).cwiseAbs().maxCoeff() : 0;
      if(!free.converged && options.fall_back_to_circle_packing)
      {
        free = free_boundary_optimum<Solver>(index, packing, is_singular, u, options.newton);
        depth = (u - packing.u0).cwiseAbs().maxCoeff();
      }
      wants_cones = !free.converged || depth > options.border_max_log_scale;
    }
    if(wants_cones)
    {
      std::vector<int> seeds;
      for(int v = 0; v < nv; ++v)
        if(is_singular[v] && !index.is_boundary_vertex[v])
          seeds.push_back(v);
      // Seeds from Algorithm 3's ranking. Genus 0 needs two cones (one would carry 4 pi) but
      // starts from the `initial_cones` strongest minima: with two, the first optimum needs
      // conformal factors of e^-30 and many capped Newton steps (bunny00: 6.2 s of cone
      // placement from 2 seeds, 1.9 s from 8). Genus g > 1 starts with 2g - 2 negative
      // cones at the maxima, so that no single cone carries all of 2 pi chi.
      const int needed = !closed ? 0 : chi > 0 ? std::max(2, options.initial_cones) : chi == 0 ? 1 : -chi;
      if(static_cast<int>(seeds.size()) < needed)
      {
        std::string why;
        std::vector<int> minima = curvature_minima<Solver>(index, packing, why, chi < 0);
        for(int v : minima)
          if(static_cast<int>(seeds.size()) < needed && !is_singular[v])
            seeds.push_back(v);
        const int minimum = chi > 0 ? 2 : 1;
        for(int v = 0; static_cast<int>(seeds.size()) < minimum && v < nv; ++v)
          if(std::find(seeds.begin(), seeds.end(), v) == seeds.end())
            seeds.push_back(v); // a surface with too few minima (a tiny closed mesh)
      }
      // Placed in the class the optimum is computed in (sphere966: mean log^2 area 0.22 with
      // 10 cones placed there, 0.58 with 8 placed by the circle packing's conformal factor).
      Cone_selection selection = greedy_cones<Solver>(index, metric, seeds, options.cones);
      if(!selection.ok() && options.fall_back_to_circle_packing)
        selection = greedy_cones<Solver>(index, packing, seeds, options.cones);
      if(!selection.ok())
        return Status::failure(ERROR_CANNOT_SOLVE_LINEAR_SYSTEM, selection.message);
      for(int v : selection.cones)
        is_singular[v] = 1;
    }
  }
  if(closed && chi > 0 && std::count(is_singular.begin(), is_singular.end(), 1) < 2)
    return Status::wrong_parameter("a closed genus-0 surface needs at least two cones (automatic cones are off)");
  report.seconds_cones += seconds_since(t);

  // The cut: through every interior singular vertex that will carry curvature (the one
  // free vertex of a torus carries none), made before the optimum so that a metric with
  // its own triangulation keeps the seams as edges.
  progress("cut", 0.35);
  t = Clock::now();
  std::vector<char> is_cone(nv, 0);
  int interior_singular = 0;
  for(int v = 0; v < nv; ++v)
  {
    is_cone[v] = is_singular[v] && !index.is_boundary_vertex[v] && prescribed[v] != 0.0;
    interior_singular += is_singular[v] && !index.is_boundary_vertex[v];
  }
  if(closed && chi == 0 && interior_singular == 1)
    std::fill(is_cone.begin(), is_cone.end(), 0);
  const Cut_graph_result graph =
    has_user_seams ? cut_graph_from_seams(index, user_seams, is_cone) : cut_graph(index, is_cone);
  if(!graph.ok())
    return graph.status;
  chart.seam_edges = graph.number_of_seam_edges;
  chart.homology_generators = graph.number_of_generators;
  cut = cut_mesh(index, graph.is_seam);
  if(!cut.ok())
    return cut.status;
  report.seconds_cut += seconds_since(t);

  // On the surface: the optimum in the class of `Metric`; on the cut: its layout. If either
  // fails, both again in the class of the circle packing, from the chart as it was.
  progress("optimum", 0.4);
  const Chart_report before_optimum = chart;
  Status failure =
    optimum_and_layout<Metric, Solver>(index, graph.is_seam, is_singular, prescribed, cut, options,
                                       report, chart, uv, energy);
  if(!failure.ok() && !std::is_same<Metric, Circle_packing_metric>::value &&
     options.fall_back_to_circle_packing)
  {
    const std::string reason = std::string(Metric::name) + ": " + failure.message;
    chart = before_optimum;
    failure = optimum_and_layout<Circle_packing_metric, Solver>(index, graph.is_seam, is_singular, prescribed,
                                                                cut, options, report, chart, uv, energy);
    chart.fallback_reason = reason;
  }
  chart.raw_overlapping_border_edges = chart.overlapping_border_edges;
  if(failure.ok() && options.remove_overlaps && chart.overlapping_border_edges > 0)
  {
    progress("overlaps", 0.9);
    t = Clock::now();
    const Overlap_removal removal = remove_overlaps(index, cut, uv);
    if(!cut.ok())
      return cut.status;
    chart.pieces = removal.pieces;
    chart.overlap_cut_edges = removal.cut_edges;
    chart.seam_edges += removal.cut_edges;
    chart.overlapping_border_edges = count_border_overlaps(cut.disk, uv).crossing_pairs;
    chart.seam_length_error = seam_length_error(cut, uv);
    report.seconds_layout += seconds_since(t);
  }
  return failure;
}


/// The normalisation of the corners of every face of `mesh`: one frame for all components.
template <class TriangleMesh>
Normalisation normalisation_of_corners(const TriangleMesh& mesh)
{
  std::vector<std::array<double, 3>> corner_points;
  const auto vpm = get(CGAL::vertex_point, mesh);
  for(auto f : faces(mesh))
    for(auto v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
    {
      const auto& p = get(vpm, v);
      corner_points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
  return normalisation_of(corner_points);
}

/// The user's cones and seams on the component `index` (whose vertices are `vertices`):
/// per vertex whether it is a user cone and its prescribed curvature (NaN: free), and per
/// edge whether it is a user seam (empty when the component has none).
template <class TriangleMesh, class SeamMap>
void component_cones_and_seams(
  const TriangleMesh& mesh, const Mesh_index& index,
  const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
  const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones,
  const SeamMap& is_user_seam, bool any_user_seam, std::vector<char>& is_user_cone, std::vector<double>& prescribed,
  std::vector<char>& component_seams)
{
  is_user_cone.assign(index.number_of_vertices(), 0);
  prescribed.assign(index.number_of_vertices(), std::nan(""));
  for(int v = 0; v < index.number_of_vertices(); ++v)
  {
    const auto it = user_cones.find(vertices[v]);
    if(it != user_cones.end())
    {
      is_user_cone[v] = 1;
      prescribed[v] = it->second;
    }
  }
  component_seams.clear();
  if(!any_user_seam)
    return;
  component_seams.assign(index.number_of_edges(), 0);
  for(int e = 0; e < index.number_of_edges(); ++e)
    component_seams[e] =
      get(is_user_seam, edge(halfedge(vertices[index.edges[e][0]], vertices[index.edges[e][1]], mesh).first, mesh));
  if(std::find(component_seams.begin(), component_seams.end(), 1) == component_seams.end())
    component_seams.clear();
}

/// The charts side by side, each at its 3D scale (UV area = 3D area, normalised units), and
/// their UVs written per corner of `mesh` in its units.
template <class TriangleMesh, class HalfedgeUVMap>
void pack_and_write_charts(
  const TriangleMesh& mesh,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>>& chart_faces,
  const std::vector<Cut_mesh>& cuts, std::vector<std::vector<Uv>>& chart_uvs, const Normalisation& normalisation,
  HalfedgeUVMap uv_map)
{
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  const std::size_t components = chart_uvs.size();
  std::vector<Chart_box> boxes;
  for(std::size_t c = 0; c < components; ++c)
  {
    const Mesh_index& disk = cuts[c].disk;
    double uv_area = 0, area = 0;
    for(const auto& f : disk.faces)
    {
      const Uv &a = chart_uvs[c][f[0]], &b = chart_uvs[c][f[1]], &d = chart_uvs[c][f[2]];
      uv_area += 0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
      area += triangle_area(disk.points[f[0]], disk.points[f[1]], disk.points[f[2]]);
    }
    const double scale = std::sqrt(area / uv_area);
    for(Uv& p : chart_uvs[c])
      p = {p[0] * scale, p[1] * scale};
    boxes.push_back(chart_bounding_box(chart_uvs[c]));
  }
  const std::vector<Uv> offsets = shelf_pack(boxes);

  using Uv_point = typename boost::property_traits<HalfedgeUVMap>::value_type;
  for(std::size_t c = 0; c < components; ++c)
    for(std::size_t f = 0; f < chart_faces[c].size(); ++f)
    {
      int corner = 0;
      for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(chart_faces[c][f], mesh), mesh))
      {
        const Uv& p = chart_uvs[c][cuts[c].disk.faces[f][corner++]];
        const Uv_point q(normalisation.scale * (p[0] + offsets[c][0]),
                         normalisation.scale * (p[1] + offsets[c][1]));
        put(uv_map, h, q);
        // The border halfedge into the same vertex, if any, shares this corner's wedge when
        // it is the corner next to the border.
        const halfedge_descriptor out = opposite(next(h, mesh), mesh);
        if(is_border(out, mesh))
          put(uv_map, prev(out, mesh), q);
      }
    }
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_SURFACE_COMPONENT_H
