// icm.parameterize with the curvature entropy (its default energy) in each metric: icm_param's
// `parameterize_surface` (examples/icm_param_energy.h) for ICM::Curvature_entropy, in a file of
// its own as icm_param's other energies are, so that the module's files compile in parallel and
// a change to the bindings (icm_module.cpp) recompiles none of the solver.

#include "icm_param_energy_impl.h"

namespace icm_param {
template ICM::Surface_parameterization_report parameterize_surface<ICM::Curvature_entropy>(
  const Mesh& mesh, const std::string& metric, Corner_uv_map uv, const ICM::Surface_parameterization_options& options,
  const std::map<Mesh::Vertex_index, double>& cones, std::vector<Mesh::Edge_index>& seams,
  const std::vector<Mesh::Edge_index>& user_seams);
} // namespace icm_param
