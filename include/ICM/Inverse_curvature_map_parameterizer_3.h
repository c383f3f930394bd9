// The CGAL-facing parameterizer: steps 0-7 of the pipeline behind CGAL's `Parameterizer_3`
// concept, so that
//   CGAL::Surface_mesh_parameterization::parameterize(mesh, parameterizer, bhd, uvmap)
// computes the conformal parameterization with least area distortion (the minimum of the
// curvature entropy with a free boundary, paper Thm 3.5), or with a free boundary the least
// value of another energy (Energies.h, Curvature_space_optimizer.h).

#ifndef ICM_INVERSE_CURVATURE_MAP_PARAMETERIZER_3_H
#define ICM_INVERSE_CURVATURE_MAP_PARAMETERIZER_3_H

#include <ICM/border/Border_conditions.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Unflip.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/Status.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Option_checks.h>

#include <CGAL/Default.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {

/// How the optimal metric is computed.
enum class Optimum_method
{
  Newton,              ///< Dirichlet problem u_S = u0_S, K(u)_N = 0 by Newton (default)
  Curvature_diffusion  ///< the paper's Algorithm 5 (slow; for validation)
};

/// Options of `Inverse_curvature_map_parameterizer_3`.
struct Parameterization_options
{
  Newton_options newton;                  ///< tolerance on max |k| over interior vertices, caps
  Diffusion_options diffusion;            ///< used with `Optimum_method::Curvature_diffusion`
  Optimum_method optimum = Optimum_method::Newton;
  Layout_method layout = Layout_method::Automatic;
  /// `Automatic` switches to the harmonic layout here. The paper switches at 30k faces;
  /// in double precision the breadth-first propagation still reproduces the metric to
  /// 1e-10 on the 40k-face horse at a tenth of the cost of a factorization.
  int harmonic_layout_min_faces = 200000;
  /// A layout whose edge lengths differ from the metric's by more than this fails (relative,
  /// see `Layout_check::max_relative_length_error`).
  double max_layout_length_error = 1e-6;
  /// When the requested metric cannot reach the optimum (a face would stop being a
  /// triangle), retry with `Circle_packing_metric`, whose every u is valid.
  bool fall_back_to_circle_packing = true;
  /// Called at the start of each stage with its name ("index", "metric", "optimum", "layout").
  std::function<void(const std::string&)> progress;
  /// The optimizer of an `Energy` other than the entropy (started from the entropy optimum).
  Curvature_space_options energy;
};

/// Whether every field of `options` is in range (`ERROR_WRONG_PARAMETER` naming the first
/// that is not).
inline Status check_options(const Parameterization_options& options)
{
  return internal::Option_checks()
    .nested(check_options(options.newton))
    .nested(check_options(options.diffusion))
    .one_of("optimum", options.optimum, 2)
    .one_of("layout", options.layout, 3)
    .at_least("harmonic_layout_min_faces", options.harmonic_layout_min_faces, 0)
    .real("max_layout_length_error", options.max_layout_length_error, 0, false)
    .nested(check_options(options.energy))
    .status();
}

