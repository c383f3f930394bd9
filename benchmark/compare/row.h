// One (mesh, method) row of compare's table, as the output writes it (output.h).

#ifndef ICM_BENCHMARK_COMPARE_ROW_H
#define ICM_BENCHMARK_COMPARE_ROW_H

#include "child_result.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace compare {

// Keys stay in the order they are set, as the JSON lines always listed them.
using Json = nlohmann::ordered_json;

struct Row
{
  std::string mesh;
  std::size_t vertices = 0, faces = 0;
  std::string method;
  std::string status;
  double seconds = NaN;
  double peak_rss_mb = NaN;
  bool has_measures = false;
  Measures m;
  std::optional<int> newton_iterations;
  std::string metric;
  // Surfaces that are not disks only (empty for a disk, whose output is unchanged):
  std::string topology; // "genus G, B loops", shown in the Markdown model label
  std::string detail;   // shown in parentheses after the method in Markdown (e.g. the cut)
  std::string note;     // appended to the Markdown status (e.g. ICM's stage times)
  std::vector<std::pair<std::string, Json>> json_extra; // key, value
};

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_ROW_H
