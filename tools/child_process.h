// Child processes for the tools that run each piece of work in a process of its own, so that
// one that crashes or hangs fails alone: benchmark/compare (a method run, its results back
// through a pipe, under a time limit) and icm_param's batches (examples/icm_param_batch.cpp:
// this executable again on each mesh, its output in files). POSIX only; on Windows this
// header declares nothing.

#ifndef ICM_TOOLS_CHILD_PROCESS_H
#define ICM_TOOLS_CHILD_PROCESS_H

#ifndef _WIN32

#include <sys/types.h>

#include <functional>
#include <optional>
#include <string>

namespace icm_tools {

/// How a child process ended: killed by a signal, or exited with a code.
struct Child_exit
{
  bool signaled = false;
  int signal = 0; ///< when signaled
  int code = 0;   ///< when not signaled: the exit code
};

/// What the child's standard streams and lifetime become before its work starts.
struct Child_setup
{
  std::string stdout_path;      ///< stdout to this file (created or truncated); empty: inherited
  std::string stderr_path;      ///< the same for stderr
  bool die_with_parent = false; ///< killed (SIGKILL) when the parent dies (Linux)
  bool result_pipe = false;     ///< a pipe from the child to the parent (Child_process::result_fd)
};

/// One child process, forked by start() and reaped by try_wait(), wait() or kill().
class Child_process
{
public:
  /// Flushes this process's output, then forks. The child sets itself up as `setup` says,
  /// runs `work` (given the write end of the result pipe, or -1) and exits with the code it
  /// returns: 127 when its streams cannot be redirected, 3 when its parent is already gone
  /// (with die_with_parent), 4 when `work` throws. False when no child started: `failed_call`
  /// names the call that failed ("pipe" or "fork"), and errno says why.
  bool start(const std::function<int(int result_fd)>& work, const Child_setup& setup, std::string& failed_call);

  pid_t pid() const { return pid_; }
  /// The read end of the result pipe in the parent (-1 without one, or once closed).
  int result_fd() const { return result_fd_; }
  /// Closes the read end of the result pipe.
  void close_result();

  /// The child's exit if it has ended (then reaped), else nothing; does not block.
  std::optional<Child_exit> try_wait();
  /// Waits for the child to end and reaps it.
  Child_exit wait();
  /// Kills the child (SIGKILL) and reaps it.
  Child_exit kill();
  /// The child's peak resident memory so far in MB (its VmHWM), NaN when unknown.
  double peak_rss_mb() const;

private:
  pid_t pid_ = -1;
  int result_fd_ = -1;
};

/// What run_isolated() saw of its child.
struct Isolated_run
{
  enum Kind
  {
    finished,  ///< the child closed its pipe and exited (or was killed by a signal): `exit`
    timed_out, ///< still running at the time limit, or after closing its pipe: killed
    not_started
  } kind = not_started;
  Child_exit exit;
  std::string output;      ///< what the child wrote to its pipe
  double peak_rss_mb = 0;  ///< timed_out: the child's peak memory when it was killed (NaN: unknown)
  std::string failed_call; ///< not_started: "pipe" or "fork" (errno says why)
};

/// Runs `work` in a child process (its stdout to /dev/null, killed if this process dies) and
/// reads what it returns through a pipe, for at most `time_limit` seconds; a child still
/// running then is killed.
Isolated_run run_isolated(const std::function<std::string()>& work, double time_limit);

/// Writes all of `text` to `fd` (retrying after interrupts); false on an error.
bool write_all(int fd, const std::string& text);

/// The peak resident memory of this process in MB: VmHWM, else getrusage's ru_maxrss; NaN
/// when unknown.
double peak_rss_mb();

/// The VmHWM of a /proc/PID/status file in MB, NaN when unknown.
double vm_hwm_mb(const std::string& status_path);

} // namespace icm_tools

#endif // _WIN32

#endif // ICM_TOOLS_CHILD_PROCESS_H