/// What the last `parameterize()` did: sizes, topology, convergence, timings, the reason of
/// any failure.
struct Parameterization_report
{
  /// `NOT_RUN` until the first `parameterize()`.
  CGAL::Surface_mesh_parameterization::Error_code status = NOT_RUN;
  std::string message = "not run";  ///< empty on success, else the human reason
  int vertices = 0, faces = 0, edges = 0, boundary_loops = 0, genus = 0, euler_characteristic = 0;
  std::string metric;            ///< the metric of the result ("vertex-scaling", ...)
  std::string metric_summary;    ///< what that metric changed of the mesh, in words
  /// Empty, or why the requested metric could not reach the optimum and the circle packing
  /// was used instead ("vertex-scaling: the Newton line search stalled ...").
  std::string fallback_reason;
  int newton_iterations = 0;             ///< of the metric that succeeded (a fallback not counted)
  std::string energy;                    ///< the energy minimised ("entropy", "log-area", ...)
  /// The energy optimizer (an `Energy` other than the entropy): its steps, E at the entropy
  /// optimum and at the result, and why it stopped early, if it did (the result is then its
  /// last, best metric).
  int energy_iterations = 0;
  double initial_energy = 0, final_energy = 0;
  std::string energy_message;
  std::vector<double> residual_history;  ///< max |k| over interior vertices per iteration
  double max_curvature_error = 0;        ///< final max |k_i| over interior vertices
  double max_layout_length_error = 0;    ///< UV edge length vs metric, see `Layout_check`
  int flipped_faces = 0;
  /// A prescribed border with straight sides (a square): the faces whose three corners are
  /// held on one side (`internal::straight_stretches`), laid out as segments whatever the
  /// metric (an "ear" on a side; CGAL's square border makes them degenerate too). Not
  /// counted in `flipped_faces`.
  int degenerate_faces = 0;
  /// Vertices moved off the metric's layout to unflip a face of the mesh that its intrinsic
  /// triangulation does not have (see `unflip_by_moving_vertices`).
  int moved_vertices = 0;
  /// Pairs of border edges whose UV segments meet (`count_border_overlaps`): with no flipped
  /// face, more than 0 exactly when the map folds over itself (the horse's free-boundary
  /// entropy map swings a leg over another). Reported, not refused: one UV per vertex leaves
  /// no cut to take the overlap apart, which `ICM::parameterize` makes (`remove_overlaps`).
  int overlapping_border_edges = 0;
  std::string layout;                    ///< "propagation" or "harmonic"
  /// The border condition's name ("free", "prescribed-curvature", "square", "circle",
  /// "polygon", "circle-domain"; doc/border_conditions.md).
  std::string border_condition;
  /// Circle borders: the outer iterations u <- K^{-1}(T(u)), and the largest relative
  /// distance of a border vertex's UV from its loop's fitted circle (`max_circle_deviation`).
  int border_iterations = 0;
  double circle_deviation = 0;
  double seconds_index = 0, seconds_metric = 0, seconds_optimum = 0, seconds_layout = 0,
         seconds_total = 0;
};

/// \brief Conformal parameterization with least area distortion by the inverse curvature map.
///
/// Model of CGAL's `Parameterizer_3`. The input is the connected component of the border
/// halfedge `bhd`; it must be a topological disk (one border, genus 0): a `CGAL::Seam_mesh`
/// whose seams cut a surface into a disk qualifies, its seams read as border (CGAL's reading;
/// `ICM::parameterize` on the seam mesh reads them as cuts of one surface). Every boundary
/// vertex is singular (free
/// boundary) and every interior vertex flat; the result is the minimum of the curvature
/// entropy in the conformal class of `Metric`, laid out isometrically. Another
/// `BorderCondition` prescribes the border instead (a rectangle, a circle, given turning
/// angles), and `Circle_domain` also takes genus 0 with several border loops, mapped onto
/// nested circles without a cut (doc/border_conditions.md). All UVs are written
/// and every vertex is marked parameterized.
///
/// When the optimum cannot be reached in the class of `Metric` (vertex scaling or inversive
/// distance: a face would stop being a triangle), the parameterizer falls back to the circle
/// packing metric, whose every u is valid, and says so in `report().metric` (see
/// `Parameterization_options::fall_back_to_circle_packing`).
///
/// CGAL's `parameterize()` takes the parameterizer by value; copies share one report, so
/// `report()` on the object passed in describes the last run.
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam Metric a model of `Metric` (doc/concepts.md); `CGAL::Default` is
///         `Default_metric` (`Intrinsic_delaunay_metric`, chosen by measurement: doc/benchmarks.md)
/// \tparam SparseSolver an Eigen sparse Cholesky; `CGAL::Default` is `Default_sparse_solver`:
///         Eigen's `SimplicialLDLT`, switching to CHOLMOD after nested dissection for large
///         meshes when SuiteSparse is present (`Size_adaptive_solver`).
/// \tparam Energy_ a model of `Energy` (doc/energies.md); `CGAL::Default` is
///         `Curvature_entropy`, whose minimum is reached directly as the Dirichlet problem
///         u_S = u0_S (the free-boundary optimum). Any other energy is minimised over the
///         free-boundary admissible metrics by `minimize_energy_on_singular_values`, started
///         from that optimum (options: `Parameterization_options::energy`).
/// \tparam BorderCondition `Free_border`, `Prescribed_border_curvature`, `Border_shape` or
///         `Circle_domain` (Border_conditions.h, doc/border_conditions.md); `CGAL::Default` is
///         `Free_border`. Any other condition prescribes the border, which leaves the energy
///         nothing to choose: it then needs the default `Energy`. `Circle_domain` also takes
///         a genus-0 mesh with several border loops, laid out without a cut.
template <class TriangleMesh, class Metric_ = CGAL::Default, class SparseSolver = CGAL::Default,
          class Energy_ = CGAL::Default, class BorderCondition = CGAL::Default>
