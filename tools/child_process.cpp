// Child processes (child_process.h): fork, the child's streams, a pipe read under a time
// limit, kill and reap, and the peak memory from /proc.

#include "child_process.h"

#ifndef _WIN32

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <thread>

namespace icm_tools {

namespace {

const double NaN = std::numeric_limits<double>::quiet_NaN();

Child_exit decoded(int status)
{
  Child_exit exit;
  if(WIFSIGNALED(status))
  {
    exit.signaled = true;
    exit.signal = WTERMSIG(status);
  }
  else if(WIFEXITED(status))
  {
    exit.code = WEXITSTATUS(status);
  }
  return exit;
}

/// In the child: `path` opened for writing as file descriptor `fd`; false when it cannot be.
/// Only async-signal-safe calls, as between fork and exec.
bool redirect(const std::string& path, int fd)
{
  if(path.empty())
    return true;
  const int file = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if(file < 0 || ::dup2(file, fd) < 0)
    return false;
  ::close(file);
  return true;
}

/// The child's side of start(): never returns.
[[noreturn]] void child_main(const std::function<int(int)>& work, const Child_setup& setup, pid_t parent, int result_fd)
{
  if(setup.die_with_parent)
  {
#ifdef __linux__
    ::prctl(PR_SET_PDEATHSIG, SIGKILL); // never outlive the parent
#endif
    if(::getppid() != parent)
      ::_exit(3);
  }
  if(!redirect(setup.stdout_path, STDOUT_FILENO) || !redirect(setup.stderr_path, STDERR_FILENO))
    ::_exit(127);
  int code = 4;
  try
  {
    code = work(result_fd);
  }
  catch(...)
  {}
  ::_exit(code);
}

using Deadline = std::chrono::time_point<std::chrono::steady_clock, std::chrono::duration<double>>;

/// Reads the child's pipe until it closes or `deadline` passes; false at the deadline.
bool read_until(int fd, Deadline deadline, std::string& data)
{
  char buf[4096];
  for(;;)
  {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if(left <= 0)
      return false;
    pollfd p{fd, POLLIN, 0};
    const int wait_ms = static_cast<int>(std::min(left * 1000.0 + 1.0, 60000.0));
    const int rc = ::poll(&p, 1, wait_ms);
    if(rc < 0 && errno == EINTR)
      continue;
    if(rc < 0)
      return true;
    if(rc == 0)
      continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if(n < 0 && errno == EINTR)
      continue;
    if(n <= 0)
      return true;
    data.append(buf, static_cast<std::size_t>(n));
  }
}

} // namespace

bool Child_process::start(const std::function<int(int)>& work, const Child_setup& setup, std::string& failed_call)
{
  int fds[2] = {-1, -1};
  if(setup.result_pipe && ::pipe(fds) != 0)
  {
    failed_call = "pipe";
    return false;
  }
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if(pid < 0)
  {
    const int fork_errno = errno;
    failed_call = "fork";
    if(setup.result_pipe)
    {
      ::close(fds[0]);
      ::close(fds[1]);
    }
    errno = fork_errno;
    return false;
  }
  if(pid == 0)
  {
    if(setup.result_pipe)
      ::close(fds[0]);
    child_main(work, setup, parent, fds[1]);
  }
  if(setup.result_pipe)
    ::close(fds[1]);
  pid_ = pid;
  result_fd_ = fds[0];
  return true;
}

void Child_process::close_result()
{
  if(result_fd_ >= 0)
    ::close(result_fd_);
  result_fd_ = -1;
}

std::optional<Child_exit> Child_process::try_wait()
{
  int status = 0;
  pid_t w = 0;
  do
    w = ::waitpid(pid_, &status, WNOHANG);
  while(w < 0 && errno == EINTR);
  if(w == 0)
    return std::nullopt;
  pid_ = -1;
  return w > 0 ? decoded(status) : Child_exit(); // an error: as if it had exited with 0
}

Child_exit Child_process::wait()
{
  int status = 0;
  pid_t w = 0;
  do
    w = ::waitpid(pid_, &status, 0);
  while(w < 0 && errno == EINTR);
  pid_ = -1;
  return w > 0 ? decoded(status) : Child_exit();
}

Child_exit Child_process::kill()
{
  ::kill(pid_, SIGKILL);
  return wait();
}

double Child_process::peak_rss_mb() const
{
  return vm_hwm_mb("/proc/" + std::to_string(pid_) + "/status");
}

Isolated_run run_isolated(const std::function<std::string()>& work, double time_limit)
{
  Isolated_run run;
  run.peak_rss_mb = NaN;
  Child_setup setup;
  setup.stdout_path = "/dev/null"; // the results go through the pipe: what the work prints goes nowhere
  setup.die_with_parent = true;
  setup.result_pipe = true;
  Child_process child;
  const auto send = [&work](int fd) {
    write_all(fd, work());
    ::close(fd);
    return 0;
  };
  if(!child.start(send, setup, run.failed_call))
    return run;
  const Deadline deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(time_limit);
  const bool closed = read_until(child.result_fd(), deadline, run.output);
  child.close_result();
  run.kind = Isolated_run::timed_out;
  if(!closed)
  {
    // The peak memory so far, read before the kill: a lower bound of what the work needs.
    run.peak_rss_mb = child.peak_rss_mb();
    child.kill();
    return run;
  }
  // The pipe is closed: the child has written its result or died. Give it a moment to exit.
  for(int i = 0; i < 1000; ++i)
  {
    if(const std::optional<Child_exit> exit = child.try_wait())
    {
      run.kind = Isolated_run::finished;
      run.exit = *exit;
      return run;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  child.kill(); // closed its pipe but still running: as if hung
  return run;
}

bool write_all(int fd, const std::string& text)
{
  const char* p = text.data();
  std::size_t left = text.size();
  while(left > 0)
  {
    const ssize_t n = ::write(fd, p, left);
    if(n < 0 && errno == EINTR)
      continue;
    if(n < 0)
      return false;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

double vm_hwm_mb(const std::string& status_path)
{
  std::ifstream status(status_path);
  std::string line;
  while(std::getline(status, line))
  {
    if(line.rfind("VmHWM:", 0) == 0)
    {
      const double kb = std::strtod(line.c_str() + 6, nullptr);
      if(kb > 0)
        return kb / 1024.0;
    }
  }
  return NaN;
}

double peak_rss_mb()
{
  const double hwm = vm_hwm_mb("/proc/self/status");
  if(std::isfinite(hwm))
    return hwm;
  rusage ru{};
  if(getrusage(RUSAGE_SELF, &ru) == 0)
    return static_cast<double>(ru.ru_maxrss) / 1024.0;
  return NaN;
}

} // namespace icm_tools

#endif // _WIN32
