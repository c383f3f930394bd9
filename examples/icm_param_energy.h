// icm_param's runs other than the entropy's, declared here and instantiated one energy, or
// the border conditions, per translation unit (icm_param_energy_*.cpp, icm_param_border.cpp):
// - `parameterize_surface<Energy>`: ICM::parameterize with an energy other than the curvature
//   entropy (--energy), on every surface, with its cones and seams;
// - `parameterize_disk<Border>`: Inverse_curvature_map_parameterizer_3 with the entropy and
//   a prescribed border condition (--boundary), on a disk.
// Each file (one energy, four metrics) takes about 40 s of CPU at -O3 on a 2-core EPYC,
// icm_param.cpp 68 s; all in icm_param.cpp would make one file of several minutes, while in
// six files `make -j2` builds them in about half that. The Python module compiles the same
// files (python/CMakeLists.txt), with the entropy's runs in its own, to run what icm_param runs.

#ifndef ICM_PARAM_ENERGY_H
#define ICM_PARAM_ENERGY_H

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/border/Border_shape.h>

#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <map>
#include <string>
#include <vector>

namespace icm_param {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
/// A UV per corner: the UV of target(h) in face(h), as ICM::parameterize writes it.
using Corner_uv_map = Mesh::Property_map<Mesh::Halfedge_index, Kernel::Point_2>;

/// `ICM::parameterize` with `Energy` in the class of the metric named `metric`
/// (`Metric::name`): the seams of every chart into `seams`.
template <class Energy>
ICM::Surface_parameterization_report parameterize_surface(const Mesh& mesh, const std::string& metric, Corner_uv_map uv,
                                                          const ICM::Surface_parameterization_options& options,
                                                          const std::map<Mesh::Vertex_index, double>& cones,
                                                          std::vector<Mesh::Edge_index>& seams,
                                                          const std::vector<Mesh::Edge_index>& user_seams);

/// The curvature entropy's conformal map of `mesh` with the border condition `Border` in the
/// class of the metric named `metric`, by CGAL's parameterize() from the mesh's longest
/// border. Every corner of a face gets its vertex's UV in `uv`. The caller checks that `mesh`
/// is one component (the parameterizer would take only the border's).
template <class Border>
ICM::Parameterization_report parameterize_disk(Mesh& mesh, const std::string& metric, Corner_uv_map uv);

/// Why `mesh` is not the surface the prescribed border `boundary` needs (a disk; a genus-0
/// surface with borders for circle-domain), as a sentence that starts with `asked` (how the
/// caller names the option: "--boundary circle"), or empty. The disk parameterizer would
/// take only the longest border's component, and find no border on a closed mesh.
std::string why_the_border_is_refused(const std::string& asked, const std::string& boundary, Mesh& mesh);

} // namespace icm_param

#endif // ICM_PARAM_ENERGY_H
