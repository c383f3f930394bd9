// icm_param's batches (icm_param_batch.h): a process per mesh, at most -j at
// once, a row of OUTDIR/summary.jsonl per mesh.

#include "icm_param_batch.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#ifndef _WIN32
#include <child_process.h>

#include <csignal>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace icm_param {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string trimmed(const std::string& s)
{
  const std::size_t first = s.find_first_not_of(" \t\r\n");
  if(first == std::string::npos)
    return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::string read_whole(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The last line of `text` that is not blank.
std::string last_line(const std::string& text)
{
  std::string last;
  std::istringstream in(text);
  for(std::string line; std::getline(in, line);)
    if(!trimmed(line).empty())
      last = trimmed(line);
  return last;
}

/// "12 s", "3 min 20 s": a duration for the progress line.
std::string duration_text(double seconds)
{
  const long s = std::lround(seconds);
  if(s < 60)
    return std::to_string(s) + " s";
  if(s < 3600)
    return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string(s % 3600 / 60) + " min";
}

std::string seconds_text(double seconds)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(seconds < 10 ? 2 : 1) << seconds << " s";
  return text.str();
}

/// One mesh of the batch, and how it went.
struct Item
{
  std::string input, output;
  Json row; ///< null until it ran; the earlier run's when --resume skips it
};

/// The rows of an earlier summary.jsonl by input (the last row of each: a
/// resumed batch appends). A line a killed batch cut short is not JSON and is
/// ignored.
std::map<std::string, Json> earlier_rows(const fs::path& summary)
{
  std::map<std::string, Json> rows;
  std::ifstream in(summary);
  for(std::string line; std::getline(in, line);)
  {
    Json row = Json::parse(line, nullptr, false);
    if(row.is_object() && row.contains("input") && row["input"].is_string())
    {
      const std::string input = row["input"].get<std::string>();
      rows[input] = std::move(row);
    }
  }
  return rows;
}

/// The string under `key`, or empty: an earlier summary is a file anyone may
/// have edited.
std::string string_at(const Json& row, const char* key)
{
  const auto value = row.find(key);
  return value != row.end() && value->is_string() ? value->get<std::string>() : std::string();
}

bool was_done(const Json& row, const std::string& output)
{
  std::error_code ec;
  return string_at(row, "status") == "ok" && string_at(row, "output") == output && fs::is_regular_file(output, ec);
}

/// The row of a mesh: what the batch knows, then the child's figures (its
/// --json line).
Json make_row(const Item& item, bool ok, const std::string& error, double seconds, const Json& figures)
{
  Json row;
  row["input"] = item.input;
  row["output"] = item.output;
  row["status"] = ok ? "ok" : "failed";
  row["error"] = error;
  row["seconds"] = seconds;
  if(ok)
    for(const auto& [key, value] : figures.items())
      if(key != "input" && key != "output")
        row[key] = value;
  return row;
}

std::string dump(const Json& row)
{
  return row.dump(-1, ' ', false, Json::error_handler_t::replace);
}

/// Replaces `summary` with one row per item, in input order, all or nothing.
bool write_summary(const fs::path& summary, const std::vector<Item>& items, std::string& error)
{
  const fs::path temporary = summary.string() + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    for(const Item& item : items)
      if(!item.row.is_null())
        out << dump(item.row) << "\n";
    out.flush();
    if(!out)
    {
      error = "cannot write '" + temporary.string() + "'";
      return false;
    }
  }
  std::error_code ec;
  fs::rename(temporary, summary, ec);
  if(ec)
  {
    error = "cannot replace '" + summary.string() + "': " + ec.message();
    fs::remove(temporary, ec);
    return false;
  }
  return true;
}

#ifndef _WIN32

/// A child process running one item.
struct Child
{
  icm_tools::Child_process process;
  std::size_t item = 0;
  Clock::time_point start;
  fs::path out, err; // its captured stdout and stderr
  bool timed_out = false;
};

