// compare's output (output.cpp, svg_panels.cpp): the rows as a Markdown table or JSON lines
// (and with --json-file also as JSON lines in a file), and the --svg-panels picture.

#ifndef ICM_BENCHMARK_COMPARE_OUTPUT_H
#define ICM_BENCHMARK_COMPARE_OUTPUT_H

#include "methods.h"
#include "options.h"
#include "row.h"

#include <string>
#include <vector>

namespace compare {

// A measured number in JSON: 10 significant digits (as the Markdown and the previous JSON
// lines gave them), null when not finite.
Json json_num(double x);

// A count in JSON: an integer, null when not finite.
Json json_count(double x);

// A count in the Markdown: digits, empty when not finite.
std::string count_text(double x);

// Seconds with three significant digits below 10 s (0.00291, 0.0412, 1.23), else 0.1 s.
std::string fmt_seconds(double x);

// Opens the --json-file stream; false when the file cannot be written.
bool open_json_file(const std::string& path);

// The title, the machine, the date, the runs and the table's header (Markdown only).
void print_markdown_preamble(const Options& opt);

// One row on stdout (JSON or Markdown; `first` names the model) and, with --json-file, as
// JSON in that file.
void emit(const Row& row, bool first, const Options& opt);

// --svg-panels: the UV layouts of panel_methods on the mesh at `mesh_path`, recomputed in
// this process (no time limit) for the picture; false with the reason on stderr.
bool write_panels(const std::string& mesh_path, const Options& opt, const std::vector<Method>& registry);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_OUTPUT_H
