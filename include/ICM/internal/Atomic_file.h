// Copyright (c) the ICM authors.
//
// Writing an output file so that it either appears complete or not at all: the content goes to
// a fresh temporary file next to the target, which is renamed over the target only once
// everything was written and flushed without error. A crash, a full disk or a failing writer
// therefore never leaves a truncated file behind, and never destroys the user's previous file.
// An interrupt (SIGINT, SIGTERM) while the files are written leaves no temporary either: the
// live temporaries are registered where a signal handler can remove them.

#ifndef ICM_INTERNAL_ATOMIC_FILE_H
#define ICM_INTERNAL_ATOMIC_FILE_H

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <locale>
#include <mutex>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <process.h>
#include <sys/stat.h>
#else
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>
#endif

namespace ICM {
namespace internal {

/// Creates a new, empty file named `name` and fails if it already exists, so that a temporary
/// name never clobbers someone else's file. Sets errno on failure.
inline bool create_new_file(const std::string& name)
{
#ifdef _WIN32
  const int fd = ::_open(name.c_str(), _O_WRONLY | _O_CREAT | _O_EXCL, _S_IREAD | _S_IWRITE);
  if(fd < 0)
    return false;
  ::_close(fd);
#else
  // 0666 before the umask: the final file gets the same permissions as one made by ofstream.
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if(fd < 0)
    return false;
  ::close(fd);
#endif
  return true;
}

inline long current_process_id()
{
#ifdef _WIN32
  return static_cast<long>(::_getpid());
#else
  return static_cast<long>(::getpid());
#endif
}

/// The reason of the last failed system call, or `fallback` when errno says nothing.
inline std::string errno_message(int err, const char* fallback)
{
  return err != 0 ? std::string(std::strerror(err)) : std::string(fallback);
}

/// Why the file at `path` must not be replaced, or empty: something that is not a regular
/// file (a directory, a device), or a file without write permission. A read-only file is
/// refused even where the rename would be allowed (the directory is writable, or the
/// process runs as root): the user said it must not change.
inline std::string replace_refusal(const std::string& path)
{
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::symlink_status(path, ec);
  if(ec || !std::filesystem::exists(status))
    return {};
  if(std::filesystem::is_symlink(status))
    return {}; // the link itself is replaced, never its target
  if(!std::filesystem::is_regular_file(status))
    return std::filesystem::is_directory(status) ? "it is a directory" : "it is not a regular file";
  using std::filesystem::perms;
  const perms p = status.permissions();
  if((p & (perms::owner_write | perms::group_write | perms::others_write)) == perms::none)
    return "the file is read-only";
#ifndef _WIN32
  if(::access(path.c_str(), W_OK) != 0)
    return "the file is not writable (" + errno_message(errno, "permission denied") + ")";
#endif
  return {};
}

/// Whether two paths name one file: through links when both exist, else once made absolute,
/// resolved as far as they exist and normalised ("a.obj" and "./x/../a.obj" are one file).
inline bool same_file(const std::string& a, const std::string& b)
{
  std::error_code ec;
  if(std::filesystem::equivalent(a, b, ec))
    return true;
  // Absolute first: weakly_canonical leaves a relative path that names nothing yet relative.
  auto resolved = [](const std::string& p) {
    std::error_code e;
    const std::filesystem::path absolute = std::filesystem::absolute(p, e);
    std::filesystem::path r = std::filesystem::weakly_canonical(absolute, e);
    if(e)
      r = absolute;
    return r.lexically_normal();
  };
  return resolved(a) == resolved(b);
}

/// The temporary files that exist now, for a signal handler to remove: fixed slots of path
/// buffers, so that the handler neither allocates nor locks. A slot is filled after its file
/// was created and freed after the file was renamed or removed, so the handler never removes
/// a name that is not (or no longer) one of ours; a temporary that finds no free slot, or a
/// longer path, is written all the same, only without that protection.
struct Temporary_registry
{
  static constexpr std::size_t slots = 16;
  static constexpr std::size_t path_size = 4096;
  enum State : int
  {
    Free,
    Filling,
    Live
  };
  std::atomic<int> state[slots];
  char path[slots][path_size];
};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

/// Zero-initialised before any code runs: every slot is free.
inline Temporary_registry temporary_registry;

/// Removes every live temporary; async-signal-safe.
inline void remove_registered_temporaries()
{
  for(std::size_t i = 0; i < Temporary_registry::slots; ++i)
    if(temporary_registry.state[i].load() == Temporary_registry::Live)
#ifdef _WIN32
      ::_unlink(temporary_registry.path[i]);
#else
      ::unlink(temporary_registry.path[i]);
#endif
}

#ifndef _WIN32
/// What SIGINT and SIGTERM did before the handler below was installed.
inline struct sigaction previous_signal_actions[2];

inline int signal_slot(int sig)
{
  return sig == SIGINT ? 0 : 1;
}

/// Removes the live temporaries, then does what the signal did before: the previous handler,
/// or the default action (the signal is raised again with the default disposition, so the
/// process still dies by it and its parent sees that).
inline void remove_temporaries_on_signal(int sig, siginfo_t* info, void* context)
{
  const int saved_errno = errno;
  remove_registered_temporaries();
  const struct sigaction& previous = previous_signal_actions[signal_slot(sig)];
  if((previous.sa_flags & SA_SIGINFO) != 0 && previous.sa_sigaction != nullptr &&
     previous.sa_sigaction != remove_temporaries_on_signal)
    previous.sa_sigaction(sig, info, context);
  else if((previous.sa_flags & SA_SIGINFO) == 0 && previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN)
    previous.sa_handler(sig);
  else
  {
    struct sigaction default_action;
    std::memset(&default_action, 0, sizeof default_action);
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(sig, &default_action, nullptr);
    ::raise(sig); // delivered when this handler returns
  }
  errno = saved_errno;
}
#endif

/// Installs the handler of SIGINT and SIGTERM when a temporary is made, unless it is the
/// one there: a signal that is ignored stays ignored, and a handler found there (installed
/// before the first temporary, or since) is called after the temporaries are removed.
inline void install_temporary_cleanup()
{
#ifndef _WIN32
  static std::mutex installing;
  const std::lock_guard<std::mutex> lock(installing);
  for(int sig : {SIGINT, SIGTERM})
  {
    struct sigaction current;
    if(::sigaction(sig, nullptr, &current) != 0)
      continue;
    const bool has_info = (current.sa_flags & SA_SIGINFO) != 0;
    if((has_info && current.sa_sigaction == remove_temporaries_on_signal) ||
       (!has_info && current.sa_handler == SIG_IGN))
      continue;
    struct sigaction action;
    std::memset(&action, 0, sizeof action);
    action.sa_sigaction = remove_temporaries_on_signal;
    action.sa_flags = SA_SIGINFO | SA_RESTART;
    sigemptyset(&action.sa_mask);
    ::sigaction(sig, &action, &previous_signal_actions[signal_slot(sig)]);
  }
#endif
}

/// A path in the registry for as long as this lives (or until `release()`).
class Registered_path
{
public:
  Registered_path() = default;
  Registered_path(const Registered_path&) = delete;
  Registered_path& operator=(const Registered_path&) = delete;
  ~Registered_path() { release(); }

