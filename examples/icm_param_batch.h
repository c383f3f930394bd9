// icm_param's batches: `icm_param IN... -O OUTDIR -j N` runs each input in a process of its
// own (this executable again, with `--batch-item INPUT`), so that a mesh that crashes, runs
// past --timeout or past --max-memory fails alone and the batch goes on. Each finished mesh
// adds a row to OUTDIR/summary.jsonl; --resume skips inputs whose row says "ok" and whose
// output exists. This file knows nothing of meshes: the child does the work, and says how it
// went in its --json line.

#ifndef ICM_PARAM_BATCH_H
#define ICM_PARAM_BATCH_H

#include <string>
#include <vector>

namespace icm_param {

/// What `-O`, `-j`, `--list`, `--format`, `--resume`, `--timeout` and `--max-memory` ask.
struct Batch_options
{
  std::vector<std::string> inputs; ///< the positional inputs, then those of --list
  std::string output_dir;          ///< -O: where OUTDIR/NAME.FORMAT and summary.jsonl go
  std::string list;                ///< --list: a file of input paths, one a line
  std::string format = "obj";      ///< --format: the outputs' extension
  int jobs = 1;                    ///< -j: meshes run at once
  bool resume = false;             ///< --resume: skip inputs already done
  bool quiet = false;              ///< -q: no progress lines
  bool json = false;               ///< --json: also print each summary row on stdout
  double timeout = 0;              ///< --timeout: seconds per mesh, 0 for none
  double max_memory_mb = 0;        ///< --max-memory: megabytes of address space per mesh, 0 for none
};

/// The input paths of a --list file (one a line; blank lines and lines starting with '#'
/// skipped), appended to `inputs`; false with the reason in `error`.
bool read_input_list(const std::string& path, std::vector<std::string>& inputs, std::string& error);

/// OUTDIR/STEM.FORMAT: where the batch writes `input`'s output.
std::string batch_output_path(const std::string& output_dir, const std::string& input, const std::string& format);

/// Why the batch cannot start (two inputs on one output, no input, OUTDIR not a directory
/// and not creatable), or empty. Creates OUTDIR when missing.
std::string check_batch(const Batch_options& options);

/// Limits this process's address space to `megabytes` (a child's --max-memory); false with
/// the reason in `error`.
bool limit_memory(double megabytes, std::string& error);

/// Runs the batch: each input through `argv` (this executable's own command line) with
/// `--batch-item INPUT` added, at most `jobs` at once. Returns the exit code: 0 when every
/// mesh is written, 1 when some failed (the summary says which and why).
int run_batch(const Batch_options& options, int argc, char** argv);

} // namespace icm_param

#endif // ICM_PARAM_BATCH_H
