// Copyright (c) the ICM authors.
//
// Writing an output file so that it either appears complete or not at all: the content goes to
// a fresh temporary file next to the target, which is renamed over the target only once
// everything was written and flushed without error. A crash, a full disk or a failing writer
// therefore never leaves a truncated file behind, and never destroys the user's previous file.

#ifndef ICM_INTERNAL_ATOMIC_FILE_H
#define ICM_INTERNAL_ATOMIC_FILE_H

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <locale>
#include <ostream>
#include <string>
#include <system_error>

#ifdef _WIN32
#  include <fcntl.h>
#  include <io.h>
#  include <process.h>
#  include <sys/stat.h>
#else
#  include <fcntl.h>
#  include <unistd.h>
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

/// Writes a file atomically.
///
/// `body` writes the whole content into the stream it is given (opened in binary mode, with
/// the classic "C" locale so numbers never get a decimal comma) and returns whether it
/// succeeded. The content goes to a temporary file `path.tmp<pid>.<n>` in the target's
/// directory (same file system, so the final rename is atomic on POSIX), which replaces
/// `path` only when `body` returned true and the stream is still good after close.
///
/// On failure the temporary file is removed, `path` is left as it was (missing, or with its
/// previous content), `error` gets a one-line reason such as
/// "cannot write '/x/y.obj': No such file or directory" and the function returns false.
/// Exceptions thrown by `body` are caught and reported the same way.
///
/// The replaced file gets default permissions, and a symbolic link at `path` is replaced by a
/// regular file rather than followed. Durability across a power loss (fsync) is not attempted.
inline bool write_file_atomically(const std::string& path,
                                  const std::function<bool(std::ostream&)>& body,
                                  std::string& error)
{
  const std::string prefix = "cannot write '" + path + "': ";
  if(path.empty()) {
    error = "cannot write an output file with an empty name";
    return false;
  }

  // A per process counter makes names unique between threads; O_EXCL makes them unique
  // against anything else.
  static std::atomic<unsigned long> counter{0};
  std::string temp;
  bool created = false;
  int err = 0;
  for(int attempt = 0; attempt < 100 && !created; ++attempt) {
    temp = path + ".tmp" + std::to_string(current_process_id()) + "." +
           std::to_string(counter.fetch_add(1));
    errno = 0;
    created = create_new_file(temp);
    err = errno;
    if(!created && err != EEXIST)
      break;
  }
  if(!created) {
    error = prefix + errno_message(err, "cannot create a temporary file");
    return false;
  }

  auto fail = [&](const std::string& reason) {
    std::remove(temp.c_str());
    error = prefix + reason;
    return false;
  };

  bool ok = false;
  {
    std::ofstream out;
    errno = 0;
    out.open(temp, std::ios::out | std::ios::binary | std::ios::trunc);
    if(!out.is_open())
      return fail(errno_message(errno, "cannot open a temporary file"));
    out.imbue(std::locale::classic());
    try {
      ok = body(out);
    } catch(const std::exception& e) {
      return fail(std::string("writer failed: ") + e.what());
    } catch(...) {
      return fail("writer failed with an unknown exception");
    }
    // Keep the reason of a write that already failed inside body; otherwise a full disk
    // usually only shows at flush or close time.
    int write_err = out.fail() ? errno : 0;
    errno = 0;
    out.flush();
    out.close();
    if(write_err == 0)
      write_err = errno;
    if(out.fail())
      return fail(errno_message(write_err, "output error"));
  }
  if(!ok)
    return fail("the writer reported a failure");

  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if(ec)
    return fail(ec.message());
  error.clear();
  return true;
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_ATOMIC_FILE_H