  void hold(const std::string& path)
  {
    release();
    install_temporary_cleanup();
    if(path.size() >= Temporary_registry::path_size)
      return;
    for(std::size_t i = 0; i < Temporary_registry::slots; ++i)
    {
      int expected = Temporary_registry::Free;
      if(temporary_registry.state[i].compare_exchange_strong(expected, Temporary_registry::Filling))
      {
        std::memcpy(temporary_registry.path[i], path.c_str(), path.size() + 1);
        temporary_registry.state[i].store(Temporary_registry::Live);
        slot_ = static_cast<int>(i);
        return;
      }
    }
  }
  void release()
  {
    if(slot_ >= 0)
      temporary_registry.state[slot_].store(Temporary_registry::Free);
    slot_ = -1;
  }

private:
  int slot_ = -1;
};

/// One file for `write_files_atomically()`: its path and the function that writes its
/// content into the stream it is given, returning whether it succeeded.
struct Atomic_output
{
  std::string path;
  std::function<bool(std::ostream&)> body;
};

/// A temporary file next to its target, removed on destruction unless it was renamed.
class Temporary_file
{
public:
  Temporary_file() = default;
  Temporary_file(const Temporary_file&) = delete;
  Temporary_file& operator=(const Temporary_file&) = delete;
  ~Temporary_file() { discard(); }

