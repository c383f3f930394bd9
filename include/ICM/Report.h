// What a run did (doc/report.md): the figures of one chart's optimum and layout, which both
// entry points report alike (`Chart_solve_report`), and around them each entry point's own:
//
//   Curvature_space_report             the energy optimizer (optimum/)
//   Chart_solve_report                 steps 5 and 7 of one chart (pipeline/Chart_solver.h)
//   +- Parameterization_report         `Inverse_curvature_map_parameterizer_3` (a disk)
//   +- Chart_report                    one component of `ICM::parameterize`, in
//      Surface_parameterization_report    with the status and the stages' seconds

#ifndef ICM_REPORT_H
#define ICM_REPORT_H

#include <ICM/Status.h>

#include <CGAL/Surface_mesh_parameterization/Error_code.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

/// What an optimizer of an energy other than the entropy did (optimum/Curvature_space_optimizer.h).
struct Curvature_space_report
{
  bool converged = false;
  int iterations = 0;        ///< accepted steps
  int evaluations = 0;       ///< metrics measured (line search trials included)
  int newton_iterations = 0; ///< Newton steps over all solves (each one factorization)
  int factorizations = 0;    ///< other factorizations (the gradient's solves)
  /// Times a frozen triangulation was flipped to be Delaunay at the current metric
  /// (`Curvature_space_options::frozen_steps`).
  int refreshes = 0;
  double initial_energy = 0, final_energy = 0; ///< NaN for an energy without a value
  /// Final stopping figure: the relative reduced gradient, or Theorem 3.2's spread.
  double final_residual = 0;
  std::vector<double> energy_history;
  double seconds = 0;
  std::string message; ///< empty when converged, else why it stopped
};

/// What steps 5 and 7 did on one chart: its optimum, its layout and their checks.
struct Chart_solve_report
{
  std::string metric;         ///< the metric of the result ("intrinsic-delaunay", ...)
  std::string metric_summary; ///< what that metric changed of the mesh, in words
  /// Empty, or why the requested metric could not reach the optimum and the circle packing
  /// was used instead ("vertex-scaling: the Newton line search stalled ...").
  std::string fallback_reason;
  int newton_iterations = 0; ///< of the metric that succeeded, the energy's and the cones' not counted
  /// The entropy optimum's Newton on a free border: numeric factorizations of the Laplacian
  /// (its main cost on a large mesh), and the triangular solves of the conjugate gradients
  /// that gave the other steps their directions from an earlier factorization.
  int factorizations = 0, preconditioned_solves = 0;
  /// max |k_target - k| over the free vertices per Newton iteration of the entropy optimum.
  std::vector<double> residual_history;
  /// An energy other than the entropy: its optimizer's steps, E at the entropy optimum and
  /// at the result (NaN for an energy without a value), and why it stopped early (empty when
  /// it converged; the result is then its last, best metric).
  int energy_iterations = 0;
  double initial_energy = std::nan(""), final_energy = std::nan("");
  std::string energy_message;
  /// Interior singular vertices (the cones, chart indices) and their curvature 2 pi - angle
  /// sum, same order.
  std::vector<int> cones;
  std::vector<double> cone_curvatures;
  /// max |k| over the non-singular vertices; for a prescribed border, max |k - target| over
  /// all vertices.
  double max_curvature_error = 0;
  std::string layout;                 ///< "propagation" or "harmonic"
  double max_layout_length_error = 0; ///< UV edge length vs metric, see `Layout_check`
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
  /// face, more than 0 exactly when the map folds over itself. Reported, not refused, by
  /// the disk parameterizer (one UV per vertex leaves no cut to take the overlap apart);
  /// `ICM::parameterize` cuts such a chart into pieces (`remove_overlaps`).
  int overlapping_border_edges = 0;
  double seam_length_error = 0; ///< max relative difference of a seam's two sides
  /// Circle borders: the outer iterations u <- K^{-1}(T(u)), and the largest relative
  /// distance of a border vertex's UV from its loop's fitted circle (`max_circle_deviation`).
  int border_iterations = 0;
  double circle_deviation = 0;
  double seconds_metric = 0, seconds_optimum = 0, seconds_layout = 0;
};

