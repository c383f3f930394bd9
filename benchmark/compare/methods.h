// compare's methods: the registry of the parameterizers run on a disk (ICM's, CGAL's), CGAL's
// on a seam mesh (a surface that is not a disk, cut along ICM's seams), and the names of the
// rows of a surface that is not a disk (ICM's pipeline, ...).

#ifndef ICM_BENCHMARK_COMPARE_METHODS_H
#define ICM_BENCHMARK_COMPARE_METHODS_H

#include "mesh_types.h"

#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace compare {

namespace SMP = CGAL::Surface_mesh_parameterization;

// A method takes a fresh mesh, its longest border halfedge and an empty UV map; it returns
// the error code, the wall time of the parameterize() call and, for ICM, the solver's report.
struct Run_result
{
  SMP::Error_code code = SMP::OK;
  double seconds = NaN;                 // wall time of the parameterize() call only
  std::string message;                  // extra failure reason (ICM's report)
  std::optional<int> newton_iterations; // ICM only
  std::string metric;                   // ICM only: the metric of the result (after a fallback)
  std::string fallback_reason;          // ICM only: why the requested metric was not used
  // ICM only: the report's times and, for an energy other than the entropy, its optimizer's
  // steps and values (energy_iterations, initial_energy, final_energy).
  std::vector<std::pair<std::string, double>> report_numbers;
};

struct Method
{
  std::string name;
  std::function<Run_result(Mesh&, halfedge_descriptor, UV_map)> run;
};

// CGAL's methods on a seam mesh; the names are those of the registry's CGAL rows.
struct Seam_method
{
  std::string name;
  std::function<Run_result(Seam_mesh&, seam_halfedge_descriptor, Corner_UV_map)> run;
};

// Times CGAL's free function parameterize(); `p` is passed on by value, as CGAL does.
template <class TriangleMesh, class Parameterizer, class UVMap>
Run_result timed_parameterize(TriangleMesh& mesh, const Parameterizer& p,
                              typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd, UVMap uvmap)
{
  Run_result r;
  const auto t0 = std::chrono::steady_clock::now();
  r.code = SMP::parameterize(mesh, p, bhd, uvmap);
  const auto t1 = std::chrono::steady_clock::now();
  r.seconds = std::chrono::duration<double>(t1 - t0).count();
  return r;
}

// The methods of a disk, in the order of the table (methods.cpp: add a method there with one
// line; its name is what --methods selects).
std::vector<Method> make_registry();

// CGAL's methods on a seam mesh (seam_methods.cpp).
std::vector<Seam_method> make_seam_registry();

// The registry's method named `name`, or nullptr.
const Method* find_method(const std::vector<Method>& registry, const std::string& name);

// Rows of a surface that is not a disk, besides the seam-mesh CGAL methods (methods.cpp).
extern const std::vector<std::string> surface_methods;

extern const std::string u_square_cones_prefix;

// The cone count of an icm_cones_N or icm_u_square_cones_N row, or -1 for another name.
int exact_cone_count(const std::string& name);

// The methods drawn by --svg-panels, in this order.
extern const std::vector<std::string> panel_methods;

// UVs are worth measuring when the method produced a complete map (possibly with flips).
inline bool has_usable_uvs(SMP::Error_code code)
{
  return code == SMP::OK || code == SMP::ERROR_NO_1_TO_1_MAPPING;
}

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_METHODS_H
