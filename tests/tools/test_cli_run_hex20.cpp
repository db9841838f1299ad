// `cushion run` on an ABAQUS deck of 20-node bricks, as a user runs it: one C3D20R element (a 10 mm cube,
// nodes written by hand in ABAQUS order, the element over two lines) on rollers, pressed 2 mm: exit 0, the
// summary, results.pvd and .vtu frames, and a history whose last RF3 is the closed-form hyperfoam force
// (nu = 0: uniaxial strain = uniaxial stress, 1e-6 relative). The same deck with an 8-node C3D20 stops with
// one input-error line, exit code 2 and no output folder.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

// Corners 1-8 (C3D8 order) then mid-edge nodes 9-20 on 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6,
// 3-7, 4-8 of the cube [0,10]^3.
std::string c3d20r_deck(bool complete) {
  const double corner[8][3] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0},
                               {0, 0, 10}, {10, 0, 10}, {10, 10, 10}, {0, 10, 10}};
  const int edge[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::ostringstream deck;
  deck << "*HEADING\none C3D20R, mm\n*NODE\n";
  for (int a = 0; a < 8; ++a) deck << a + 1 << ", " << corner[a][0] << ", " << corner[a][1] << ", " << corner[a][2] << "\n";
  for (int m = 0; m < 12; ++m) {
    deck << 9 + m;
    for (int i = 0; i < 3; ++i) deck << ", " << 0.5 * (corner[edge[m][0]][i] + corner[edge[m][1]][i]);
    deck << "\n";
  }
  if (complete)
    deck << "*ELEMENT, TYPE=C3D20R, ELSET=FOAM\n1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n16, 17, 18, 19, 20\n";
  else
    deck << "*ELEMENT, TYPE=C3D20, ELSET=FOAM\n1, 1, 2, 3, 4, 5, 6, 7, 8\n";
  return deck.str();
}

fs::path write_case(const fs::path& dir, bool complete) {
  std::ofstream(dir / "cube.inp") << c3d20r_deck(complete);
  std::ofstream(dir / "foam.json") << R"({"name": "foam", "density_kg_m3": 65, "hyperfoam": {"terms": [
      {"mu_kPa": 10.0, "alpha": 10.0, "nu": 0}, {"mu_kPa": 0.5, "alpha": 3.0, "nu": 0}]}})";
  std::ofstream(dir / "case.json") << R"({"mesh": {"inp": "cube.inp"}, "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.5},
               "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                            {"set": "bottom", "type": "symmetry_z"}, {"set": "top", "dof": "z", "value_mm": -2}],
               "output": {"history": [{"set": "top", "quantities": ["RF3"]}]}}]})";
  return dir / "case.json";
}

// Last value of column `name` of a CSV file ('#' comment lines first).
double last_value(const fs::path& csv, const std::string& name) {
  std::ifstream in(csv);
  std::string header, line, last;
  while (std::getline(in, header) && header.rfind('#', 0) == 0) {
  }
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::stringstream h(header), v(last);
  for (std::string column, value; std::getline(h, column, ',') && std::getline(v, value, ',');)
    if (column == name) return std::stod(value);
  return NAN;
}

}  // namespace

TEST(CliRunHex20, C3D20RDeckRunsToParaviewFiles) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_cli_run_hex20_");
  const CommandRun run = run_cushion("run " + quoted(write_case(dir, true)) + " -o " + quoted(dir / "out") + " --threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("summary: 1 steps"), std::string::npos) << run.output;
  for (const char* file : {"results.pvd", "results_0001.vtu", "history.csv"}) EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  // P11 = (2 / l) sum mu_i / alpha_i (l^alpha_i - 1) at l = 0.8 [MPa], times the 100 mm^2 top face.
  const double l = 0.8;
  const double P11 = 2.0 / l * (10e-3 / 10.0 * (std::pow(l, 10.0) - 1.0) + 0.5e-3 / 3.0 * (std::pow(l, 3.0) - 1.0));
  const double rf3 = last_value(dir / "out" / "history.csv", "top.RF3_N");
  EXPECT_NEAR(rf3, 100.0 * P11, 1e-6 * std::abs(100.0 * P11));
}

TEST(CliRunHex20, ShortC3D20ElementIsAnInputError) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_cli_run_hex20_");
  const CommandRun run = run_cushion("run " + quoted(write_case(dir, false)) + " -o " + quoted(dir / "out"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("cushion: input error: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("cube.inp:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("C3D20 needs a label and 20 nodes, got 9 fields"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}
