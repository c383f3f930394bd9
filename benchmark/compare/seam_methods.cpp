// CGAL's methods on a seam mesh (methods.h): a surface that is not a disk, cut along ICM's
// seams, with one UV per corner.

#include "methods.h"

#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>

namespace compare {

namespace {

template <class Parameterizer>
Seam_method seam_cgal_method(std::string name)
{
  return {std::move(name), [](Seam_mesh& mesh, seam_halfedge_descriptor bhd, Corner_UV_map uvmap) {
            return timed_parameterize(mesh, Parameterizer(), bhd, uvmap);
          }};
}

} // namespace

std::vector<Seam_method> make_seam_registry()
{
  return {
    seam_cgal_method<SMP::LSCM_parameterizer_3<Seam_mesh>>("lscm"),
    seam_cgal_method<SMP::ARAP_parameterizer_3<Seam_mesh>>("arap"),
    seam_cgal_method<SMP::Discrete_conformal_map_parameterizer_3<Seam_mesh>>("dcm"),
    seam_cgal_method<SMP::Discrete_authalic_parameterizer_3<Seam_mesh>>("dac"),
    seam_cgal_method<SMP::Mean_value_coordinates_parameterizer_3<Seam_mesh>>("mvc"),
  };
}

} // namespace compare