class Inverse_curvature_map_parameterizer_3
{
public:
  using Error_code = CGAL::Surface_mesh_parameterization::Error_code;
  using Metric = typename CGAL::Default::Get<Metric_, Default_metric>::type;
  using Solver = typename CGAL::Default::Get<SparseSolver, Default_sparse_solver>::type;
  using Energy = typename CGAL::Default::Get<Energy_, Curvature_entropy>::type;
  using Border_condition = typename CGAL::Default::Get<BorderCondition, Free_border>::type;
  /// Whether the energy needs the optimizer (the entropy's minimum is the Dirichlet problem).
  static constexpr bool optimizes_energy = !std::is_same<Energy, Curvature_entropy>::value;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;

  /// A parameterizer with these options (doc/parameterizer.md) minimising `energy` under
  /// the border condition `border` (doc/border_conditions.md).
  explicit Inverse_curvature_map_parameterizer_3(
    const Parameterization_options& options = Parameterization_options(), const Energy& energy = Energy(),
    const Border_condition& border = Border_condition())
    : options_(options), energy_(energy), border_(border), report_(std::make_shared<Parameterization_report>())
  {}

  const Energy& energy() const { return energy_; }
  const Border_condition& border_condition() const { return border_; }

  /// The options of the next `parameterize()` call.
  Parameterization_options& options() { return options_; }
  const Parameterization_options& options() const { return options_; }
  /// What the last `parameterize()` call of this object or of any copy of it did
  /// (doc/report.md).
  const Parameterization_report& report() const { return *report_; }

  /// Parameterizes the component of `bhd`. `vimap` and `vpmap` follow CGAL's concept: the
  /// index map is not needed (the mesh is indexed once, internally) and `vpmap` is set to
  /// true for every vertex that receives a UV.
  template <class VertexUVMap, class VertexIndexMap, class VertexParameterizedMap>
  Error_code parameterize(TriangleMesh& mesh, halfedge_descriptor bhd, VertexUVMap uvmap,
                          VertexIndexMap vimap, VertexParameterizedMap vpmap)
  {
    using namespace CGAL::Surface_mesh_parameterization;
    Run run(*report_);

    // Step 0: index the component once.
    stage("index");
    if(faces(mesh).empty())
      return run.fail(ERROR_EMPTY_MESH, "the mesh has no faces");
    if(const Status checked = check_options(options_); !checked.ok())
      return run.fail(checked.code, checked.message);
    if(bhd == boost::graph_traits<TriangleMesh>::null_halfedge())
      return run.fail(ERROR_WRONG_PARAMETER, "no border halfedge given");
    const auto mesh_halfedges = halfedges(mesh);
    if(std::find(mesh_halfedges.begin(), mesh_halfedges.end(), bhd) == mesh_halfedges.end())
      return run.fail(ERROR_WRONG_PARAMETER, "the border halfedge given is not a halfedge of this mesh");
    if(face(bhd, mesh) != boost::graph_traits<TriangleMesh>::null_face())
      return run.fail(ERROR_WRONG_PARAMETER, "the halfedge given is not on a border");
    internal::Mesh_index index;
    std::vector<vertex_descriptor> vertices;
    const Status indexed =
      internal::index_mesh(mesh, face(opposite(bhd, mesh), mesh), get(CGAL::vertex_point, mesh),
                           index, vertices);
    run.report_topology(index);
    run.report.energy = energy_name<Energy>();
    run.report.border_condition = border_.name();
    run.report.seconds_index = run.lap();
    if(!indexed.ok())
      return run.fail(indexed.code, indexed.message);
    Border_target border;
    if(const Error_code refused = border_target(mesh, bhd, index, vertices, vimap, border); refused != OK)
      return run.fail(refused, border.message);

    // Steps 1-7 in the class of `Metric`, then in the circle packing's if it cannot get there.
    std::vector<Uv> uv;
    Error_code status = optimum_and_layout<Metric>(index, border, run, uv);
    if(status != OK && !std::is_same<Metric, Circle_packing_metric>::value &&
       options_.fall_back_to_circle_packing)
    {
      run.report.fallback_reason = std::string(Metric::name) + ": " + run.report.message;
      run.report.message.clear();
      status = optimum_and_layout<Circle_packing_metric>(index, border, run, uv);
      // Both failed: the first metric's reason is the one to act on, the fallback's follows.
      if(status != OK)
        return run.fail(status, run.report.fallback_reason + "; then " + Circle_packing_metric::name + ": " +
                                  run.report.message);
    }
    if(status != OK)
      return run.fail(status, run.report.message);

    // The layout is in the index's normalised units: back to the mesh's.
    using Uv_point = typename boost::property_traits<VertexUVMap>::value_type;
    const double scale = index.normalisation.scale;
    for(int v = 0; v < index.number_of_vertices(); ++v)
    {
      put(uvmap, vertices[v], Uv_point(scale * uv[v][0], scale * uv[v][1]));
      put(vpmap, vertices[v], true);
    }
    return run.succeed();
  }

private:
  struct Run;

