// compare's command line (options.cpp, parsed with CLI11).

#ifndef ICM_BENCHMARK_COMPARE_OPTIONS_H
#define ICM_BENCHMARK_COMPARE_OPTIONS_H

#include <string>
#include <vector>

namespace compare {

struct Options
{
  bool json = false;
  bool quiet = false;
  int runs = 0; // 0: automatic (3 if one run takes < 2 s, else 1)
  double time_limit = 600.0;
  int subdivide = 0;
  bool open = false;
  std::vector<std::string> methods; // empty: all
  std::string svg_panels;
  std::string json_file;  // --json-file: the JSON lines also go to this file
  std::string write_mesh; // --write-mesh: the prepared mesh (triangulated, subdivided, opened) to this file
  std::vector<std::string> meshes;
};

// The options of the command line. `known_methods` are the names --methods takes. After
// --help prints the usage and exits with 0; a wrong command line prints the reason (and
// mostly the usage) on stderr and exits with 2.
Options parse_options(int argc, char** argv, const std::vector<std::string>& known_methods);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_OPTIONS_H
