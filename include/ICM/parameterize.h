// One call for any triangle mesh: `ICM::parameterize(mesh, uv_map, options)`.
//
// CGAL's `Parameterizer_3` concept takes one border halfedge and writes one UV per vertex, so
// it only fits a disk. This entry point takes any triangle mesh (closed, any genus, holes,
// several components) and writes one UV per corner (a halfedge map, as CGAL's `Seam_mesh`
// examples use). Per connected component, the two levels of the pipeline stay apart:
//   on the surface as given   index -> cones (Singular_vertices.h) -> entropy optimum with the
//                             cones singular, in the metric's class (Optimal_metric.h), or
//                             the minimum of another energy over the same singular set
//                             (Curvature_space_optimizer.h)
//   on the surface cut open   cut graph and wedges (Cut_graph.h) -> layout of the surface's
//                             flat metric, both sides of a seam one length (Layout.h) ->
//                             checks: orientation, lengths, seams, border overlaps
// and the charts are then packed side by side (Chart_packing.h). See doc/surfaces.md.

#ifndef ICM_PARAMETERIZE_H
#define ICM_PARAMETERIZE_H

#include <ICM/Border_overlaps.h>
#include <ICM/Chart_packing.h>
#include <ICM/Circle_packing_metric.h>
#include <ICM/Curvature_map.h>
#include <ICM/Curvature_space_optimizer.h>
#include <ICM/Cut_graph.h>
#include <ICM/Energies.h>
#include <ICM/Inverse_curvature_map.h>
#include <ICM/Intrinsic_delaunay_metric.h>
#include <ICM/Layout.h>
#include <ICM/Overlap_removal.h>
#include <ICM/Singular_vertices.h>
#include <ICM/Status.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Option_checks.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
// Declared only: Seam_mesh.h itself must come after the BGL header of the mesh under it.
template <class TM, class SEM, class SVM>
class Seam_mesh;
} // namespace CGAL

