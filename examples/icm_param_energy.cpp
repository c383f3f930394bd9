// icm_param --energy NAME: the energy chosen by its name; the parameterizer of each energy is
// instantiated in its own file (icm_param_energy_*.cpp).

#include "icm_param_energy.h"

#include <ICM/Energies.h>

namespace icm_param {

ICM::Parameterization_report parameterize_disk_with_energy(Mesh& mesh, const std::string& energy,
                                                           const std::string& metric, Corner_uv_map uv)
{
  if(energy == ICM::U_square::name)
    return parameterize_disk<ICM::U_square>(mesh, metric, uv);
  if(energy == ICM::Area_distortion::name)
    return parameterize_disk<ICM::Area_distortion>(mesh, metric, uv);
  if(energy == ICM::Angle_distortion::name)
    return parameterize_disk<ICM::Angle_distortion>(mesh, metric, uv);
  return parameterize_disk<ICM::Log_area_distortion>(mesh, metric, uv);
}

} // namespace icm_param
