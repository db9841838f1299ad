// `cushion run` as a user runs it: bad arguments or input end with one line and a non-zero exit (2 for
// bad files), a run
// that cannot converge with exit code 1 and its frames so far on disk, a good run with exit 0, one
// progress line per increment, the summary (the benchmark reads its figures) and the output files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

#include "cli_runner.hpp"

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

fs::path scratch_dir() { return cli_test::scratch_dir("cushion_test_cli_run_"); }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// A 1-element block compressed by `value_mm` of its 10 mm in 4 increments.
fs::path write_case(const fs::path& dir, double value_mm, const std::string& solver = "{}") {
  const std::string material = std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json";
  std::ofstream(dir / "case.json") << R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 1]}},
    "material": {"file": ")" << material << R"("},
    "sets": {"bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "visco", "time_period_s": 1, "increment": {"initial_s": 0.25, "max_s": 0.25},
               "boundary": [{"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "z", "value_mm": )" << value_mm << R"(}],
               "output": {"history": [{"set": "top", "quantities": ["U3", "RF3"]}]}}],
    "solver": )" << solver << "}";
  return dir / "case.json";
}

}  // namespace

TEST(CliRun, GoodRunPrintsProgressSummaryAndWritesFiles) {
  const fs::path dir = scratch_dir();
  const CommandRun run = run_cushion("run \"" + write_case(dir, -3).string() + "\" -o \"" + (dir / "out").string() + "\" --threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(count(run.output, "press      inc"), 4u) << run.output;
  for (const char* line : {"summary: 1 steps, 4 increments", "free dofs", "nonzeros", "us per element", "factorizations",
                           "peak memory", "results.pvd (5 frames)"})
    EXPECT_NE(run.output.find(line), std::string::npos) << line << "\n" << run.output;
  for (const char* file : {"results.pvd", "results_0004.vtu", "history.csv", "solver.log"})
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  const CommandRun quiet = run_cushion("run \"" + (dir / "case.json").string() + "\" -o \"" + (dir / "q").string() + "\" --quiet");
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(count(quiet.output, " inc "), 0u) << quiet.output;
  EXPECT_NE(quiet.output.find("summary:"), std::string::npos);
}

TEST(CliRun, BadInputIsOneLineWithExitCode2) {
  const fs::path dir = scratch_dir();
  // Argument errors and a missing case file: one line, exit code 2.
  for (const std::string& args : {std::string("run"), std::string("run x.json"), std::string("run x.json -o o --threads -1")}) {
    const CommandRun run = run_cushion(args);
    EXPECT_EQ(run.exit_code, 2) << args << "\n" << run.output;
    EXPECT_EQ(count(run.output, "\n"), 1u) << run.output;
  }
  const CommandRun missing = run_cushion(std::string("run \"") + (dir / "missing.json").string() + "\" -o out");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_EQ(count(missing.output, "\n"), 1u) << missing.output;
  std::ofstream(dir / "bad.json") << "{\"mesh\": }";
  const CommandRun run = run_cushion("run \"" + (dir / "bad.json").string() + "\" -o \"" + (dir / "out").string() + "\"");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("bad.json:1"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out"));  // nothing written for bad input
}

TEST(CliRun, NonConvergenceExitsWith1AndKeepsFrames) {
  const fs::path dir = scratch_dir();
  // Pushing the top 11 mm down on a 10 mm block inverts the element before the end of the step.
  const CommandRun run = run_cushion("run \"" + write_case(dir, -11, R"({"max_cutbacks": 2})").string() + "\" -o \"" +
                                     (dir / "out").string() + "\"");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("cushion: error: step 'press' at t = "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("frames written so far are complete"), std::string::npos) << run.output;
  std::ifstream pvd(dir / "out" / "results.pvd");
  const std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  EXPECT_GE(count(text, "<DataSet"), 2u);  // t = 0 and the converged increments
}
