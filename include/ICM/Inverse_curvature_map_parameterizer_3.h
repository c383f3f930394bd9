// The CGAL-facing parameterizer: steps 0-7 of the pipeline behind CGAL's `Parameterizer_3`
// concept, so that
//   CGAL::Surface_mesh_parameterization::parameterize(mesh, parameterizer, bhd, uvmap)
// computes the conformal parameterization with least area distortion (the minimum of the
// curvature entropy with a free boundary, paper Thm 3.5), or with a free boundary the least
// value of another energy (Energies.h, Curvature_space_optimizer.h).

#ifndef ICM_INVERSE_CURVATURE_MAP_PARAMETERIZER_3_H
#define ICM_INVERSE_CURVATURE_MAP_PARAMETERIZER_3_H

#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/Status.h>
#include <ICM/border/Border_conditions.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/border/Border_shape.h>
#include <ICM/pipeline/Chart_solver.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/pipeline/Cgal_arguments.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>

#include <CGAL/Default.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {

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
/// \image html three_peaks_icm_lscm_arap.svg "three_peaks (examples/data): the free-boundary layout of this parameterizer (icm_free_boundary) beside CGAL's LSCM and ARAP, faces coloured by log(UV area / 3D area)" width=100%
///
/// When the optimum cannot be reached in the class of `Metric` (vertex scaling or inversive
/// distance: a face would stop being a triangle), the parameterizer falls back to the circle
/// packing metric, whose every u is valid, and says so in `report().metric` (see
/// `Parameterization_options::fall_back_to_circle_packing`).
///
/// CGAL's `parameterize()` takes the parameterizer by value; copies share one report, so
/// `report()` on the object passed in describes the last run.
///
/// \cgalModels{CGAL's <a href="https://doc.cgal.org/latest/Surface_mesh_parameterization/classParameterizer__3.html">Parameterizer_3</a>}
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam Metric a model of \ref ::Metric "Metric"; `CGAL::Default` is
///         `Default_metric` (`Intrinsic_delaunay_metric`, chosen by measurement: doc/benchmarks.md)
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver" (an Eigen sparse
///         Cholesky); `CGAL::Default` is `Default_sparse_solver`:
///         Eigen's `SimplicialLDLT`, switching to CHOLMOD after nested dissection for large
///         meshes when SuiteSparse is present (`Size_adaptive_solver`).
/// \tparam Energy_ a model of \ref ::Energy "Energy" (doc/energies.md); `CGAL::Default` is
///         `Curvature_entropy`, whose minimum is reached directly as the Dirichlet problem
///         u_S = u0_S (the free-boundary optimum). Any other energy is minimised over the
///         free-boundary admissible metrics by `minimize_energy_on_singular_values`, started
///         from that optimum (options: `Parameterization_options::energy`).
/// \tparam BorderCondition a model of \ref ::BorderCondition "BorderCondition":
///         `Free_border`, `Prescribed_border_curvature`, `Border_shape` or
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
  using Metric = internal::Metric_argument<Metric_>;
  using Solver = typename internal::Solver_argument<SparseSolver>::type;
  using Energy = typename CGAL::Default::Get<Energy_, Curvature_entropy>::type;
  using Border_condition = typename internal::Border_condition_argument<BorderCondition, Metric_>::type;
  /// CGAL's names of the second and third arguments, when they are CGAL's
  /// (pipeline/Cgal_arguments.h): the border parameterizer, the solver traits.
  using Border_parameterizer = Metric_;
  using Solver_traits = SparseSolver;
  static_assert(internal::Is_metric<Metric>::value,
                "Inverse_curvature_map_parameterizer_3: the second template argument must be a Metric "
                "(doc/concepts.md), a CGAL border parameterizer or CGAL::Default");
  static_assert(internal::Is_sparse_solver<Solver>::value,
                "Inverse_curvature_map_parameterizer_3: the third template argument must be an Eigen sparse "
                "Cholesky, a CGAL solver traits or CGAL::Default");
  static_assert(!internal::Is_border_parameterizer<Metric_>::value ||
                  std::is_same<BorderCondition, CGAL::Default>::value,
                "Inverse_curvature_map_parameterizer_3: a CGAL border parameterizer as second template argument "
                "is the border condition; do not give a fifth one as well");
  /// Whether the energy needs the optimizer (the entropy's minimum is the Dirichlet problem).
  static constexpr bool optimizes_energy = !std::is_same<Energy, Curvature_entropy>::value;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;

  /// A parameterizer with these options (doc/parameterizer.md) minimising `energy` under
  /// the border condition `border` (doc/border_conditions.md).
  explicit Inverse_curvature_map_parameterizer_3(const Parameterization_options& options = Parameterization_options(),
                                                 const Energy& energy = Energy(),
                                                 const Border_condition& border = Border_condition())
    : options_(options), energy_(energy), border_(border), report_(std::make_shared<Parameterization_report>())
  {}

  /// CGAL's form: the border parameterizer given as second template argument, and a solver
  /// traits object, which carries nothing the solver needs.
  template <class BorderParameterizer = Border_parameterizer,
            std::enable_if_t<internal::Is_border_parameterizer<BorderParameterizer>::value, int> = 0>
  explicit Inverse_curvature_map_parameterizer_3(const BorderParameterizer& border,
                                                 const Solver_traits& = Solver_traits())
    : Inverse_curvature_map_parameterizer_3(Parameterization_options(), Energy(),
                                            internal::border_condition_of<Border_condition>(border))
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
  Error_code parameterize(TriangleMesh& mesh, halfedge_descriptor bhd, VertexUVMap uvmap, VertexIndexMap vimap,
                          VertexParameterizedMap vpmap)
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
      internal::index_mesh(mesh, face(opposite(bhd, mesh), mesh), get(CGAL::vertex_point, mesh), index, vertices);
    run.report_topology(index);
    run.report.energy = energy_name<Energy>();
    run.report.border_condition = border_.name();
    if(!indexed.ok())
    {
      run.report.seconds_index = run.lap();
      return run.fail(indexed.code, indexed.message);
    }
    internal::order_vertices_for_elimination_in<Metric>(index); // once for every Laplacian of the run
    run.report.seconds_index = run.lap();
    const Border_target border = border_target(mesh, bhd, index, vertices, vimap);
    if(!border.ok())
      return run.fail(border.status.code, border.status.message);

    // Steps 1-7 in the class of `Metric`, then in the circle packing's if it cannot get there.
    std::vector<Uv> uv;
    const Status solved = internal::solve_chart<Metric, Solver>(disk_problem(index, border), options_, chart_method(),
                                                                energy_, run.report, uv);
    if(!solved.ok())
      return run.fail(solved.code, solved.message);

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
  Border_target border_target(const TriangleMesh& mesh, halfedge_descriptor bhd, const internal::Mesh_index& index,
                              const std::vector<vertex_descriptor>& vertices, VertexIndexMap vimap) const
  {
    using CGAL::Surface_mesh_parameterization::ERROR_NO_TOPOLOGICAL_DISC;
    const std::string name = "the border condition \"" + border_.name() + "\"";
    constexpr bool several_loops = std::is_same<Border_condition, Circle_domain>::value;
    Border_target refused;
    if(index.genus() != 0)
      refused.status =
        Status::failure(ERROR_NO_TOPOLOGICAL_DISC, internal::describe_topology(index) + ": not a disk" +
                                                     (several_loops ? " (" + name + " needs genus 0)" : ""));
    else if(!several_loops && !index.is_disk())
      refused.status = Status::failure(ERROR_NO_TOPOLOGICAL_DISC,
                                       internal::describe_topology(index) + ": not a disk (" + name +
                                         " needs one border loop; Circle_domain maps several without a cut)");
    if(!refused.ok())
      return refused;
    Border_target border = border_.target(mesh, bhd, index, vertices, vimap);
    if(border.ok() && border.prescribes_border() && optimizes_energy)
      border.status = Status::wrong_parameter(
        std::string("the energy \"") + energy_name<Energy>() + "\" cannot be minimised with " + name +
        ": a prescribed border leaves a single admissible metric (no interior cones on this path), so only the "
        "default entropy applies");
    return border;
  }

  /// The chart problem of a disk: a free border is the Dirichlet problem on the interior; a
  /// prescribed border makes every vertex free but one, which fixes the scale (its equation
  /// holds by Gauss-Bonnet).
  static internal::Chart_problem disk_problem(const internal::Mesh_index& index, const Border_target& border)
  {
    internal::Chart_problem problem;
    problem.mesh = &index;
    problem.border = &border;
    problem.is_singular = boundary_singular_set(index);
    problem.target = border.prescribes_border() ? border.curvature : Eigen::VectorXd::Zero(index.number_of_vertices());
    problem.is_free.resize(index.number_of_vertices());
    for(int v = 0; v < index.number_of_vertices(); ++v)
      problem.is_free[v] = border.prescribes_border() ? v != 0 : !index.is_boundary_vertex[v];
    return problem;
  }

  /// The disk parameterizer's choices of how the chart is solved.
  internal::Chart_method chart_method() const
  {
    internal::Chart_method method;
    method.optimum = options_.optimum;
    method.diffusion = options_.diffusion;
    method.layout = options_.layout;
    method.harmonic_layout_min_faces = options_.harmonic_layout_min_faces;
    method.progress = options_.progress;
    return method;
  }

  /// The clock and the report of one `parameterize()` call.
  struct Run
  {
    Parameterization_report& report;
    internal::Stopwatch stopwatch;

    explicit Run(Parameterization_report& r) : report(r) { report = Parameterization_report(); }

    double lap() { return stopwatch.lap(); }
    Error_code fail(Error_code code, const std::string& why)
    {
      report.status = code;
      report.message = why;
      report.seconds_total = stopwatch.total();
      return code;
    }
    Error_code succeed() { return fail(CGAL::Surface_mesh_parameterization::OK, ""); }
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