namespace ICM {

/// Options of `ICM::parameterize`.
struct Surface_parameterization_options
{
  /// Interior cones chosen automatically (`greedy_cones`) on closed surfaces, and on
  /// surfaces with a border whose free-boundary optimum is extreme. False: only the border
  /// and the user's cones are singular (a torus then needs none; a closed genus-0 surface
  /// needs user cones).
  bool automatic_cones = true;
  Cone_options cones;
  /// Cones a closed genus-0 surface starts from (Algorithm 3's strongest minima) before the
  /// greedy placement adds more; 8 is BFF's default count.
  int initial_cones = 8;
  /// A surface with a border gets automatic interior cones only when its free-boundary
  /// optimum changes some area by more than exp(2 * this) ~ 55 (measured max |u - u0| in
  /// the default metric: three_peaks 5.0, lion-head 4.5, camelhead 6.8, mannequin-devil
  /// 7.4, horse 2.2; mushroom 1.8, nefertiti 0.7); an ordinary disk keeps its free
  /// boundary and no seam. At 2 rather than 4, three more shared meshes get cones, with no
  /// flipped face nor overlap (mean log^2 area / QC / pieces after overlap removal): horse
  /// 0.296 / 1.033 / 9 -> 0.115 / 1.026 / 9 (13 cones), pig 0.910 / 1.248 / 1 -> 0.170 /
  /// 1.149 / 4 (23), mech-holes-shark 0.079 / 1.014 / 1 -> 0.033 / 1.012 / 2 (4).
  double border_max_log_scale = 2.0;
  Newton_options newton;
  /// The optimizer of an energy other than the entropy (`parameterize`'s `energy`), run from
  /// the entropy optimum over the same singular set: the border and the cones.
  Curvature_space_options energy;
  bool fall_back_to_circle_packing = true;
  /// A layout whose edge lengths differ from the metric's by more than this fails. The
  /// propagation across a long cut disk loses more digits on slivers than on a plain disk
  /// (mech-holes-shark: 2.4e-6 on its CAD slivers, while its seams agree to 6e-13).
  double max_layout_length_error = 1e-5;
  /// A chart whose layout overlaps itself is cut into pieces that do not (`remove_overlaps`);
  /// false keeps the raw optimum and only counts its overlaps.
  bool remove_overlaps = true;
  /// Called, when set, at the start of each stage of each component ("cones", "cut",
  /// "optimum", "overlaps") and once at the end ("done"), with the share of the work done so
  /// far, 0 to 1 (components weighted by their faces; within one, a fixed share per stage).
  /// For a progress line on long runs; it must not throw.
  std::function<void(const std::string& stage, double fraction)> progress;
};

/// Whether every field of `options` is in range (`ERROR_WRONG_PARAMETER` naming the first
/// that is not).
inline Status check_options(const Surface_parameterization_options& options)
{
  return internal::Option_checks()
    .nested(check_options(options.cones))
    .at_least("initial_cones", options.initial_cones, 0)
    .real("border_max_log_scale", options.border_max_log_scale, 0, true)
    .nested(check_options(options.newton))
    .nested(check_options(options.energy))
    .real("max_layout_length_error", options.max_layout_length_error, 0, false)
    .status();
}

/// What `ICM::parameterize` did to one connected component.
struct Chart_report
{
  int vertices = 0, faces = 0, boundary_loops = 0, genus = 0;
  std::vector<int> cones;              ///< interior singular vertices (component indices)
  std::vector<double> cone_curvatures; ///< their curvature 2 pi - angle sum, same order
  int seam_edges = 0, homology_generators = 0;
  std::string metric, fallback_reason;
  int newton_iterations = 0;
  /// An energy other than the entropy: its optimizer's steps, E at the entropy optimum and
  /// at the result (NaN for an energy without a value), and why it stopped early (empty when
  /// it converged).
  int energy_iterations = 0;
  double initial_energy = std::nan(""), final_energy = std::nan("");
  std::string energy_message;
  double max_curvature_error = 0;      ///< max |k| over non-singular vertices
  int flipped_faces = 0;
  int moved_vertices = 0;              ///< see `Parameterization_report::moved_vertices`
  int overlapping_border_edges = 0;    ///< pairs of border edges of the chart that cross
  /// Overlap removal: pairs of border edges that crossed in the raw layout, the pieces the
  /// chart was cut into (1: none) and the seam edges that cut added.
  int raw_overlapping_border_edges = 0;
  int pieces = 1, overlap_cut_edges = 0;
  double max_layout_length_error = 0;
  double seam_length_error = 0;        ///< max relative difference of a seam's two sides
};

/// What `ICM::parameterize` did: the status, the reason of a failure, one `Chart_report` per
/// connected component and the seconds of each stage (doc/report.md).
struct Surface_parameterization_report
{
  /// `NOT_RUN` until filled by `ICM::parameterize`.
  CGAL::Surface_mesh_parameterization::Error_code status = NOT_RUN;
  std::string message = "not run";     ///< empty on success, else the reason
  std::vector<Chart_report> charts;    ///< one per connected component
  double seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_total = 0;
};

/// An energy's figures over every component of a report: the optimizer's steps summed, E at
/// the entropy optimum and at the result as the components' means weighted by their faces (a
/// component that optimised nothing, whose E is NaN, adds nothing), and the first reason an
/// optimizer stopped early.
struct Energy_summary
{
  int iterations = 0;
  double initial_energy = 0, final_energy = 0;
  std::string message;
};

inline Energy_summary energy_summary(const Surface_parameterization_report& report)
{
  Energy_summary summary;
  double faces = 0;
  for(const Chart_report& c : report.charts)
    faces += c.faces;
  for(const Chart_report& c : report.charts)
  {
    summary.iterations += c.energy_iterations;
    if(std::isfinite(c.initial_energy))
    {
      summary.initial_energy += c.faces / faces * c.initial_energy;
      summary.final_energy += c.faces / faces * c.final_energy;
    }
    if(summary.message.empty())
      summary.message = c.energy_message;
  }
  return summary;
}

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
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
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
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
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


} // namespace internal

/// \brief Parameterizes any triangle mesh: every connected component is cut into a disk
/// through its cones (chosen automatically, or the user's), laid out with the minimum of the
/// curvature entropy in the class of `Metric` (or of `Energy` over the same border and
/// cones), and the charts are packed side by side at their 3D scale.
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam HalfedgeUVMap a writable property map from `halfedge_descriptor` to a 2D point:
///         the UV of the corner at `target(h)` in `face(h)` (border halfedges get the UV of
///         the corner across `next(h)`). It serves directly as the UV map of a
///         `CGAL::Seam_mesh` whose seams are `seam_edges`.
/// \tparam Metric a model of `Metric` (doc/concepts.md); `CGAL::Default` is `Default_metric`
/// \tparam Energy a model of `Energy` (Energies.h, doc/energies.md); `CGAL::Default` is
///         `Curvature_entropy`. Another energy is minimised over the conformal maps with the
///         singular set the entropy's run chose (the border and the cones; a user cone's
///         fixed angle stays fixed), from the entropy optimum, by
///         `minimize_energy_on_singular_values` with `options.energy`
/// \param mesh the triangle mesh; it is not modified
/// \param uv_map receives one UV per corner (see `HalfedgeUVMap`)
/// \param options cones, Newton, fallback and overlap options (doc/parameterizer.md)
/// \param user_cones vertices that must be singular: with a curvature 2 pi - angle, or NaN
///        to leave the angle to the optimum (Thm 3.5)
/// \param seam_edges if not null, receives the seam edges of every chart
/// \param user_seams the user's own cut (as a CGAL selection file gives it): a component with
///        any of these edges is cut along exactly them (they must cut it into one disk through
///        every user cone), their ends and branch points become singular with a free angle
///        and no automatic cone is added; a component without any is cut as usual
/// \param energy the energy's own settings (for example `Log_area_distortion`'s weighting)
/// \returns the status, the reason of a failure and one `Chart_report` per component
///          (doc/report.md)
template <class Metric_ = CGAL::Default, class SparseSolver = CGAL::Default, class Energy_ = CGAL::Default,
          class TriangleMesh, class HalfedgeUVMap>