  /// Creates `target.tmp<pid>.<n>` (a per-process counter makes names unique between
  /// threads; O_EXCL against anything else). Returns false with the reason on failure.
  bool create(const std::string& target, std::string& reason)
  {
    static std::atomic<unsigned long> counter{0};
    int err = 0;
    for(int attempt = 0; attempt < 100; ++attempt)
    {
      const std::string name =
        target + ".tmp" + std::to_string(current_process_id()) + "." + std::to_string(counter.fetch_add(1));
      errno = 0;
      if(create_new_file(name))
      {
        name_ = name;
        registered_.hold(name_);
        return true;
      }
      err = errno;
      if(err != EEXIST)
        break;
    }
    reason = errno_message(err, "cannot create a temporary file");
    return false;
  }

  /// Writes the content with `body`; returns false with the reason on failure, keeping the
  /// reason of a write that failed inside `body` (a full disk often shows only at close).
  bool write(const std::function<bool(std::ostream&)>& body, std::string& reason)
  {
    bool ok = false;
    std::ofstream out;
    errno = 0;
    out.open(name_, std::ios::out | std::ios::binary | std::ios::trunc);
    if(!out.is_open())
    {
      reason = errno_message(errno, "cannot open a temporary file");
      return false;
    }
    out.imbue(std::locale::classic());
    try
    {
      ok = body(out);
    }
    catch(const std::exception& e)
    {
      reason = std::string("writer failed: ") + e.what();
      return false;
    }
    catch(...)
    {
      reason = "writer failed with an unknown exception";
      return false;
    }
    int write_err = out.fail() ? errno : 0;
    errno = 0;
    out.flush();
    out.close();
    if(write_err == 0)
      write_err = errno;
    if(out.fail())
    {
      reason = errno_message(write_err, "output error");
      return false;
    }
    if(!ok)
    {
      reason = "the writer reported a failure";
      return false;
    }
    return true;
  }

  /// Renames the temporary over `target`; it is then no longer removed.
  bool rename_to(const std::string& target, std::string& reason)
  {
    std::error_code ec;
    std::filesystem::rename(name_, target, ec);
    if(ec)
    {
      reason = ec.message();
      return false;
    }
    name_.clear();
    registered_.release();
    return true;
  }

  void discard()
  {
    if(!name_.empty())
      std::remove(name_.c_str());
    name_.clear();
    registered_.release();
  }

