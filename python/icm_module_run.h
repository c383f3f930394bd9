// The runs of `icm.parameterize`: icm_param's (examples/icm_param_energy.h), every metric,
// energy and border condition it takes, instantiated one energy (or the borders) per file, so
// that the module runs what icm_param runs; the GIL is released while they solve.

#ifndef ICM_MODULE_RUN_H
#define ICM_MODULE_RUN_H

#include "icm_module_request.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace icm_module {

/// What the report says of a run of either parameterizer, as icm_param's JSON line reads it
/// (its `Run_figures`): totals over the charts, the worst of each check.
struct Run_figures
{
  ICM::Surface_summary summary;
  std::size_t components = 1, seam_edges = 0;
  double seam_length = 0; ///< over the square root of the 3D area
  std::string energy = ICM::Curvature_entropy::name;
  std::optional<ICM::Energy_summary> energy_run; ///< an energy other than the entropy
  std::string boundary = "free";
  int degenerate_faces = 0, border_iterations = 0; ///< a prescribed border
  double circle_deviation = 0;
  int atlas_charts = 0, atlas_rotated_charts = 0;
  double atlas_utilization = 0;
  double seconds_index = 0, seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_total = 0;
};

/// ICM::parameterize with the energy and metric asked, as icm_param's `run_surface` calls it:
/// a user's cut is the whole singular set unless `cones` asked for automatic cones besides.
Run_figures run_surface(const Request& request, const Mesh& mesh, Corner_uv_map uv,
                        const std::map<Mesh::Vertex_index, double>& cones,
                        const std::vector<Mesh::Edge_index>& user_seams, std::vector<Mesh::Edge_index>& seams);

/// Inverse_curvature_map_parameterizer_3 with the border asked, on a disk (a circle domain:
/// genus 0 with borders), as icm_param's `run_border`; refused as icm_param refuses it: not
/// the surface the border needs, or a map that folds over itself unless `keep_overlaps`
/// (one chart with a UV per vertex cannot be cut apart where it folds, as a free border's is).
Run_figures run_border(const Request& request, Mesh& mesh, Corner_uv_map uv);

} // namespace icm_module

#endif // ICM_MODULE_RUN_H
