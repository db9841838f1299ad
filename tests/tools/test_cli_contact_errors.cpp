// Requirement: bad contact input given to `cushion run` ends with a clear one-line message that names the
// file and key, exit code 2, no crash and nothing written; a run stopped part-way keeps its frames readable.
// Checks, on a 20 mm cube (2x2x2 hex8) pressed by a rigid plane: indenter starting 1 mm inside the
// block; contact set on interior nodes (z == 10); an STL indenter that is not closed; a penalty too
// low for the penetration tolerance (stops after the first frame: results_0000.vtu and results.pvd
// complete).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() /
                       ("cushion_test_cli_contact_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                        "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The case with `contact` as the one contact entry of the step.
fs::path write_case(const fs::path& dir, const std::string& contact) {
  const std::string material = std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json";
  std::ofstream(dir / "case.json")
      << R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 20, 0, 20, 0, 20], "elements": [2, 2, 2]}},
    "material": {"file": ")"
      << material << R"("},
    "sets": {"base": "z == 0", "top": "z == 20", "middle": "z == 10", "sym_x": "x == 0", "sym_y": "y == 0"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.25, "max_s": 0.25},
      "boundary": [{"set": "base", "type": "symmetry_z"}, {"set": "sym_x", "type": "symmetry_x"},
                   {"set": "sym_y", "type": "symmetry_y"}],
      "contact": [)"
      << contact << R"(]}]})";
  return dir / "case.json";
}

std::string plane_contact(const std::string& set, double start_z, const std::string& extra = "") {
  return R"({"name": "platen", "set": ")" + set + R"(", "indenter": {"type": "plane", "point_mm": [0, 0, )" +
         std::to_string(start_z) + R"(], "normal": [0, 0, -1]}, "motion_mm": [0, 0, -5])" + extra + "}";
}

CommandRun run_case(const fs::path& dir, const fs::path& file) {
  return run_cushion("run " + quoted(file) + " -o " + quoted(dir / "out") + " --threads 1 --quiet");
}

/// Bad contact input: one line naming the case file, the contact's key and the problem, exit code 2, and
/// nothing written (the contacts are checked before the first frame; without --quiet too).
void expect_rejected_before_writing(const fs::path& dir, const fs::path& file, const std::vector<std::string>& fragments) {
  for (const std::string quiet : {" --quiet", ""}) {
    const CommandRun run = run_cushion("run " + quoted(file) + " -o " + quoted(dir / "out") + " --threads 1" + quiet);
    cli_test::expect_input_error(run, fragments);
    EXPECT_FALSE(fs::exists(dir / "out")) << cli_test::listed(dir / "out");
  }
}

TEST(CliContactErrors, IndenterStartingInsideTheBlock) {
  const fs::path dir = scratch_dir();
  expect_rejected_before_writing(dir, write_case(dir, plane_contact("top", 19.0)),
                                 {"case.json: steps[0].contact[0]: ", "starts inside"});
}

TEST(CliContactErrors, ContactSetNotOnTheSurface) {
  const fs::path dir = scratch_dir();
  expect_rejected_before_writing(dir, write_case(dir, plane_contact("middle", 20.0)),
                                 {"case.json: steps[0].contact[0]", "not on the outer surface", "(first: node "});
}

TEST(CliContactErrors, StlIndenterNotClosed) {
  const fs::path dir = scratch_dir();
  // Four faces of a tetrahedron minus one: an open surface.
  std::ofstream(dir / "open.stl") << "solid open\n"
                                     "facet normal 0 0 -1\nouter loop\nvertex 0 0 21\nvertex 0 10 21\nvertex 10 0 21\nendloop\nendfacet\n"
                                     "facet normal 0 -1 0\nouter loop\nvertex 0 0 21\nvertex 10 0 21\nvertex 0 0 31\nendloop\nendfacet\n"
                                     "facet normal -1 0 0\nouter loop\nvertex 0 0 21\nvertex 0 0 31\nvertex 0 10 21\nendloop\nendfacet\n"
                                     "endsolid open\n";
  const std::string contact = R"({"name": "shape", "set": "top", "indenter": {"type": "stl", "file": "open.stl"},
      "motion_mm": [0, 0, -5]})";
  expect_rejected_before_writing(dir, write_case(dir, contact), {"open.stl", "steps[0].contact[0]", "closed"});
}

TEST(CliContactErrors, PenaltyTooLowForTheTolerance) {
  const fs::path dir = scratch_dir();
  const CommandRun run = run_case(
      dir, write_case(dir, plane_contact("top", 20.0,
                                         R"(, "penalty_MPa_per_mm": 1e-6, "tolerance_mm": 1e-4, "max_augmentations": 2)")));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("penalty"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("too low"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("frames written so far are complete"), std::string::npos) << run.output;
  const std::string frame = read_text(dir / "out" / "results_0000.vtu");
  EXPECT_NE(frame.find("</VTKFile>"), std::string::npos);
  const std::string pvd = read_text(dir / "out" / "results.pvd");
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  EXPECT_NE(pvd.find("results_0000.vtu"), std::string::npos);
}

}  // namespace