Surface_parameterization_report parameterize(
  const TriangleMesh& mesh, HalfedgeUVMap uv_map,
  const Surface_parameterization_options& options = Surface_parameterization_options(),
  const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones = {},
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>* seam_edges = nullptr,
  const std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& user_seams = {},
  const typename CGAL::Default::Get<Energy_, Curvature_entropy>::type& energy =
    typename CGAL::Default::Get<Energy_, Curvature_entropy>::type())
{
  using namespace CGAL::Surface_mesh_parameterization;
  using Metric = typename CGAL::Default::Get<Metric_, Default_metric>::type;
  using Solver = typename CGAL::Default::Get<SparseSolver, Default_sparse_solver>::type;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();

  Surface_parameterization_report report;
  auto finish = [&](Error_code code, const std::string& why) {
    report.status = code;
    report.message = why;
    report.seconds_total = std::chrono::duration<double>(Clock::now() - start).count();
    return report;
  };
  if(const Status checked = check_options(options); !checked.ok())
    return finish(checked.code, checked.message);
  if(faces(mesh).empty())
    return finish(ERROR_EMPTY_MESH, "the mesh has no faces");
  if(const Status checked = internal::check_user_cones_and_seams(mesh, user_cones, user_seams); !checked.ok())
    return finish(checked.code, checked.message);

  // Components, each with a seed face.
  auto component_of = get(CGAL::dynamic_face_property_t<std::size_t>(), mesh);
  const std::size_t components = CGAL::Polygon_mesh_processing::connected_components(mesh, component_of);
  std::vector<face_descriptor> seeds(components, boost::graph_traits<TriangleMesh>::null_face());
  for(face_descriptor f : faces(mesh))
    if(seeds[get(component_of, f)] == boost::graph_traits<TriangleMesh>::null_face())
      seeds[get(component_of, f)] = f;

  auto is_user_seam = get(CGAL::dynamic_edge_property_t<bool>(), mesh);
  for(auto e : edges(mesh))
    put(is_user_seam, e, false);
  for(auto e : user_seams)
    put(is_user_seam, e, true);

  // One frame for every component, so that the charts are packed in common units; the UVs
  // go back to the mesh's units when written.
  std::vector<std::array<double, 3>> corner_points;
  std::vector<std::size_t> component_faces(components, 0);
  const auto vpm = get(CGAL::vertex_point, mesh);
  for(face_descriptor f : faces(mesh))
  {
    ++component_faces[get(component_of, f)];
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
    {
      const auto& p = get(vpm, v);
      corner_points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
  }
  const internal::Normalisation normalisation = internal::normalisation_of(corner_points);
  corner_points = {};
  const double total_faces = static_cast<double>(num_faces(mesh));
  double faces_done = 0;

  std::vector<std::vector<Uv>> chart_uvs(components);
  std::vector<Cut_mesh> cuts(components);
  std::vector<std::vector<face_descriptor>> chart_faces(components);
  for(std::size_t c = 0; c < components; ++c)
  {
    internal::Stage_progress progress{&options.progress, faces_done / total_faces,
                                      static_cast<double>(component_faces[c]) / total_faces};
    faces_done += static_cast<double>(component_faces[c]);
    internal::Mesh_index index;
    std::vector<vertex_descriptor> vertices;
    const Status indexed = internal::index_mesh(
      mesh, seeds[c], get(CGAL::vertex_point, mesh), index, vertices, &chart_faces[c], &normalisation);
    Chart_report chart;
    chart.vertices = index.number_of_vertices();
    chart.faces = index.number_of_faces();
    chart.boundary_loops = index.number_of_boundary_loops();
    chart.genus = index.genus();
    if(!indexed.ok())
      return finish(indexed.code, "component " + std::to_string(c) + ": " + indexed.message);
    std::vector<char> is_user_cone(index.number_of_vertices(), 0);
    std::vector<double> prescribed(index.number_of_vertices(), std::nan(""));
    for(int v = 0; v < index.number_of_vertices(); ++v)
    {
      const auto it = user_cones.find(vertices[v]);
      if(it != user_cones.end())
      {
        is_user_cone[v] = 1;
        prescribed[v] = it->second;
      }
    }
    std::vector<char> component_seams;
    if(!user_seams.empty())
    {
      component_seams.assign(index.number_of_edges(), 0);
      for(int e = 0; e < index.number_of_edges(); ++e)
        component_seams[e] =
          get(is_user_seam, edge(halfedge(vertices[index.edges[e][0]], vertices[index.edges[e][1]], mesh).first, mesh));
      if(std::find(component_seams.begin(), component_seams.end(), 1) == component_seams.end())
        component_seams.clear();
    }
    const Status failure = internal::parameterize_component<Metric, Solver>(
      index, is_user_cone, prescribed, component_seams, options, report, chart, cuts[c], chart_uvs[c], energy,
      progress);
    report.charts.push_back(chart);
    if(!failure.ok())
      return finish(failure.code,
                    "component " + std::to_string(c) + " (" + std::to_string(chart.vertices) +
                      " vertices, genus " + std::to_string(chart.genus) + ", " +
                      std::to_string(chart.boundary_loops) + " boundary loops): " + failure.message);
    if(seam_edges)
      for(int e = 0; e < index.number_of_edges(); ++e)
        if(cuts[c].disk_edges[e][1] >= 0)
          seam_edges->push_back(edge(halfedge(vertices[index.edges[e][0]], vertices[index.edges[e][1]], mesh).first, mesh));
  }

  // The charts side by side, each at its 3D scale: UV area = 3D area (normalised units).
  std::vector<Chart_box> boxes;
  for(std::size_t c = 0; c < components; ++c)
  {
    const internal::Mesh_index& disk = cuts[c].disk;
    double uv_area = 0, area = 0;
    for(const auto& f : disk.faces)
    {
      const Uv &a = chart_uvs[c][f[0]], &b = chart_uvs[c][f[1]], &d = chart_uvs[c][f[2]];
      uv_area += 0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
      area += internal::triangle_area(disk.points[f[0]], disk.points[f[1]], disk.points[f[2]]);
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
  if(options.progress)
    options.progress("done", 1.0);
  return finish(OK, "");
}

/// \brief Parameterizes the surface under a `CGAL::Seam_mesh`, cut along its seams and nothing
/// else: the metric is flat across every seam, both sides of a seam get one length and fit
/// together by a rigid motion, and the seams' ends and branch points are the cones, their
/// angles chosen by the optimum (the seams are `user_seams` of the overload above). CGAL's
/// `parameterize()` with `Inverse_curvature_map_parameterizer_3` reads the same seams as free
/// border instead, whose two sides need not fit.
///
/// Every component of the underlying mesh is parameterized (a `Seam_mesh` offers no way to
/// restrict it to one), each at its own place in the plane. The seams are the whole cut:
/// `options.automatic_cones` and `options.remove_overlaps` do not apply (a cone off the seams,
/// or a cut of the overlap removal, would need seams the seam mesh does not have).
///
/// \tparam VertexUVMap a writable property map from the seam mesh's `vertex_descriptor` (one
///         per side of a seam) to a 2D point, as CGAL's `parameterize()` takes
/// \returns as the overload above
template <class Metric_ = CGAL::Default, class SparseSolver = CGAL::Default, class Energy_ = CGAL::Default,
          class TriangleMesh, class SeamEdgeMap, class SeamVertexMap, class VertexUVMap>
Surface_parameterization_report parameterize(
  const CGAL::Seam_mesh<TriangleMesh, SeamEdgeMap, SeamVertexMap>& seam_mesh, VertexUVMap uv_map,
  const Surface_parameterization_options& options = Surface_parameterization_options(),
  const typename CGAL::Default::Get<Energy_, Curvature_entropy>::type& energy =
    typename CGAL::Default::Get<Energy_, Curvature_entropy>::type())
{
  using Uv_point = typename boost::property_traits<VertexUVMap>::value_type;
  const TriangleMesh& surface = seam_mesh.mesh();
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor> seams;
  for(auto e : edges(surface))
    if(seam_mesh.has_on_seam(e))
      seams.push_back(e);
  Surface_parameterization_options along_seams = options;
  along_seams.automatic_cones = false;
  along_seams.remove_overlaps = false;
  auto corner_uv = get(CGAL::dynamic_halfedge_property_t<Uv_point>(), surface);
  const Surface_parameterization_report report =
    parameterize<Metric_, SparseSolver, Energy_>(surface, corner_uv, along_seams, {}, nullptr, seams, energy);
  if(report.status == CGAL::Surface_mesh_parameterization::OK)
    for(auto f : faces(seam_mesh))
      for(auto h : CGAL::halfedges_around_face(halfedge(f, seam_mesh), seam_mesh))
        put(uv_map, target(h, seam_mesh), get(corner_uv, h.tmhd));
  return report;
}

} // namespace ICM

#endif // ICM_PARAMETERIZE_H
