// icm_param's runs of Inverse_curvature_map_parameterizer_3<Mesh, Metric, CGAL::Default,
// Energy, Border>: an energy other than the curvature entropy (free border, on a disk), or a
// border condition other than the free one (--boundary, with the entropy). Declared here and
// instantiated one energy, or the border conditions, per translation unit
// (icm_param_energy_*.cpp, icm_param_border.cpp): each file (one energy, four metrics) takes about 41 s of CPU at
// -O3 on a 2-core EPYC, icm_param.cpp 68 s; sixteen instantiations in icm_param.cpp would make
// one file of some 2.5 minutes, while in five files `make -j2` builds them in about two.

#ifndef ICM_PARAM_ENERGY_H
#define ICM_PARAM_ENERGY_H

#include <ICM/Inverse_curvature_map_parameterizer_3.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <string>

namespace icm_param {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
/// A UV per corner: the UV of target(h) in face(h), as ICM::parameterize writes it.
using Corner_uv_map = Mesh::Property_map<Mesh::Halfedge_index, Kernel::Point_2>;

/// The minimum of `Energy` over the conformal maps of `mesh` with the border condition `Border`
/// in the class of the metric named `metric` (`Metric::name`), by CGAL's parameterize() from
/// the mesh's longest border. Every corner of a face gets its vertex's UV in `uv`. The caller
/// checks that `mesh` is one component (the parameterizer would take only the border's).
template <class Energy, class Border = ICM::Free_border>
ICM::Parameterization_report parameterize_disk(Mesh& mesh, const std::string& metric, Corner_uv_map uv);

} // namespace icm_param

#endif // ICM_PARAM_ENERGY_H
