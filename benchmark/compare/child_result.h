// What a child process measures of one method run and sends back to compare through its pipe,
// as a JSON object (child_result.cpp).

#ifndef ICM_BENCHMARK_COMPARE_CHILD_RESULT_H
#define ICM_BENCHMARK_COMPARE_CHILD_RESULT_H

#include "mesh_types.h"

#include <ICM/measures/Distortion.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace compare {

struct Measures
{
  double faces = NaN, flipped = NaN, degenerate = NaN;
  double conformality = NaN, angle_distortion = NaN, l2_shear = NaN, l2_stretch = NaN, log_area_distortion = NaN,
         log_area_weighted = NaN, qc_mean = NaN, qc_max = NaN, area_ratio_min = NaN, area_ratio_max = NaN;
};

Measures to_measures(const ICM::Distortion_measures& d);

struct Child_result
{
  bool complete = false; // the whole result arrived
  int code = 0;
  double seconds = NaN;
  double peak_rss_mb = NaN;
  bool has_measures = false;
  Measures m;
  std::optional<int> newton_iterations;
  std::string metric;
  std::string message;
  std::string exception;
  std::vector<std::pair<std::string, double>> extra; // named numbers (ICM's report), in order
  std::string fallback_reason;                       // ICM's, when it fell back
  std::vector<std::size_t> seams;                    // ICM's seam edges (edge indices)
};

// The named number `key` of the result, NaN when it has none.
double extra_value(const Child_result& r, const std::string& key);

// The result as the child writes it to its pipe: one JSON object, its texts on one line.
std::string to_pipe_text(const Child_result& r);

// The result the parent reads from the pipe; not `complete` when the text is not a whole
// result (the child died before it was written).
Child_result from_pipe_text(const std::string& text);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_CHILD_RESULT_H
