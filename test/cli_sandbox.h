// The command-line tool icm_param run as a separate process in a sandbox directory, for the
// tests of test_cli.cpp and test_cli_batch.cpp.

#ifndef ICM_TEST_CLI_SANDBOX_H
#define ICM_TEST_CLI_SANDBOX_H

#include "test_support.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#ifndef _WIN32
#include <sys/wait.h>
#endif

namespace icm_test {

namespace fs = std::filesystem;

inline std::vector<std::string> lines_of(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for(std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

inline std::string quote(const std::string& s)
{
  std::string out = "'";
  for(char c : s)
  {
    if(c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

/// A fresh directory under GoogleTest's temporary directory: `work` for the tool's outputs,
/// and the captured streams beside it, so that `work` holds exactly what the tool wrote.
class Sandbox
{
public:
  Sandbox() : root_("icm_cli") { fs::create_directories(work()); }
  fs::path work() const { return root_.path() / "work"; }
  fs::path file(const std::string& name) const { return work() / name; }

  /// Files in `work`, sorted.
  std::vector<std::string> listing() const
  {
    std::vector<std::string> names;
    for(const auto& entry : fs::directory_iterator(work()))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  struct Result
  {
    int exit_code = -1;
    std::string out, err;
  };

  /// Runs icm_param with `arguments` (already quoted) in `work`, with the environment
  /// variables of `environment` ("NAME=value ...", quoted) added.
  Result run(const std::string& arguments, const std::string& environment = "") const
  {
    const fs::path out = root_.path() / "stdout.txt", err = root_.path() / "stderr.txt";
    const std::string command = "cd " + quote(work().string()) + " && " +
                                (environment.empty() ? "" : "env " + environment + " ") + quote(ICM_PARAM_EXE) + " " +
                                arguments + " >" + quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(command.c_str());
    Result r;
#ifdef _WIN32
    r.exit_code = status;
#else
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
#endif
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
  }

private:
  icm_test::Scratch_directory root_;
};

} // namespace icm_test

#endif // ICM_TEST_CLI_SANDBOX_H