  const std::string& name() const { return name_; }

private:
  std::string name_;
  Registered_path registered_;
};

/// Writes several files all or nothing.
///
/// Every content goes to a temporary file next to its target (same file system, so each
/// rename is atomic on POSIX); the targets are replaced only once every content was written
/// without error, each target refused beforehand if it is read-only or not a regular file,
/// and the same path named twice is refused. Should a rename still fail, the targets already
/// renamed get their previous content back (kept under a hard link until the end) or are
/// removed if they did not exist. No temporary remains, whatever happens; durability across
/// a power loss (fsync) is not attempted.
///
/// On failure `error` gets a one-line reason such as "cannot write '/x/y.obj': No such file
/// or directory" and the function returns false. Exceptions thrown by a body are caught and
/// reported the same way.
inline bool write_files_atomically(const std::vector<Atomic_output>& outputs, std::string& error)
{
  for(std::size_t i = 0; i < outputs.size(); ++i)
  {
    if(outputs[i].path.empty())
    {
      error = "cannot write an output file with an empty name";
      return false;
    }
    for(std::size_t j = 0; j < i; ++j)
    {
      if(same_file(outputs[i].path, outputs[j].path))
      {
        error = "cannot write '" + outputs[i].path + "' twice (two outputs name the same file)";
        return false;
      }
    }
    const std::string refusal = replace_refusal(outputs[i].path);
    if(!refusal.empty())
    {
      error = "cannot write '" + outputs[i].path + "': " + refusal;
      return false;
    }
  }

  std::vector<Temporary_file> temporaries(outputs.size());
  std::string reason;
  for(std::size_t i = 0; i < outputs.size(); ++i)
    if(!temporaries[i].create(outputs[i].path, reason) || !temporaries[i].write(outputs[i].body, reason))
    {
      error = "cannot write '" + outputs[i].path + "': " + reason;
      return false; // the destructors remove every temporary
    }

  // Previous content of each target, under a hard link, in case a later rename fails.
  struct Previous
  {
    std::string backup;
    bool existed = false;
    Registered_path registered; // the backup, removed by a signal handler too
  };
  std::vector<Previous> previous(outputs.size());
  auto drop_backups = [&]() {
    for(Previous& p : previous)
    {
      if(!p.backup.empty())
        std::remove(p.backup.c_str());
      p.registered.release();
    }
  };
  for(std::size_t i = 0; i < outputs.size() && outputs.size() > 1; ++i)
  {
    std::error_code ec;
    previous[i].existed = std::filesystem::exists(std::filesystem::symlink_status(outputs[i].path, ec));
    if(!previous[i].existed)
      continue;
    Temporary_file name;
    if(!name.create(outputs[i].path, reason))
      continue;
    const std::string backup = name.name();
    name.discard();
    std::filesystem::create_hard_link(outputs[i].path, backup, ec);
    if(!ec)
    {
      previous[i].backup = backup;
      previous[i].registered.hold(backup);
    }
  }
  for(std::size_t i = 0; i < outputs.size(); ++i)
  {
    if(temporaries[i].rename_to(outputs[i].path, reason))
      continue;
    for(std::size_t j = 0; j < i; ++j)
    {
      std::error_code ec;
      if(!previous[j].backup.empty())
      {
        std::filesystem::rename(previous[j].backup, outputs[j].path, ec);
        if(!ec)
        {
          previous[j].backup.clear();
          previous[j].registered.release();
        }
      }
      else if(!previous[j].existed)
        std::filesystem::remove(outputs[j].path, ec);
    }
    drop_backups();
    error = "cannot write '" + outputs[i].path + "': " + reason;
    return false;
  }
  drop_backups();
  error.clear();
  return true;
}

/// Writes one file atomically: `write_files_atomically()` with one output.
///
/// `body` writes the whole content into the stream it is given (opened in binary mode, with
/// the classic "C" locale so numbers never get a decimal comma) and returns whether it
/// succeeded. The content goes to a temporary file `path.tmp<pid>.<n>` in the target's
/// directory, which replaces `path` only when `body` returned true and the stream is still
/// good after close.
///
/// On failure the temporary file is removed, `path` is left as it was (missing, or with its
/// previous content), `error` gets a one-line reason and the function returns false. A
/// read-only `path` is refused, not replaced. The replaced file gets default permissions,
/// and a symbolic link at `path` is replaced by a regular file rather than followed.
inline bool write_file_atomically(const std::string& path, const std::function<bool(std::ostream&)>& body,
                                  std::string& error)
{
  return write_files_atomically({Atomic_output{path, body}}, error);
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_ATOMIC_FILE_H