  /// What the border condition asks on this mesh, or why it cannot hold: the topology each
  /// condition needs, and the energy (a prescribed border leaves it nothing to choose).
  template <class VertexIndexMap>
  Error_code border_target(const TriangleMesh& mesh, halfedge_descriptor bhd, const internal::Mesh_index& index,
                           const std::vector<vertex_descriptor>& vertices, VertexIndexMap vimap,
                           Border_target& border) const
  {
    using namespace CGAL::Surface_mesh_parameterization;
    const std::string name = "the border condition \"" + border_.name() + "\"";
    constexpr bool several_loops = std::is_same<Border_condition, Circle_domain>::value;
    if(index.genus() != 0)
    {
      border.message = internal::describe_topology(index) + ": not a disk" +
                       (several_loops ? " (" + name + " needs genus 0)" : std::string());
      return ERROR_NO_TOPOLOGICAL_DISC;
    }
    if(!several_loops && !index.is_disk())
    {
      border.message = internal::describe_topology(index) + ": not a disk (" + name +
                       " needs one border loop; Circle_domain maps several without a cut)";
      return ERROR_NO_TOPOLOGICAL_DISC;
    }
    border = border_.target(mesh, bhd, index, vertices, vimap);
    if(!border.ok())
      return border.status;
    if(border.prescribes_border() && optimizes_energy)
    {
      border.message = std::string("the energy \"") + energy_name<Energy>() + "\" cannot be minimised with " + name +
                       ": a prescribed border leaves a single admissible metric (no interior cones on this "
                       "path), so only the default entropy applies";
      return ERROR_WRONG_PARAMETER;
    }
    return OK;
  }

  /// The clock and the report of one `parameterize()` call.
  struct Run
  {
    using Clock = std::chrono::steady_clock;
    Parameterization_report& report;
    Clock::time_point start = Clock::now(), last = start;

    explicit Run(Parameterization_report& r) : report(r) { report = Parameterization_report(); }

    /// Seconds since the last lap.
    double lap()
    {
      const Clock::time_point now = Clock::now();
      const double s = std::chrono::duration<double>(now - last).count();
      last = now;
      return s;
    }
    Error_code fail(Error_code code, const std::string& why)
    {
      report.status = code;
      report.message = why;
      report.seconds_total = std::chrono::duration<double>(Clock::now() - start).count();
      return code;
    }
    Error_code succeed()
    {
      report.status = CGAL::Surface_mesh_parameterization::OK;
      report.message.clear();
      report.seconds_total = std::chrono::duration<double>(Clock::now() - start).count();
      return report.status;
    }
    void report_topology(const internal::Mesh_index& index)
    {
      report.vertices = index.number_of_vertices();
      report.faces = index.number_of_faces();
      report.edges = index.number_of_edges();
      report.boundary_loops = index.number_of_boundary_loops();
      report.euler_characteristic = index.euler_characteristic();
      report.genus = index.genus();
    }
  };

