// icm_param --boundary circle|square|circle-domain: the parameterizer with the curvature entropy
// and each prescribed border condition, in a file of its own so that it compiles in parallel
// with the energies (icm_param_energy.h).

#include "icm_param_energy_impl.h"

#include <ICM/border/Border_conditions.h>
#include <ICM/border/Border_shape.h>

namespace icm_param {
template ICM::Parameterization_report
parameterize_disk<ICM::Circular_border<Mesh>>(Mesh& mesh, const std::string& metric, Corner_uv_map uv);
template ICM::Parameterization_report parameterize_disk<ICM::Square_border<Mesh>>(Mesh& mesh, const std::string& metric,
                                                                                  Corner_uv_map uv);
template ICM::Parameterization_report parameterize_disk<ICM::Circle_domain>(Mesh& mesh, const std::string& metric,
                                                                            Corner_uv_map uv);
} // namespace icm_param