/// Starts this executable on `input`: `argv` with `--batch-item INPUT` added,
/// its stdout and stderr into the child's files; false (errno says why) when no
/// process started.
bool spawn(Child& child, int argc, char** argv, const std::string& input)
{
  std::vector<std::string> words(argv, argv + argc);
  words.push_back("--batch-item");
  words.push_back(input);
  std::vector<char*> child_argv;
  for(std::string& word : words)
    child_argv.push_back(word.data());
  child_argv.push_back(nullptr);
  icm_tools::Child_setup setup;
  setup.stdout_path = child.out.string();
  setup.stderr_path = child.err.string();
  const char* self = argv[0];
  const auto exec = [&child_argv, self](int) {
    // In the child: only async-signal-safe calls until exec.
    ::execv("/proc/self/exe", child_argv.data());
    ::execv(self, child_argv.data());
    return 127;
  };
  std::string failed_call;
  return child.process.start(exec, setup, failed_call);
}

/// " (SIGSEGV)": the name of a signal a crash ends with, as icm.batch writes
/// it, or empty.
std::string signal_name(int signal)
{
  for(const auto& [number, name] : {std::pair<int, const char*>{SIGSEGV, "SIGSEGV"},
                                    {SIGABRT, "SIGABRT"},
                                    {SIGBUS, "SIGBUS"},
                                    {SIGFPE, "SIGFPE"},
                                    {SIGILL, "SIGILL"},
                                    {SIGKILL, "SIGKILL"},
                                    {SIGTERM, "SIGTERM"}})
    if(signal == number)
      return std::string(" (") + name + ")";
  return {};
}

/// Why a child that ended as `exit` says failed, or empty when it wrote its
/// outputs; its figures (the --json line) in `figures`.
std::string failure_of(const Child& child, const icm_tools::Child_exit& exit, const Batch_options& options,
                       Json& figures)
{
  if(child.timed_out)
  {
    std::ostringstream text;
    text << "timed out after " << options.timeout << " s";
    return text.str();
  }
  const std::string out = read_whole(child.out), err = read_whole(child.err);
  const Json line = Json::parse(last_line(out), nullptr, false);
  std::string reason;
  if(exit.signaled)
    reason = "crashed: signal " + std::to_string(exit.signal) + signal_name(exit.signal);
  else if(exit.code == 0)
  {
    if(line.is_object() && !line.contains("error"))
    {
      figures = line;
      return {};
    }
    reason = "the process printed no figures";
  }
  else if(line.is_object() && line.contains("error") && line["error"].is_string())
    reason = line["error"].get<std::string>();
  else if(exit.code == 127)
    reason = "cannot start " + std::string("/proc/self/exe");
  else
    reason = "the process exited with status " + std::to_string(exit.code) +
             (last_line(err).empty() ? "" : ": " + last_line(err));
  // An allocation refused under the limit shows as "out of memory", or as a
  // crash in a library that does not check: either way the limit is the likely
  // cause.
  if(options.max_memory_mb > 0 && (exit.signaled || reason.find("memory") != std::string::npos))
  {
    std::ostringstream text;
    text << reason << " (--max-memory " << options.max_memory_mb << " MB)";
    reason = text.str();
  }
  return reason;
}

/// The progress line of a finished mesh: the count, its outcome, elapsed time
/// and the time left at the pace so far.
void print_progress(std::size_t done, std::size_t to_run, const Item& item, double elapsed)
{
  const bool ok = item.row.value("status", "") == "ok";
  std::cerr << "icm_param: [" << done << "/" << to_run << "] " << (ok ? "ok " : "failed ")
            << fs::path(item.input).filename().string();
  if(ok)
    std::cerr << " (" << seconds_text(item.row.value("seconds", 0.0)) << ")";
  else
    std::cerr << ": " << item.row.value("error", "");
  std::cerr << ", elapsed " << duration_text(elapsed);
  if(done < to_run)
    std::cerr << ", ETA " << duration_text(elapsed / double(done) * double(to_run - done));
  std::cerr << std::endl;
}

