// The rows of one mesh (disk_rows.cpp, surface_rows.cpp): each method asked for, run in child
// processes, and printed as soon as it is done.

#ifndef ICM_BENCHMARK_COMPARE_ROWS_H
#define ICM_BENCHMARK_COMPARE_ROWS_H

#include "meshes.h"
#include "methods.h"
#include "options.h"
#include "row.h"

#include <string>
#include <vector>

namespace compare {

// A disk: the registry's methods (all when `asked` is empty), and the pipeline rows asked for.
void run_disk(const Mesh& mesh, const Row& base, const Options& opt, const std::vector<std::string>& asked,
              const std::vector<Method>& registry);

// A mesh that is not a disk: ICM's one call, CGAL's methods on its cut, and the other surface
// rows (surface_names() when `asked` is empty).
void run_surface(const Mesh& mesh, const Topology& topology, Row base, const Options& opt,
                 const std::vector<std::string>& asked, const std::vector<Method>& registry,
                 const std::vector<Seam_method>& seam_registry);

// ICM's report of ICM::parameterize() in a row: the named numbers as JSON keys, the counts
// and stage times in the Markdown status.
void add_icm_report(Row& row, const Child_result& result);

// A registry method's row, with ICM's report when it has one.
Row run_method(const Mesh& mesh, const Method& method, const Options& opt, Row row);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_ROWS_H