/// What the last `Inverse_curvature_map_parameterizer_3::parameterize()` did: sizes,
/// topology, the chart's figures, timings, the reason of any failure.
struct Parameterization_report : Chart_solve_report
{
  /// `NOT_RUN` until the first `parameterize()`.
  CGAL::Surface_mesh_parameterization::Error_code status = NOT_RUN;
  std::string message = "not run"; ///< empty on success, else the human reason
  int vertices = 0, faces = 0, edges = 0, boundary_loops = 0, genus = 0, euler_characteristic = 0;
  std::string energy; ///< the energy minimised ("entropy", "log-area", ...)
  /// The border condition's name ("free", "prescribed-curvature", "square", "circle",
  /// "polygon", "circle-domain"; doc/border_conditions.md).
  std::string border_condition;
  double seconds_index = 0, seconds_total = 0;
};

/// What `ICM::parameterize` did to one connected component.
struct Chart_report : Chart_solve_report
{
  int vertices = 0, faces = 0, boundary_loops = 0, genus = 0;
  int seam_edges = 0, homology_generators = 0;
  /// Total 3D length of the seam edges (the cut and the overlap removal's cuts) over the
  /// square root of the component's 3D area: scale-free, 0 without a seam.
  double seam_length = 0;
  /// Overlap removal: pairs of border edges that crossed in the raw layout, the pieces the
  /// chart was cut into (1: none) and the seam edges that cut added.
  int raw_overlapping_border_edges = 0;
  int pieces = 1, overlap_cut_edges = 0;
  /// Automatic cones left out because the chart with all of them overlapped itself (a
  /// surface with a border, automatic count), the last placed first, until it lays out in one piece.
  int cones_given_up = 0;
};

/// What `ICM::parameterize` did: the status, the reason of a failure, one `Chart_report` per
/// connected component and the seconds of each stage (doc/report.md).
struct Surface_parameterization_report
{
  /// `NOT_RUN` until filled by `ICM::parameterize`.
  CGAL::Surface_mesh_parameterization::Error_code status = NOT_RUN;
  std::string message = "not run";  ///< empty on success, else the reason
  std::vector<Chart_report> charts; ///< one per connected component
  /// `seconds_index`: the components read into flat arrays and their elimination orders.
  double seconds_index = 0, seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_total = 0;
  /// Atlas mode only (`Surface_parameterization_options::atlas`): the charts packed (the
  /// pieces of every component), how many were turned by a quarter turn, and the share of
  /// the unit square that their UV triangles cover (sum of the triangles' areas).
  int atlas_charts = 0, atlas_rotated_charts = 0;
  double atlas_utilization = 0;
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

/// The components of a report taken together, as the command-line tool and the Python
/// module report them: counts summed (charts are the pieces the components were cut into,
/// wide cones those of angle above 2 pi), the largest Newton run and errors, each metric and
/// layout named once, and the first reason of a fallback.
struct Surface_summary
{
  int charts = 0, cones = 0, wide_cones = 0, genus = 0, boundary_loops = 0, newton_iterations = 0, moved_vertices = 0,
      overlapping_border_edges = 0, raw_overlapping_border_edges = 0, cones_given_up = 0;
  int factorizations = 0, preconditioned_solves = 0; ///< summed over the charts
  double max_curvature_error = 0, max_layout_length_error = 0, seam_length_error = 0;
  std::string metrics, layouts, fallback_reason;
};

inline Surface_summary surface_summary(const Surface_parameterization_report& report)
{
  const auto add_once = [](std::string& list, const std::string& name) {
    if(list.find(name) == std::string::npos)
      list += (list.empty() ? "" : ",") + name;
  };
  Surface_summary s;
  for(const Chart_report& c : report.charts)
  {
    s.charts += c.pieces;
    s.cones += static_cast<int>(c.cones.size());
    for(double k : c.cone_curvatures)
      s.wide_cones += k < 0;
    s.genus += c.genus;
    s.boundary_loops += c.boundary_loops;
    s.newton_iterations = std::max(s.newton_iterations, c.newton_iterations);
    s.factorizations += c.factorizations;
    s.preconditioned_solves += c.preconditioned_solves;
    s.moved_vertices += c.moved_vertices;
    s.overlapping_border_edges += c.overlapping_border_edges;
    s.raw_overlapping_border_edges += c.raw_overlapping_border_edges;
    s.cones_given_up += c.cones_given_up;
    s.max_curvature_error = std::max(s.max_curvature_error, c.max_curvature_error);
    s.max_layout_length_error = std::max(s.max_layout_length_error, c.max_layout_length_error);
    s.seam_length_error = std::max(s.seam_length_error, c.seam_length_error);
    add_once(s.metrics, c.metric);
    add_once(s.layouts, c.layout);
    if(s.fallback_reason.empty())
      s.fallback_reason = c.fallback_reason;
  }
  return s;
}

} // namespace ICM

#endif // ICM_REPORT_H
