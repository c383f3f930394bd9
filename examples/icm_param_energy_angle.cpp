// icm_param --energy angle: ICM::parameterize with ICM::Angle_distortion, in a file of its own so that
// the energies compile in parallel (icm_param_energy.h).

#include "icm_param_energy_impl.h"

namespace icm_param {
template ICM::Surface_parameterization_report parameterize_surface<ICM::Angle_distortion>(
  const Mesh& mesh, const std::string& metric, Corner_uv_map uv, const ICM::Surface_parameterization_options& options,
  const std::map<Mesh::Vertex_index, double>& cones, std::vector<Mesh::Edge_index>& seams,
  const std::vector<Mesh::Edge_index>& user_seams);
} // namespace icm_param