/// The batch's items, once each in input order, those --resume finds done with
/// their earlier row; returns the indices of the items to run.
std::vector<std::size_t> plan_items(const Batch_options& options, const fs::path& summary, std::vector<Item>& items)
{
  const std::map<std::string, Json> earlier = options.resume ? earlier_rows(summary) : std::map<std::string, Json>();
  std::vector<std::size_t> to_run;
  std::map<std::string, bool> seen;
  for(const std::string& input : options.inputs)
  {
    if(seen[input]) // an input listed twice runs once
      continue;
    seen[input] = true;
    Item item;
    item.input = input;
    item.output = batch_output_path(options.output_dir, input, options.format);
    if(const auto row = earlier.find(input); row != earlier.end() && was_done(row->second, item.output))
      item.row = row->second;
    else
      to_run.push_back(items.size());
    items.push_back(std::move(item));
  }
  return to_run;
}

/// The items to run, at most -j children at once, each finished one's row in
/// the journal as soon as it ends.
class Batch_run
{
public:
  Batch_run(const Batch_options& options, int argc, char** argv, std::vector<Item>& items, std::ofstream& journal,
            const fs::path& scratch, Clock::time_point start)
    : options_(options), argc_(argc), argv_(argv), items_(items), journal_(journal), scratch_(scratch), start_(start)
  {}

  /// Runs the items `to_run`; returns how many failed.
  std::size_t run(const std::vector<std::size_t>& to_run)
  {
    to_run_ = &to_run;
    const std::size_t jobs = static_cast<std::size_t>(std::max(1, options_.jobs));
    while(next_ < to_run.size() || !running_.empty())
    {
      while(running_.size() < jobs && next_ < to_run.size())
        start_child(to_run[next_++]);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      reap_children();
    }
    return failed_;
  }

private:
  const Batch_options& options_;
  int argc_;
  char** argv_;
  std::vector<Item>& items_;
  std::ofstream& journal_;
  fs::path scratch_;
  Clock::time_point start_;
  const std::vector<std::size_t>* to_run_ = nullptr;
  std::vector<Child> running_;
  std::size_t next_ = 0, done_ = 0, failed_ = 0;

  void start_child(std::size_t index)
  {
    Child child;
    child.item = index;
    child.out = scratch_ / (std::to_string(index) + ".out");
    child.err = scratch_ / (std::to_string(index) + ".err");
    child.start = Clock::now();
    if(spawn(child, argc_, argv_, items_[index].input))
    {
      running_.push_back(child);
      return;
    }
    Item& item = items_[index];
    item.row = make_row(item, false, std::string("cannot start a process: ") + std::strerror(errno), 0, {});
    journal_ << dump(item.row) << "\n" << std::flush;
    ++done_, ++failed_;
  }

  /// The children that ended, or ran past --timeout (then killed), finished.
  void reap_children()
  {
    for(auto child = running_.begin(); child != running_.end();)
    {
      std::optional<icm_tools::Child_exit> exit = child->process.try_wait();
      if(!exit && options_.timeout > 0 && seconds_since(child->start) > options_.timeout)
      {
        child->timed_out = true;
        exit = child->process.kill();
      }
      if(!exit)
      {
        ++child;
        continue;
      }
      finish(*child, *exit);
      child = running_.erase(child);
    }
  }

  void finish(const Child& child, const icm_tools::Child_exit& exit)
  {
    Item& item = items_[child.item];
    Json figures;
    const std::string reason = failure_of(child, exit, options_, figures);
    item.row = make_row(item, reason.empty(), reason, seconds_since(child.start), figures);
    journal_ << dump(item.row) << "\n" << std::flush;
    if(options_.json)
      std::cout << dump(item.row) << std::endl;
    ++done_;
    failed_ += reason.empty() ? 0 : 1;
    if(!options_.quiet)
      print_progress(done_, to_run_->size(), item, seconds_since(start_));
    std::error_code ec;
    fs::remove(child.out, ec);
    fs::remove(child.err, ec);
  }
};

/// The batch's last line: how many meshes were written, skipped, failed, and
/// the time.
void print_totals(const Batch_options& options, std::size_t items, std::size_t skipped, std::size_t failed,
                  const fs::path& summary, Clock::time_point start)
{
  if(options.quiet && failed == 0)
    return;
  std::cerr << "icm_param: " << items - failed << " of " << items << " meshes written to " << options.output_dir;
  if(skipped > 0)
    std::cerr << " (" << skipped << " done before, skipped)";
  if(failed > 0)
    std::cerr << ", " << failed << " failed (" << summary.string() << ")";
  std::cerr << ", " << seconds_text(seconds_since(start)) << "\n";
}

