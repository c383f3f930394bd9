// Tests of the command-line tool icm_param, run as a separate process: outputs on success,
// one-line diagnostics and no written (or clobbered) file on failure, exit codes.

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#ifndef _WIN32
#  include <sys/wait.h>
#  include <unistd.h>
#endif

namespace {

namespace fs = std::filesystem;

using icm_test::data_path;
using icm_test::read_text;
using icm_test::write_text;

std::vector<std::string> lines_of(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for(std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

std::string quote(const std::string& s)
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

  /// Runs icm_param with `arguments` (already quoted) in `work`.
  Result run(const std::string& arguments) const
  {
    const fs::path out = root_.path() / "stdout.txt", err = root_.path() / "stderr.txt";
    const std::string command = "cd " + quote(work().string()) + " && " + quote(ICM_PARAM_EXE) +
                                " " + arguments + " >" + quote(out.string()) + " 2>" +
                                quote(err.string());
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

/// Checks a failed run: non-zero exit, nothing on stdout, exactly one line on stderr that
/// contains `expected` and names the tool, and no file left in the work directory but
/// `allowed` (temporary files included).
void expect_clean_failure(const Sandbox& box, const Sandbox::Result& r, const std::string& expected,
                          const std::vector<std::string>& allowed = {})
{
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 128 + 6) << "aborted";
  EXPECT_NE(r.exit_code, 128 + 11) << "crashed";
  EXPECT_TRUE(r.out.empty()) << "stdout: " << r.out;
  const std::vector<std::string> lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << r.err;
  EXPECT_NE(lines[0].find(expected), std::string::npos) << "stderr: " << lines[0];
  EXPECT_EQ(lines[0].rfind("icm_param: ", 0), 0u) << "stderr: " << lines[0];
  EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << "the line is not terminated";
  EXPECT_EQ(box.listing(), allowed);
}

/// The value of a numeric JSON key in a flat one-line object, or "" when absent.
std::string json_value(const std::string& json, const std::string& key)
{
  const std::string needle = "\"" + key + "\":";
  const std::size_t at = json.find(needle);
  if(at == std::string::npos)
    return "";
  const std::size_t start = at + needle.size();
  const std::size_t end = json.find_first_of(",}", start);
  return json.substr(start, end - start);
}

TEST(Cli, NefertitiWritesObjSvgAndJson)
{
  Sandbox box;
  const Sandbox::Result r =
    box.run(quote(data_path("nefertiti.off")) + " -o out.obj --svg out.svg --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "stderr: " << r.err;

  const std::vector<std::string> out_lines = lines_of(r.out);
  ASSERT_EQ(out_lines.size(), 1u) << r.out;
  const std::string& json = out_lines[0];
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  EXPECT_EQ(json_value(json, "vertices"), "299");
  EXPECT_EQ(json_value(json, "faces"), "562");
  EXPECT_EQ(json_value(json, "boundary_loops"), "1");
  EXPECT_EQ(json_value(json, "genus"), "0");
  EXPECT_EQ(json_value(json, "flipped_faces"), "0");
  EXPECT_EQ(json_value(json, "layout"), "\"propagation\"");
  const std::string iterations = json_value(json, "newton_iterations");
  ASSERT_FALSE(iterations.empty()) << json;
  EXPECT_GE(std::stoi(iterations), 1);
  EXPECT_LE(std::stoi(iterations), 10);
  const std::string residual = json_value(json, "max_curvature_error");
  ASSERT_FALSE(residual.empty()) << json;
  EXPECT_LT(std::stod(residual), 1e-9);
  for(const char* key : {"seconds_total", "seconds_read", "seconds_cones", "seconds_optimum",
                         "seconds_cut", "seconds_layout", "seconds_parameterize", "seconds_write"})
  {
    const std::string v = json_value(json, key);
    ASSERT_FALSE(v.empty()) << key << " missing in " << json;
    EXPECT_GE(std::stod(v), 0.0) << key;
  }
  EXPECT_GE(std::stod(json_value(json, "seconds_total")),
            std::stod(json_value(json, "seconds_parameterize")));

  EXPECT_EQ(box.listing(), (std::vector<std::string>{"out.obj", "out.svg"}));
  const std::vector<std::string> obj = lines_of(read_text(box.file("out.obj")));
  const std::regex face(R"(f (\d+)/(\d+) (\d+)/(\d+) (\d+)/(\d+))");
  int v = 0, vt = 0, f = 0, bad_faces = 0, out_of_range = 0;
  for(const std::string& line : obj)
  {
    if(line.rfind("v ", 0) == 0)
      ++v;
    else if(line.rfind("vt ", 0) == 0)
      ++vt;
    else if(line.rfind("f ", 0) == 0)
    {
      ++f;
      std::smatch m;
      if(!std::regex_match(line, m, face))
        ++bad_faces;
      else
        for(int i = 1; i <= 6; ++i)
          if(std::stoi(m[i]) < 1 || std::stoi(m[i]) > 299)
            ++out_of_range;
    }
  }
  EXPECT_EQ(v, 299);
  EXPECT_EQ(vt, 299);
  EXPECT_EQ(f, 562);
  EXPECT_EQ(bad_faces, 0);
  EXPECT_EQ(out_of_range, 0);

  const std::string svg = read_text(box.file("out.svg"));
  EXPECT_EQ(svg.rfind("<svg", 0), 0u) << svg.substr(0, 80);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(Cli, WithoutJsonPrintsOneSummaryLineOnStderr)
{
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("nefertiti.off")) + " -o out.obj");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_EQ(box.listing(), (std::vector<std::string>{"out.obj"}));
}

TEST(Cli, ClosedMeshIsCutThroughCones)
{
  // A closed sphere: automatic cones, a seam tree through them, a vt per side of each seam.
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("sphere966.off")) + " -o out.obj --svg out.svg --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string json = lines_of(r.out).at(0);
  EXPECT_EQ(json_value(json, "charts"), "1");
  EXPECT_EQ(json_value(json, "genus"), "0");
  EXPECT_EQ(json_value(json, "boundary_loops"), "0");
  EXPECT_GE(std::stoi(json_value(json, "cones")), 2);
  EXPECT_GT(std::stoi(json_value(json, "seam_edges")), 0);
  EXPECT_EQ(json_value(json, "flipped_faces"), "0");
  EXPECT_EQ(json_value(json, "overlapping_border_edges"), "0");
  EXPECT_LT(std::stod(json_value(json, "seam_length_error")), 1e-9);
  int v = 0, vt = 0;
  for(const std::string& line : lines_of(read_text(box.file("out.obj"))))
  {
    v += line.rfind("v ", 0) == 0;
    vt += line.rfind("vt ", 0) == 0;
  }
  EXPECT_EQ(v, 926);
  // One vt per side of the seams: a vertex of degree d in the seam tree has d copies, and a
  // tree of s edges has s + 1 vertices of total degree 2 s, so s - 1 vt more than vertices.
  EXPECT_EQ(vt, v + std::stoi(json_value(json, "seam_edges")) - 1);
}

TEST(Cli, UserSeamsFromASelectionFile)
{
  // The bundled selection: a star of 44 edges whose 4 ends and centre become the cones.
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("sphere966.off")) + " -o out.obj --json --seams " +
                                    quote(data_path("sphere966.selection.txt")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string json = lines_of(r.out).at(0);
  EXPECT_EQ(json_value(json, "seam_edges"), "44");
  EXPECT_EQ(json_value(json, "cones"), "5");
  EXPECT_EQ(json_value(json, "flipped_faces"), "0");
  EXPECT_LT(std::stod(json_value(json, "seam_length_error")), 1e-9);

  // A seam file that names a pair of vertices without an edge: refused, nothing written.
  Sandbox bad;
  write_text(bad.work() / "bad.selection.txt", "\n\n0 1 0 500\n");
  const Sandbox::Result refused =
    bad.run(quote(data_path("sphere966.off")) + " -o out.obj --seams bad.selection.txt");
  expect_clean_failure(bad, refused, "line 3", {"bad.selection.txt"});
}

TEST(Cli, ClosedSphereWithoutConesIsRefused)
{
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("sphere966.off")) + " -o out.obj --cones 0");
  expect_clean_failure(box, r, "needs at least two cones");
}

