// The arguments of `icm.parameterize` but V and F, each checked, as icm_param checks its
// command line: the names and options into a `Request` (what icm_param's `Arguments` hold),
// the arguments that icm_param refuses together refused together, for the same reason, and
// the cones and seams named by rows of V found on the mesh.

#ifndef ICM_MODULE_REQUEST_H
#define ICM_MODULE_REQUEST_H

#include "icm_module_arrays.h"

#include <ICM/parameterize.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace icm_module {

/// The names `energy`, `metric` and `boundary` take, the default first: icm_param's
/// --energy, --metric and --boundary.
const std::vector<std::string>& energy_names();
const std::vector<std::string>& metric_names();
const std::vector<std::string>& boundary_names();

/// The arguments of `icm.parameterize` but the arrays, each checked: what icm_param's
/// `Arguments` hold once its command line is parsed.
struct Request
{
  std::string energy, metric, boundary;
  /// `cones` is a count > 0 (icm_param's `--cones N`): automatic cones on the components
  /// without user seams too, and refused with a prescribed border. `cones=0` turns them off,
  /// which is no request, and "auto" is the default, which cannot be told from none either.
  bool cones_asked = false;
  bool keep_overlaps = false;
  ICM::Surface_parameterization_options options;

  bool prescribes_border() const { return boundary != "free"; }
};

/// The arguments of `icm.parameterize` but the arrays, the cone and the seams, each checked,
/// or `Icm_error` naming the one at fault (with ICM's error code for an option that
/// ICM::check_options refuses).
Request request_of(const py::object& cones, const std::string& energy, const std::string& metric,
                   const std::string& boundary, const py::object& atlas, int padding, bool keep_overlaps);

/// Why the arguments cannot go together, or empty, as icm_param refuses them before reading
/// the mesh (its `energy_conflict` and `parse_atlas`): a prescribed border leaves no choice
/// to an energy, is solved on a disk without cones or seams, and packs no atlas.
std::string border_conflict(const Request& request, bool has_cone, bool has_seams);

/// The mesh's vertices that each row of V became: none for a dropped vertex, several for a
/// split one (icm_param's `vertices_by_file_index`).
using Vertices_by_row = std::vector<std::vector<Mesh::Vertex_index>>;

Vertices_by_row vertices_by_row(const ICM::IO::Mesh_reading_report& read);

/// `cone`'s (row of V, degrees) as curvatures at the mesh's vertices (icm_param's --cone).
std::map<Mesh::Vertex_index, double> user_cones_of(const std::vector<std::pair<long long, double>>& cone,
                                                   const Vertices_by_row& by_row);

/// The edges `seams` names, an (s, 2) array of pairs of rows of V, as icm_param reads the
/// edges of a --seams file (ICM::IO::read_selection): a pair names the edge between the
/// vertices its rows became (any copy of a split vertex), each edge is kept once, in the
/// array's order. A pair that names no interior edge is refused naming its row; the library
/// would refuse a border edge too, without saying which.
std::vector<Mesh::Edge_index> user_seams_of(const py::object& seams, const Mesh& mesh, const Vertices_by_row& by_row);

} // namespace icm_module

#endif // ICM_MODULE_REQUEST_H