#endif // _WIN32

} // namespace

bool read_input_list(const std::string& path, std::vector<std::string>& inputs, std::string& error)
{
  std::error_code ec;
  if(!fs::is_regular_file(path, ec))
  {
    error = "--list: cannot read '" + path + "': no such file";
    return false;
  }
  std::ifstream in(path);
  if(!in)
  {
    error = "--list: cannot read '" + path + "'";
    return false;
  }
  for(std::string line; std::getline(in, line);)
  {
    const std::string entry = trimmed(line);
    if(!entry.empty() && entry[0] != '#')
      inputs.push_back(entry);
  }
  return true;
}

std::string batch_output_path(const std::string& output_dir, const std::string& input, const std::string& format)
{
  return (fs::path(output_dir) / (fs::path(input).stem().string() + "." + format)).string();
}

std::string check_batch(const Batch_options& options)
{
  if(options.inputs.empty())
    return options.list.empty() ? "no input file" : "--list '" + options.list + "' names no input file";
  std::map<std::string, std::string> input_of_output;
  for(const std::string& input : options.inputs)
  {
    const std::string output = batch_output_path(options.output_dir, input, options.format);
    const auto [it, inserted] = input_of_output.emplace(output, input);
    if(!inserted && it->second != input)
      return "'" + it->second + "' and '" + input + "' would both be written to '" + output +
             "': give them different names, or run them in two batches";
  }
  std::error_code ec;
  if(fs::exists(options.output_dir, ec) && !fs::is_directory(options.output_dir, ec))
    return "-O: '" + options.output_dir + "' is not a directory";
  fs::create_directories(options.output_dir, ec);
  if(ec)
    return "-O: cannot create '" + options.output_dir + "': " + ec.message();
  return {};
}

bool limit_memory(double megabytes, std::string& error)
{
#ifndef _WIN32
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(megabytes * 1024.0 * 1024.0);
  if(::setrlimit(RLIMIT_AS, &limit) == 0)
    return true;
  error = std::string("--max-memory: cannot limit the memory: ") + std::strerror(errno);
#else
  (void)megabytes;
  error = "--max-memory needs a POSIX system";
#endif
  return false;
}

int run_batch(const Batch_options& options, int argc, char** argv)
{
#ifdef _WIN32
  (void)options, (void)argc, (void)argv;
  std::cerr << "icm_param: batches (-O) need a POSIX system\n";
  return 2;
#else
  const Clock::time_point start = Clock::now();
  const fs::path summary = fs::path(options.output_dir) / "summary.jsonl";
  std::vector<Item> items;
  const std::vector<std::size_t> to_run = plan_items(options, summary, items);

  std::ofstream journal(summary, options.resume ? std::ios::app : std::ios::trunc);
  if(!journal)
  {
    std::cerr << "icm_param: cannot write '" << summary.string() << "'\n";
    return 1;
  }
  std::error_code ec;
  const fs::path scratch = fs::temp_directory_path(ec) / ("icm_param-batch-" + std::to_string(::getpid()));
  fs::create_directories(scratch, ec);
  if(ec)
  {
    std::cerr << "icm_param: cannot create '" << scratch.string() << "': " << ec.message() << "\n";
    return 1;
  }

  // The children inherit one BLAS thread each, whatever -j: several share the
  // cores, and a supernodal factorization's sums depend on the thread count, so
  // that the outputs of -j 1 and -j 2 are the same bytes (as icm.batch's).
  ::setenv("OPENBLAS_NUM_THREADS", "1", 1);
  ::setenv("OMP_NUM_THREADS", "1", 1);
  const std::size_t failed = Batch_run(options, argc, argv, items, journal, scratch, start).run(to_run);
  journal.close();
  fs::remove_all(scratch, ec);

  std::string error;
  if(!write_summary(summary, items, error))
  {
    std::cerr << "icm_param: " << error << "\n";
    return 1;
  }
  print_totals(options, items.size(), items.size() - to_run.size(), failed, summary, start);
  return failed == 0 ? 0 : 1;
#endif
}

} // namespace icm_param