  /// Steps 1, 5 and 7 in the conformal class of `M`: its initial metric, the free-boundary
  /// optimum (S = border, N = interior), and the checked isometric layout into `uv`. Sets the
  /// report's message and returns the error code on failure.
  template <class M>
  Error_code optimum_and_layout(const internal::Mesh_index& index, const Border_target& border, Run& run,
                                std::vector<Uv>& uv)
  {
    using namespace CGAL::Surface_mesh_parameterization;
    Parameterization_report& report = run.report;
    stage("metric");
    const M metric(index);
    report.metric = M::name;
    report.metric_summary = metric.summary();
    report.seconds_metric += run.lap();

    stage("optimum");
    // Free border: the Dirichlet problem on the interior. A prescribed border: every vertex
    // free but one, which fixes the scale (its equation holds by Gauss-Bonnet).
    std::vector<char> is_free(index.number_of_vertices());
    for(int v = 0; v < index.number_of_vertices(); ++v)
      is_free[v] = border.prescribes_border() ? v != 0 : !index.is_boundary_vertex[v];
    Inverse_curvature_map<Solver, M> solver(index, metric, is_free);
    Eigen::VectorXd u;
    if(border.prescribes_border())
    {
      const Error_code status = prescribed_border_optimum(index, metric, border, solver, u, report);
      report.seconds_optimum += run.lap();
      if(status != OK)
        return status;
    }
    else if(options_.optimum == Optimum_method::Newton)
    {
      const Newton_report newton = free_boundary_optimum(solver, metric, u, options_.newton);
      report.newton_iterations = newton.iterations;
      report.residual_history = newton.residual_history;
      report.max_curvature_error = newton.final_residual();
      report.seconds_optimum += run.lap();
      if(!newton.converged)
      {
        report.message = newton.message;
        return ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
      }
    }
    else
    {
      const Diffusion_report diffusion =
        free_boundary_curvature_diffusion(index, metric, boundary_singular_set(index), u,
                                          options_.diffusion);
      report.max_curvature_error = diffusion.final_residual;
      report.seconds_optimum += run.lap();
      if(!diffusion.converged)
      {
        report.message = diffusion.message;
        return ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
      }
    }

    if constexpr(optimizes_energy)
    {
      if(!border.prescribes_border()) // refused before: a prescribed border has no choice left
      {
        const Error_code status = minimize_energy(index, metric, solver, u, report);
        report.seconds_optimum += run.lap();
        if(status != OK)
          return status;
      }
    }

    stage("layout");
    Eigen::VectorXd k;
    std::vector<double> w;
    Curvature_map<M>& curvature = solver.curvature_map();
    curvature.evaluate(u, k, &w);
    report.metric_summary = curvature.metric().summary(); // with the flips made during Newton
    const std::vector<double>& lengths = curvature.lengths();
    // The metric's own triangulation (the mesh's, or its intrinsic Delaunay one) is laid
    // out; it has the mesh's vertices, so its UVs are the mesh's.
    const internal::Mesh_index& triangulation = curvature.mesh_index();
    // The harmonic layout solves with the Newton system's Laplacian, the Dirichlet problem's
    // only with a free border (a prescribed border's pins one vertex): those are propagated.
    const bool harmonic =
      !border.prescribes_border() &&
      (options_.layout == Layout_method::Harmonic ||
       (options_.layout == Layout_method::Automatic &&
        index.number_of_faces() >= options_.harmonic_layout_min_faces));
    if(harmonic)
    {
      report.layout = "harmonic";
      if(!layout_harmonic(triangulation, lengths, k, w, solver.laplacian(), uv, report.message))
        return ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
    }
    else
    {
      report.layout = "propagation";
      uv = layout_by_propagation(triangulation, lengths, curvature.face_angles());
    }
    Layout_check check = check_layout(triangulation, lengths, uv);
    if(&triangulation != &index && check.flipped_faces == 0)
    {
      // A prescribed border stays where the metric put it (a moved border vertex would
      // leave its circle or its rectangle's side): only interior vertices move.
      std::vector<char> is_movable(index.number_of_vertices(), 1);
      if(border.prescribes_border())
        for(int v = 0; v < index.number_of_vertices(); ++v)
          is_movable[v] = !index.is_boundary_vertex[v];
      report.moved_vertices = unflip_by_moving_vertices(index, uv, is_movable);
      check.flipped_faces = count_flipped_faces(index, uv);
    }
    if(border.kind == Border_kind::Prescribed_curvature)
    {
      // Faces whose three corners are held on one straight side (border vertices of it, or
      // interior vertices whose neighbours all are) are segments in any such layout:
      // counted apart (exactly flat on a rectangle) rather than as flipped.
      const std::vector<std::array<int, 2>> stretches = internal::straight_stretches(index, border.curvature);
      internal::make_rectangle_sides_exact(index, border.curvature, stretches, uv);
      const std::vector<int> flat = internal::faces_on_a_straight_stretch(index, stretches);
      report.degenerate_faces = static_cast<int>(flat.size());
      check.flipped_faces = count_flipped_faces(index, uv) - internal::count_flipped_faces_among(index, uv, flat);
    }
    report.flipped_faces = check.flipped_faces;
    report.max_layout_length_error = check.max_relative_length_error;
    if(border.kind == Border_kind::Circles)
      report.circle_deviation = max_circle_deviation(index, uv);
    report.seconds_layout += run.lap();
    if(check.flipped_faces > 0)
    {
      report.message = std::to_string(check.flipped_faces) + " faces are flipped in the layout";
      return ERROR_NO_1_TO_1_MAPPING;
    }
    if(!(check.max_relative_length_error <= options_.max_layout_length_error))
    {
      report.message = "the layout does not reproduce the metric (relative edge length error " +
                       std::to_string(check.max_relative_length_error) + ")";
      return ERROR_NO_1_TO_1_MAPPING;
    }
    report.overlapping_border_edges = count_border_overlaps(index, uv).crossing_pairs;
    report.seconds_layout += run.lap();
    return OK;
  }

