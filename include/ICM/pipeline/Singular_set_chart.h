// One component's steps 4 to 7 for a given singular set (pipeline/Surface_component.h): the
// cut through its cones, the Dirichlet problem of the set, the optimum and the layout of the
// cut surface with its checks, the overlap removal, and the figures that judge a map.

#ifndef ICM_PIPELINE_SINGULAR_SET_CHART_H
#define ICM_PIPELINE_SINGULAR_SET_CHART_H

#include <ICM/Status.h>
#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/pipeline/Chart_solver.h>
#include <ICM/pipeline/Component_cones.h>
#include <ICM/cut/Cut_graph.h>
#include <ICM/cut/Cut_mesh.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Overlap_removal.h>
#include <ICM/measures/Distortion.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>
#include <ICM/internal/Vector_geometry.h>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

namespace ICM {
namespace internal {

/// The cut: through every interior singular vertex that will carry curvature (the one free
/// vertex of a torus carries none), made before the optimum so that a metric with its own
/// triangulation keeps the seams as edges, and through (not to) the cones expected to take
/// an angle above 2 pi (`expected_curvature`: the prescribed or predicted curvature, NaN
/// where unknown). User seams are the cut as given.
inline Status cut_component(const Mesh_index& index, const std::vector<char>& is_singular,
                            const std::vector<double>& prescribed, const std::vector<double>& expected_curvature,
                            const std::vector<char>& user_seams, Chart_report& chart, std::vector<char>& seams,
                            Cut_mesh& cut, const std::vector<double>& path_lengths = {})
{
  const int nv = index.number_of_vertices();
  std::vector<char> is_cone(nv, 0);
  int interior_singular = 0;
  for(int v = 0; v < nv; ++v)
  {
    is_cone[v] = is_singular[v] && !index.is_boundary_vertex[v] && prescribed[v] != 0.0;
    interior_singular += is_singular[v] && !index.is_boundary_vertex[v];
  }
  if(index.number_of_boundary_loops() == 0 && index.euler_characteristic() == 0 && interior_singular == 1)
    std::fill(is_cone.begin(), is_cone.end(), 0);
  Cut_graph_options options;
  options.cone_curvatures = expected_curvature;
  options.path_lengths = path_lengths;
  Cut_graph_result graph =
    user_seams.empty() ? cut_graph(index, is_cone, options) : cut_graph_from_seams(index, user_seams, is_cone);
  if(!graph.ok())
    return graph.status;
  chart.seam_edges = graph.number_of_seam_edges;
  chart.homology_generators = graph.number_of_generators;
  cut = cut_mesh(index, graph.is_seam);
  seams = std::move(graph.is_seam);
  return cut.status;
}

/// The Dirichlet problem of the singular set S: u_S = u0_S, the other vertices flat, and
/// user cones with a fixed angle (`prescribed`, NaN where free) among the unknowns with
/// their target curvature. Every singular angle prescribed: the kernel of Delta is pinned at
/// vertex 0, whose equation then holds by Gauss-Bonnet (checked before).
inline Chart_problem singular_set_problem(const Mesh_index& index, const std::vector<char>& is_singular,
                                          const std::vector<double>& prescribed)
{
  const int nv = index.number_of_vertices();
  Chart_problem problem;
  problem.mesh = &index;
  problem.is_singular = is_singular;
  problem.is_free.resize(nv);
  problem.target = Eigen::VectorXd::Zero(nv);
  bool any_fixed = false;
  for(int v = 0; v < nv; ++v)
  {
    const bool fixed_angle = !std::isnan(prescribed[v]);
    problem.is_free[v] = !is_singular[v] || fixed_angle;
    if(fixed_angle)
      problem.target[v] = prescribed[v];
    any_fixed = any_fixed || !problem.is_free[v];
  }
  if(!any_fixed && nv > 0)
    problem.is_free[0] = 0;
  return problem;
}

/// A chart whose layout overlaps itself cut into pieces that do not.
inline Status remove_component_overlaps(const Mesh_index& index, Chart_report& chart, Cut_mesh& cut,
                                        std::vector<Uv>& uv)
{
  // A cone of angle above 2 pi (the negative cones of genus > 1) that the cut tree meets only
  // once lays its neighbourhood on two sheets, which takes a cut of its own: the limit grows
  // with the cones (genus 150 needs about 300; test_surfaces, HighGenusSlabsMapWithoutFlipsOrOverlaps).
  const int max_cuts = std::max(64, 2 * static_cast<int>(chart.cones.size()));
  const Overlap_removal removal = remove_overlaps(index, cut, uv, max_cuts);
  if(!cut.ok())
    return cut.status;
  chart.pieces = removal.pieces;
  chart.overlap_cut_edges = removal.cut_edges;
  chart.seam_edges += removal.cut_edges;
  chart.overlapping_border_edges = count_border_overlaps(cut.disk, uv).crossing_pairs;
  chart.seam_length_error = seam_length_error(cut, uv);
  return Status::success();
}

/// `Chart_report::seam_length`: the 3D length of the surface edges cut open, over the square
/// root of the 3D area.
inline double relative_seam_length(const Mesh_index& index, const Cut_mesh& cut)
{
  double length = 0, area = 0;
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(cut.disk_edges[e][1] >= 0)
    {
      const Point3 d = difference(index.points[index.edges[e][1]], index.points[index.edges[e][0]]);
      length += std::hypot(d[0], d[1], d[2]);
    }
  for(const auto& f : index.faces)
    area += triangle_area(index.points[f[0]], index.points[f[1]], index.points[f[2]]);
  return area > 0 ? length / std::sqrt(area) : 0.0;
}

/// Steps 4 to 7 of one component with the singular set `is_singular`: the cut (along
/// `path_lengths`' shortest paths when given), the optimum, the layout and its checks, into
/// `chart` (from `before`, the component's figures so far), `cut` and `uv`.
template <class Metric, class Solver, class Energy>
Status cut_and_solve(const Mesh_index& index, const std::vector<char>& is_singular,
                     const std::vector<double>& prescribed, const std::vector<double>& expected_curvature,
                     const std::vector<char>& user_seams, Eigen::VectorXd first_step,
                     const Surface_parameterization_options& options, Surface_parameterization_report& report,
                     const Chart_report& before, Chart_report& chart, Cut_mesh& cut, std::vector<Uv>& uv,
                     const Energy& energy, const Stage_progress& progress, const std::vector<double>& path_lengths = {})
{
  progress("cut", cones_stage_share);
  const Clock::time_point t = Clock::now();
  chart = before;
  Chart_problem problem = singular_set_problem(index, is_singular, prescribed);
  problem.first_step = std::move(first_step);
  if(const Status status = cut_component(index, is_singular, prescribed, expected_curvature, user_seams, chart,
                                         problem.seams, cut, path_lengths);
     !status.ok())
    return status;
  problem.cut = &cut;
  report.seconds_cut += seconds_since(t);

  progress("optimum", 0.4);
  const Status status = solve_chart<Metric, Solver>(problem, options, Chart_method(), energy, chart, uv);
  report.seconds_optimum += chart.seconds_metric + chart.seconds_optimum;
  report.seconds_layout += chart.seconds_layout;
  chart.raw_overlapping_border_edges = chart.overlapping_border_edges;
  return status;
}

/// How much more area distortion (area-weighted mean log^2 area) a map in one piece may have
/// than one that folds (which the overlap removal cuts into pieces), still to be kept: a map
/// with cones given up against the one with all its cones, or other cone angles' map. Measured on the
/// shared disks whose map folds with every automatic cone: pig 1.46, camelhead 1.79,
/// mannequin-devil 1.91, lion-head 2.05 times (one piece each, still 2 to 40 times less than
/// with no cone); a nearly closed surface (camel with one vertex star removed) would keep 3 of
/// 32 cones in one piece at an eq. 8 log area of 138, where all of them give 1.02 in pieces.
constexpr double fewer_cones_distortion_factor = 2.5;

/// The area-weighted mean of log^2 (UV area / 3D area) of the layout `uv` of `cut`, as the
/// report measures it (`measure_distortion_of_triangles`).
inline double mean_log_area_squared(const Mesh_index& index, const Cut_mesh& cut, const std::vector<Uv>& uv)
{
  std::vector<Point3> xyz;
  std::vector<Uv> corner_uv;
  xyz.reserve(3 * index.faces.size());
  corner_uv.reserve(3 * index.faces.size());
  for(std::size_t f = 0; f < index.faces.size(); ++f)
    for(int k = 0; k < 3; ++k)
    {
      xyz.push_back(index.points[index.faces[f][k]]);
      corner_uv.push_back(uv[cut.disk.faces[f][k]]);
    }
  return measure_distortion_of_triangles(xyz, corner_uv).log_area_distortion_area_weighted;
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_SINGULAR_SET_CHART_H
