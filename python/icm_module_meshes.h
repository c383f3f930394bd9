// The functions of the module `icm` on meshes and their UVs but parameterize: ICM's checked
// mesh readers and UV mesh writers, and the distortion measures, on numpy arrays.

#ifndef ICM_MODULE_MESHES_H
#define ICM_MODULE_MESHES_H

#include "icm_module_arrays.h"

#include <string>

namespace icm_module {

/// `icm.read_mesh`: (V, F, the repairs made) of a mesh file, or `Icm_error` with the reason.
py::tuple read_mesh(const std::string& path, bool triangulate);

/// `icm.write_mesh`: the mesh with its UVs in the format of the extension, or `Icm_error`.
void write_mesh(const std::string& path, const py::object& V, const py::object& F, const py::object& uv,
                const py::object& fuv, bool binary_ply);

/// `icm.measure_distortion`: the distortion figures of the map from (V, F) to (uv, fuv) under
/// the names of icm_param's JSON line.
py::dict measure_distortion(const py::object& V, const py::object& F, const py::object& uv, const py::object& fuv);

} // namespace icm_module

#endif // ICM_MODULE_MESHES_H
