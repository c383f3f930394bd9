// The result of `icm.parameterize`: the UVs on the rows of F, the seams on the rows of V, and
// the report, the run's figures under the keys of icm_param's JSON line (doc/cli.md).

#ifndef ICM_MODULE_RESULT_H
#define ICM_MODULE_RESULT_H

#include "icm_module_run.h"

#include <ICM/measures/Distortion.h>

#include <cstdint>
#include <string>
#include <vector>

namespace icm_module {

/// The result of `icm.parameterize`.
struct Parameterization
{
  py::array_t<double> uv;
  py::array_t<std::int64_t> fuv;
  int charts = 0;
  py::array_t<std::int64_t> seams;
  py::dict report;
};

/// The run's figures under the keys of icm_param's JSON line (doc/cli.md), in its order.
py::dict report_dict(const Mesh& mesh, const Run_figures& t, const Request& request,
                     const ICM::IO::Mesh_reading_report& read, const ICM::Distortion_measures& m);

/// The UVs of `uvmap` on the rows of F and the seams on the rows of V: face f of the mesh is
/// row f of F (no face is added or dropped), whose corners may have been reversed (a
/// reoriented face) or renumbered (a dropped or split vertex).
Parameterization result_of(const py::object& F, const Mesh& mesh, Corner_uv_map uvmap,
                           const std::vector<Mesh::Edge_index>& seams, const ICM::IO::Mesh_reading_report& read);

/// " (the input was repaired: ...)", or empty: a failure after the repairs names them, as
/// icm_param's do, since they may be why (a dropped vertex).
std::string repairs_note(const ICM::IO::Mesh_reading_report& read);

} // namespace icm_module

#endif // ICM_MODULE_RESULT_H
