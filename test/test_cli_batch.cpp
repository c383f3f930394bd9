// Tests of icm_param's batches (-O OUTDIR): every good mesh written as a single run writes
// it, every broken, crashing, slow or greedy one recorded in summary.jsonl with its reason
// while the others go on, --resume, and the command lines refused before any work.

#include <gtest/gtest.h>

#include "cli_sandbox.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using icm_test::data_path;
using icm_test::lines_of;
using icm_test::quote;
using icm_test::read_text;
using icm_test::Sandbox;
using icm_test::write_text;

/// The rows of a summary.jsonl, each line parsed (a line that is not JSON fails the test).
std::vector<Json> summary_rows(const fs::path& path)
{
  std::vector<Json> rows;
  for(const std::string& line : lines_of(read_text(path)))
  {
    rows.push_back(Json::parse(line, nullptr, false));
    EXPECT_TRUE(rows.back().is_object()) << line;
  }
  return rows;
}

/// Broken inputs in the sandbox, by name, with a word of the reason each must be refused for.
std::map<std::string, std::string> write_broken_inputs(const Sandbox& box)
{
  write_text(box.file("truncated.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1");
  write_text(box.file("nonmanifold.off"),
             "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  write_text(box.file("infinite.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n");
  return {{"truncated.off", "truncated"}, {"nonmanifold.off", "non-manifold edge"}, {"infinite.off", "non-finite"}};
}

TEST(CliBatch, WritesEveryGoodMeshAsASingleRunAndRecordsEveryFailure)
{
  Sandbox box;
  const std::map<std::string, std::string> broken = write_broken_inputs(box);
  const std::vector<std::string> good = {data_path("nefertiti.off"), data_path("sphere966.off"),
                                         data_path("mushroom.off")};
  write_text(box.file("list.txt"), "# the bundled meshes\n" + good[1] + "\n\n" + good[2] + "\n");
  // A crash (a child killed by SIGSEGV, as a bug would) must not stop the batch either.
  write_text(box.file("crash.off"), read_text(data_path("nefertiti.off")));
  const Sandbox::Result r = box.run(
    quote(good[0]) + " truncated.off nonmanifold.off infinite.off crash.off --list list.txt -O out -j 2 --cones 4",
    "ICM_PARAM_TEST_CRASH=crash.off");
  EXPECT_EQ(r.exit_code, 1) << r.err; // some failed
  EXPECT_NE(r.err.find("3 of 7 meshes written to out, 4 failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[7/7]"), std::string::npos) << r.err;

  const std::vector<Json> rows = summary_rows(box.file("out/summary.jsonl"));
  ASSERT_EQ(rows.size(), 7u);
  const std::vector<std::string> order = {good[0], "truncated.off", "nonmanifold.off", "infinite.off", "crash.off",
                                          good[1], good[2]};
  for(std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(rows[i]["input"], order[i]) << "rows in input order";
  for(const Json& row : rows)
  {
    const std::string input = row["input"];
    const std::string name = fs::path(input).stem().string();
    EXPECT_EQ(row["output"], "out/" + name + ".obj");
    EXPECT_GE(row["seconds"].get<double>(), 0.0);
    if(input == "crash.off")
    {
      EXPECT_EQ(row["status"], "failed");
      EXPECT_NE(row["error"].get<std::string>().find("crashed: signal 11 (SIGSEGV)"), std::string::npos) << row;
    }
    else if(broken.count(input))
    {
      EXPECT_EQ(row["status"], "failed") << row;
      EXPECT_NE(row["error"].get<std::string>().find(broken.at(input)), std::string::npos) << row;
      EXPECT_FALSE(row.contains("faces")) << "a failed row has no figures";
    }
    else
    {
      ASSERT_EQ(row["status"], "ok") << row;
      EXPECT_EQ(row["error"], "");
      EXPECT_EQ(row["flipped_faces"], 0);
      EXPECT_EQ(row["cones"], 4);
      // The batch runs the single run: the same file, byte for byte, and the same figures.
      Sandbox single;
      const Sandbox::Result one = single.run(quote(input) + " -o one.obj --json --cones 4");
      ASSERT_EQ(one.exit_code, 0) << one.err;
      EXPECT_EQ(read_text(box.file(row["output"])), read_text(single.file("one.obj"))) << input;
      const Json figures = Json::parse(one.out);
      for(const char* key : {"vertices", "faces", "charts", "cones", "seam_edges", "log_area_distortion", "qc_mean"})
        EXPECT_EQ(row[key], figures[key]) << input << " " << key;
    }
  }
  const std::vector<std::string> written = {"mushroom.obj", "nefertiti.obj", "sphere966.obj", "summary.jsonl"};
  std::vector<std::string> listing;
  for(const auto& entry : fs::directory_iterator(box.file("out")))
    listing.push_back(entry.path().filename().string());
  std::sort(listing.begin(), listing.end());
  EXPECT_EQ(listing, written) << "only the good meshes' outputs and the summary";
}

TEST(CliBatch, ResumeRunsOnlyWhatIsNotDone)
{
  Sandbox box;
  write_text(box.file("broken.off"), "OFF\n4 2 0\n0 0 0\n");
  const std::string inputs =
    quote(data_path("nefertiti.off")) + " " + quote(data_path("sphere966.off")) + " broken.off -O out --format ply";
  ASSERT_EQ(box.run(inputs + " --quiet").exit_code, 1);
  const std::vector<Json> before = summary_rows(box.file("out/summary.jsonl"));
  ASSERT_EQ(before.size(), 3u);
  EXPECT_EQ(before[0]["status"], "ok");
  EXPECT_EQ(before[1]["status"], "ok");
  EXPECT_EQ(before[2]["status"], "failed");

  // The broken file repaired and one output lost: these two run again, the third is skipped.
  fs::copy_file(data_path("nefertiti.off"), box.file("broken.off"), fs::copy_options::overwrite_existing);
  fs::remove(box.file("out/sphere966.ply"));
  const Sandbox::Result r = box.run(inputs + " --resume");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("[2/2]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("3 of 3 meshes written to out (1 done before, skipped)"), std::string::npos) << r.err;
  const std::vector<Json> after = summary_rows(box.file("out/summary.jsonl"));
  ASSERT_EQ(after.size(), 3u) << "one row per input, not one per run";
  EXPECT_EQ(after[0], before[0]) << "the skipped mesh keeps its row";
  EXPECT_EQ(after[1]["status"], "ok");
  EXPECT_EQ(after[2]["status"], "ok");
  EXPECT_TRUE(fs::is_regular_file(box.file("out/sphere966.ply")));

  // Without --resume everything runs again and the summary is replaced.
  const Sandbox::Result again = box.run(inputs);
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("[3/3]"), std::string::npos) << again.err;
  EXPECT_EQ(summary_rows(box.file("out/summary.jsonl")).size(), 3u);
}

TEST(CliBatch, TimeoutAndMemoryLimitFailOneMeshAndTheBatchGoesOn)
{
  Sandbox box;
  const Sandbox::Result slow = box.run(quote(data_path("three_peaks.off")) + " -O slow --timeout 0.001 --quiet --json");
  EXPECT_EQ(slow.exit_code, 1);
  const std::vector<Json> slow_rows = summary_rows(box.file("slow/summary.jsonl"));
  ASSERT_EQ(slow_rows.size(), 1u);
  EXPECT_EQ(slow_rows[0]["status"], "failed");
  EXPECT_EQ(slow_rows[0]["error"], "timed out after 0.001 s");
  EXPECT_EQ(Json::parse(slow.out), slow_rows[0]) << "--json prints each row on stdout";
  EXPECT_FALSE(fs::exists(box.file("slow/three_peaks.obj")));

  // Meshes whose run needs more than the heap already holds: with malloc on huge pages
  // (doc/cli.md) nefertiti's fits in the slack of one 2 MB page and needs no more.
  const Sandbox::Result greedy =
    box.run(quote(data_path("three_peaks.off")) + " " + quote(data_path("mushroom.off")) + " -O greedy --max-memory 1");
  EXPECT_EQ(greedy.exit_code, 1);
  const std::vector<Json> rows = summary_rows(box.file("greedy/summary.jsonl"));
  ASSERT_EQ(rows.size(), 2u);
  for(const Json& row : rows)
  {
    EXPECT_EQ(row["status"], "failed");
    EXPECT_NE(row["error"].get<std::string>().find("(--max-memory 1 MB)"), std::string::npos) << row;
  }
  // With room enough the same meshes are written.
  const Sandbox::Result roomy = box.run(quote(data_path("three_peaks.off")) + " " + quote(data_path("nefertiti.off")) +
                                        " -O roomy --max-memory 4000");
  EXPECT_EQ(roomy.exit_code, 0) << roomy.err;
  EXPECT_TRUE(fs::is_regular_file(box.file("roomy/three_peaks.obj")));
}

TEST(CliBatch, CommandLinesRefusedBeforeAnyWork)
{
  Sandbox box;
  write_text(box.file("a.off"), read_text(data_path("nefertiti.off")));
  fs::create_directories(box.file("sub"));
  write_text(box.file("sub/a.off"), read_text(data_path("nefertiti.off")));
  const std::vector<std::pair<std::string, std::string>> refused = {
    {"a.off sub/a.off -O out", "'a.off' and 'sub/a.off' would both be written to 'out/a.obj'"},
    {"a.off -O out -o x.obj", "-o names one file"},
    {"a.off -O out --png x.png", "--png names one file"},
    {"a.off -O out --list missing.txt", "--list: cannot read 'missing.txt'"},
    {"-O out", "no input file"},
    {"a.off -o x.obj -j 2", "-j needs a batch: -O OUTDIR"},
    {"a.off -o x.obj --resume", "--resume needs a batch"},
    {"a.off -o x.obj --format ply", "--format needs a batch"},
    {"a.off sub/a.off -o x.obj", "more than one input file ('sub/a.off')"},
    {"a.off -O out --format off", "--format"},
    {"a.off -O out -j 0", "-j"},
    {"a.off -O out --ply-binary", "--ply-binary needs a .ply output"},
    {"a.off -O a.off", "-O: 'a.off' is not a directory"},
  };
  for(const auto& [arguments, reason] : refused)
  {
    const Sandbox::Result r = box.run(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_EQ(box.listing(), (std::vector<std::string>{"a.off", "sub"})) << arguments << ": nothing written";
  }
}

} // namespace