TEST(Cli, BadConeArgumentsAreRefused)
{
  Sandbox box;
  for(const char* bad : {"--cone 5", "--cone 5:-90", "--cone x:90", "--cones many"})
  {
    const Sandbox::Result r = box.run(quote(data_path("sphere966.off")) + " -o out.obj " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(bad[6] == 's' ? "--cones takes" : "VERTEX:DEGREES"), std::string::npos) << r.err;
    EXPECT_TRUE(box.listing().empty()) << bad;
  }
  expect_clean_failure(box, box.run(quote(data_path("sphere966.off")) + " -o out.obj --cone 99999:90"), "926 vertices");
  // A border vertex of a disk is singular already.
  expect_clean_failure(box, box.run(quote(data_path("nefertiti.off")) + " -o out.obj --cone 0:90"), "boundary vertex");
  // Every angle prescribed on a closed surface: the curvatures must sum to 4 pi.
  expect_clean_failure(box, box.run(quote(data_path("sphere966.off")) + " -o out.obj --cone 0:90 --cone 500:90"),
                       "Gauss-Bonnet");
}

TEST(Cli, MissingInputFile)
{
  Sandbox box;
  const Sandbox::Result r = box.run(quote(box.file("no_such_mesh.off").string()) + " -o out.obj");
  expect_clean_failure(box, r, "no_such_mesh.off");
}

