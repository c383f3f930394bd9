// What icm_param tells of a run: the figures of either parameterizer's report
// (`Run_figures`), as the JSON line of --json (doc/cli.md: its keys, in this order) or the
// summary line on stderr, and the JSON error object of a failure (`Failure_report`).

#ifndef ICM_PARAM_REPORT_H
#define ICM_PARAM_REPORT_H

#include "icm_param_arguments.h"
#include "icm_param_energy.h"

#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/measures/Distortion.h>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>

namespace icm_param {

using Json = nlohmann::ordered_json;

/// What the JSON line and the summary line tell of a run, from either parameterizer's report:
/// totals over the charts and the worst of each check.
struct Run_figures
{
  int charts = 1, components = 1, cones = 0, wide_cones = 0, cones_given_up = 0, genus = 0, loops = 0, newton = 0,
      moved = 0;
  int factorizations = 0, preconditioned_solves = 0; ///< the entropy optimum's Newton, over the charts
  /// Pairs of crossing border edges, after and before overlap removal (the parameterizer of
  /// an energy or a prescribed border removes none: both are its count).
  std::optional<int> overlaps, raw_overlaps;
  std::size_t seam_edges = 0;
  double seam_length = 0; ///< over the square root of the 3D area
  double curvature_error = 0, length_error = 0, seam_error = 0;
  std::string metrics, fallbacks, layout;
  double seconds_index = 0, seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_parameterize = 0;
  std::string energy = ICM::Curvature_entropy::name;
  /// An energy other than the entropy: its optimizer's steps, E at the entropy optimum and
  /// at the result, and why it stopped early (empty if it converged).
  bool optimized_energy = false;
  int energy_iterations = 0;
  double initial_energy = 0, final_energy = 0;
  std::string energy_message;
  /// The border condition (doc/border_conditions.md): "free" unless --boundary prescribed one,
  /// then its faces flat on a straight side, its outer iterations and its circles' deviation.
  std::string boundary = "free";
  int degenerate_faces = 0, border_iterations = 0;
  double circle_deviation = 0;
  /// --atlas: the charts packed, those turned, the share of the square their triangles cover.
  int atlas_charts = 0, atlas_rotated_charts = 0;
  double atlas_utilization = 0;

  /// `ICM::parameterize`'s run of `energy_` with `seam_edges` cut (the energy over the
  /// components: `ICM::energy_summary`).
  Run_figures(const ICM::Surface_parameterization_report& report, std::size_t seam_edges_, const std::string& energy_);

  /// `Inverse_curvature_map_parameterizer_3`'s run (a prescribed border): one chart, never cut.
  explicit Run_figures(const ICM::Parameterization_report& report);
};

/// The seconds of the steps that are icm_param's, not the parameterizer's.
struct Timings
{
  double read = 0, write = 0, total = 0;
};

/// The JSON line of --json: the run's figures, the distortion and the repairs of the input.
Json summary_json(const Arguments& args, const Mesh& mesh, const ICM::IO::Mesh_reading_report& read,
                  const Run_figures& t, const ICM::Distortion_measures& measures, const Timings& seconds);

/// The summary line: components and charts apart, as the JSON's `components` and `charts`
/// (the overlap removal cuts a component into several charts).
void print_summary_line(const Arguments& args, const Mesh& mesh, const Run_figures& t,
                        const ICM::Distortion_measures& measures);

} // namespace icm_param

#endif // ICM_PARAM_REPORT_H
