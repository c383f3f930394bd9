// The options of `ICM::parameterize` and what it reports: per chart (`Chart_report`) and for
// the whole call (`Surface_parameterization_report`), with the checks of every option.

#ifndef ICM_SURFACE_PARAMETERIZATION_OPTIONS_H
#define ICM_SURFACE_PARAMETERIZATION_OPTIONS_H

#include <ICM/Status.h>
#include <ICM/cones/Singular_vertices.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/internal/Option_checks.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

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


} // namespace ICM

#endif // ICM_SURFACE_PARAMETERIZATION_OPTIONS_H
