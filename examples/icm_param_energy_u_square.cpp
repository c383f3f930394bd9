// icm_param --energy u-square: the parameterizer for ICM::U_square, in a file of its own
// so that the energies compile in parallel (icm_param_energy.h).

#include "icm_param_energy_impl.h"

namespace icm_param {
template ICM::Parameterization_report parameterize_disk<ICM::U_square>(Mesh& mesh, const std::string& metric,
                                                                  Corner_uv_map uv);
} // namespace icm_param