  /// Step 5 for a prescribed border: Algorithm 1 for a given curvature, or the circle
  /// domain's fixed point, from u0. Fills the report's Newton figures.
  template <class M>
  Error_code prescribed_border_optimum(const internal::Mesh_index& index, const M& metric, const Border_target& border,
                                       Inverse_curvature_map<Solver, M>& solver, Eigen::VectorXd& u,
                                       Parameterization_report& report)
  {
    u = metric.u0;
    const Border_solve_report solved = border.kind == Border_kind::Circles
                                         ? solve_circle_domain(solver, index, border, u, options_.newton)
                                         : solve_prescribed_border(solver, border.curvature, u, options_.newton);
    report.newton_iterations = solved.newton_iterations;
    report.border_iterations = solved.outer_iterations;
    report.residual_history = solved.residual_history;
    report.max_curvature_error = solved.final_residual();
    if(!solved.converged)
    {
      report.message = solved.message;
      return CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
    }
    return CGAL::Surface_mesh_parameterization::OK;
  }

  /// Step 5 for an energy other than the entropy, from the entropy optimum `u`. An optimizer
  /// that stops early (iteration cap, a line search without decrease) still leaves its best
  /// metric, which is used and the reason reported; only a failure at the start is an error.
  template <class M>
  Error_code minimize_energy(const internal::Mesh_index& index, const M& metric,
                             Inverse_curvature_map<Solver, M>& solver, Eigen::VectorXd& u,
                             Parameterization_report& report)
  {
    const Curvature_space_report optimizer =
      minimize_energy_on_singular_values(solver, index, metric, energy_, u, options_.energy);
    report.energy_iterations = optimizer.iterations;
    report.newton_iterations += optimizer.newton_iterations;
    report.initial_energy = optimizer.initial_energy;
    report.final_energy = optimizer.final_energy;
    report.energy_message = optimizer.message;
    if(optimizer.energy_history.empty())
    {
      report.message = std::string(energy_name<Energy>()) + " energy: " + optimizer.message;
      return CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM;
    }
    return CGAL::Surface_mesh_parameterization::OK;
  }

  void stage(const std::string& name) const
  {
    if(options_.progress)
      options_.progress(name);
  }

  Parameterization_options options_;
  Energy energy_;
  Border_condition border_;
  std::shared_ptr<Parameterization_report> report_;
};

} // namespace ICM

#endif // ICM_INVERSE_CURVATURE_MAP_PARAMETERIZER_3_H
