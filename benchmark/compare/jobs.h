// What a child process does for one row: copy the mesh, run the method, measure (jobs.cpp,
// and icm_jobs.cpp for ICM's whole pipeline).

#ifndef ICM_BENCHMARK_COMPARE_JOBS_H
#define ICM_BENCHMARK_COMPARE_JOBS_H

#include "child_result.h"
#include "methods.h"

#include <functional>
#include <string>
#include <vector>

namespace compare {

// Fills `r` (copy the mesh, run, measure). `measure` is false for the extra timing runs.
using Job = std::function<void(Child_result& r, bool measure)>;

// A registry method on a disk: its own copy of the mesh, the longest border, a vertex UV map.
Job method_job(const Mesh& input, const Method& method);

// A CGAL method on the mesh cut along `seams` (edge indices of the mesh): a CGAL::Seam_mesh,
// its longest border (the cut, plus the holes it joins) as the border halfedge, one UV per
// seam-mesh vertex stored at its halfedge. The cut must make one disk; else the row says so.
Job seam_job(const Mesh& input, const std::vector<std::size_t>& seams, const Seam_method& method);

// The job of an icm, icm_keep_overlaps or exact-cone-count row (ICM::parameterize()).
Job icm_pipeline_job(const Mesh& mesh, const std::string& name);

// The job of a surface row with an energy (icm_u_square, ...), or none for another name.
Job icm_energy_job(const Mesh& mesh, const std::string& name);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_JOBS_H