TEST(Cli, ExistingOutputIsKeptWhenTheRunFails)
{
  Sandbox box;
  const std::string previous = "# the user's precious file\nv 1 2 3\n";
  write_text(box.file("out.obj"), previous);
  write_text(box.file("out.svg"), "<svg/>");
  const Sandbox::Result r = box.run(quote(data_path("sphere966.off")) + " -o out.obj --svg out.svg --cones 0");
  expect_clean_failure(box, r, "needs at least two cones", {"out.obj", "out.svg"});
  EXPECT_EQ(read_text(box.file("out.obj")), previous);
  EXPECT_EQ(read_text(box.file("out.svg")), "<svg/>");
}

TEST(Cli, NanCoordinate)
{
  Sandbox box;
  // A small valid disk (two triangles) with one coordinate NaN.
  write_text(box.file("nan.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const Sandbox::Result r = box.run("nan.off -o out.obj");
  // Either the reader rejects the number or the tool's finiteness check does; both are one
  // line naming the problem file or the coordinate.
  const bool names_file = r.err.find("nan.off") != std::string::npos;
  const bool names_coordinate = r.err.find("non-finite") != std::string::npos;
  EXPECT_TRUE(names_file || names_coordinate) << r.err;
  expect_clean_failure(box, r, "icm_param: ", {"nan.off"});
  RecordProperty("message", r.err);
}

TEST(Cli, QuadFace)
{
  Sandbox box;
  write_text(box.file("quad.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const Sandbox::Result r = box.run("quad.off -o out.obj");
  expect_clean_failure(box, r, "non-triangle", {"quad.off"});
}

TEST(Cli, ZeroAreaFace)
{
  Sandbox box;
  // A valid disk (one border loop, genus 0) whose third face has three collinear corners:
  // it passes the tool's own checks and reaches the parameterizer, which refuses it.
  write_text(box.file("flat.off"),
             "OFF\n4 3 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n3 0 1 3\n3 1 2 3\n3 0 2 1\n");
  const Sandbox::Result r = box.run("flat.off -o out.obj");
  EXPECT_NE(r.exit_code, 128 + 6)
    << "CLI BUG: icm_param aborts (std::logic_error 'basic_string: construction from null') "
       "because CGAL 5.5.1's SMP::get_error_message() has no entry for "
       "ERROR_NO_TOPOLOGICAL_BALL, so get_error_message(ERROR_WRONG_PARAMETER) is a null "
       "pointer, which icm_param passes to std::string. stderr:\n"
    << r.err;
  expect_clean_failure(box, r, "degenerate", {"flat.off"});
}

TEST(Cli, UnknownOption)
{
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("nefertiti.off")) + " -o out.obj --frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown option --frobnicate"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("usage:"), std::string::npos) << r.err;
  EXPECT_TRUE(box.listing().empty());
}

TEST(Cli, MissingOutputOption)
{
  Sandbox box;
  const Sandbox::Result r = box.run(quote(data_path("nefertiti.off")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no output file"), std::string::npos) << r.err;
  EXPECT_TRUE(box.listing().empty());
}

} // namespace
