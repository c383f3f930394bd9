// Running a job in child processes (run.cpp): one run under the time limit, and all the runs
// of one row with the median time.

#ifndef ICM_BENCHMARK_COMPARE_RUN_H
#define ICM_BENCHMARK_COMPARE_RUN_H

#include "jobs.h"
#include "options.h"
#include "row.h"

#include <string>

namespace compare {

struct Child_outcome
{
  enum Kind
  {
    finished,
    timeout,
    crashed,
    lost
  } kind = lost;
  int signal = 0;
  int exit_code = 0;
  double peak_rss_mb = NaN; // timeout only: the child's peak memory when it was killed
  Child_result result;
};

// One run of `job` in a child process of its own, killed after `time_limit` seconds.
Child_outcome run_in_child(const Job& job, bool measure, double time_limit);

// The status column of a run: "ok", "timeout", "crashed (...)" or "failed: ...".
std::string status_of(const Child_outcome& o);

// All runs of one job on one mesh: the first run measures; more runs only time. The first
// run's result goes to `first_result` when given (ICM's seams and report), its stage times
// the medians over the runs.
Row run_job(const Job& job, const std::string& name, const Options& opt, Row row, Child_result* first_result = nullptr);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_RUN_H
