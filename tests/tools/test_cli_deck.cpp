// Requirement: `cushion run DECK.inp` shall run an ABAQUS/CalculiX deck through the case file's analysis
// (results checked against the closed form of a homogeneous stretch), carry model-data and step boundary
// conditions from step to step as ABAQUS does, convert the deck's unit system named by --units, skip
// output-only keywords with a warning naming file and line, and refuse every other keyword or parameter
// outside the supported subset with one line "FILE:LINE: keyword *X (parameter P of *X) is not supported by
// cushion run", exit 2, writing nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "io/csv.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

/// One C3D8 cube of side `a`, hyperfoam N=1 (nu = 0: no lateral contraction, so the stretch is
/// homogeneous and uniaxial), the top pulled to `u1` in step 1 and back to `u2` in step 2; `extra`
/// is inserted after the first *STEP line.
std::string cube_deck(double a, double mu, double u1, double u2, const std::string& extra = "") {
  auto x = [a](int i) { return std::to_string(i * a); };
  return "*HEADING\ncube\n*NODE, NSET=ALL\n1, 0, 0, 0\n2, " + x(1) + ", 0, 0\n3, " + x(1) + ", " + x(1) +
         ", 0\n4, 0, " + x(1) + ", 0\n5, 0, 0, " + x(1) + "\n6, " + x(1) + ", 0, " + x(1) + "\n7, " + x(1) + ", " +
         x(1) + ", " + x(1) + "\n8, 0, " + x(1) + ", " + x(1) +
         "\n*ELEMENT, TYPE=C3D8, ELSET=FOAM\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
         "*NSET, NSET=BOTTOM\n1, 2, 3, 4\n*NSET, NSET=TOP, GENERATE\n5, 8\n"
         "*MATERIAL, NAME=FOAM\n*HYPERFOAM, N=1\n" + std::to_string(mu) + ", 10, 0\n"
         "*SOLID SECTION, ELSET=FOAM, MATERIAL=FOAM\n"
         "*BOUNDARY\nBOTTOM, 3, 3\n1, 1, 2\n2, 2, 2\n4, 1, 1\n"
         "*STEP, NLGEOM, INC=50\n" + extra + "*STATIC\n0.25, 1.0\n*BOUNDARY\nTOP, 3, 3, " + std::to_string(u1) +
         "\n*NODE PRINT, NSET=TOP\nU, RF\n*END STEP\n"
         "*STEP, NLGEOM\n*STATIC\n0.5, 1.0\n*BOUNDARY\nTOP, 3, 3, " + std::to_string(u2) + "\n*END STEP\n";
}

/// Nominal stress of a hyperfoam term with nu = 0 in uniaxial stretch l: 2 mu/alpha (l^(alpha-1) - 1/l).
double nominal(double mu, double alpha, double l) { return 2.0 * mu / alpha * (std::pow(l, alpha - 1.0) - 1.0 / l); }

/// Sum of RF3 over the rows of the print table at total time t.
double reaction_at(const cushion::CsvTable& t, double time) {
  double sum = 0.0;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (std::abs(t.col("time_s")[r] - time) < 1e-12) sum += t.col("RF3_N")[r];
  return sum;
}

using cli_test::line_of;
using cli_test::write_text;

}  // namespace

TEST(Deck, CubeMatchesClosedFormAndConditionsCarryOverSteps) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_");
  const CommandRun r = run_cushion("run " + quoted(write_text(dir, cube_deck(10.0, 0.01, 2.0, 1.0))) + " -o " +
                                   quoted(dir / "out") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("model.inp:1: keyword *HEADING skipped (output only"), std::string::npos) << r.output;
  const cushion::CsvTable t = cushion::read_csv(dir / "out" / "node_print_TOP.csv");
  // RF3 = P(l) x 100 mm^2 at l = 1.2 (end of step 1, t = 1) and l = 1.1 (end of step 2, t = 2); 1e-8 relative.
  for (const auto& [time, l] : {std::pair{1.0, 1.2}, std::pair{2.0, 1.1}})
    EXPECT_NEAR(reaction_at(t, time), 100.0 * nominal(0.01, 10.0, l), 1e-8 * 100.0 * nominal(0.01, 10.0, l)) << time;
}

TEST(Deck, UnitsConvertTheDeckToMillimetresNewtonsMegapascals) {
  // The same cube in m-N-Pa (side 0.01 m, mu 1e4 Pa, 2 mm = 0.002 m): the same table in mm and N.
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_");
  const CommandRun mm = run_cushion("run " + quoted(write_text(dir, cube_deck(10.0, 0.01, 2.0, 1.0), "mm.inp")) + " -o " +
                                    quoted(dir / "mm") + " --quiet");
  const CommandRun si = run_cushion("run " + quoted(write_text(dir, cube_deck(0.01, 1e4, 0.002, 0.001), "si.inp")) +
                                    " --units m-N-Pa -o " + quoted(dir / "si") + " --quiet");
  ASSERT_EQ(mm.exit_code, 0) << mm.output;
  ASSERT_EQ(si.exit_code, 0) << si.output;
  const cushion::CsvTable a = cushion::read_csv(dir / "mm" / "node_print_TOP.csv");
  const cushion::CsvTable b = cushion::read_csv(dir / "si" / "node_print_TOP.csv");
  ASSERT_EQ(a.rows(), b.rows());
  for (const char* column : {"U3_mm", "RF3_N"})
    for (std::size_t r = 0; r < a.rows(); ++r)
      EXPECT_NEAR(b.col(column)[r], a.col(column)[r], 1e-9 * std::max(1.0, std::abs(a.col(column)[r]))) << column;

  const CommandRun bad = run_cushion("run " + quoted(dir / "mm.inp") + " --units m-mm-furlong -o " + quoted(dir / "x"));
  cli_test::expect_input_error(bad, {"--units: unknown unit system 'm-mm-furlong'", "mm-N-MPa, m-N-Pa"});
  EXPECT_FALSE(fs::exists(dir / "x"));
  const fs::path json = fs::path(CUSHION_SOURCE_DIR) / "cases" / "cube_compression" / "case.json";
  cli_test::expect_input_error(run_cushion("run " + quoted(json) + " --units m-N-Pa -o " + quoted(dir / "x")),
                               {"--units: only for ABAQUS/CalculiX decks (.inp)"});
  EXPECT_FALSE(fs::exists(dir / "x"));
}

TEST(Deck, OutputOnlyKeywordsAreWarnedWithTheirLineAndSkipped) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_");
  const std::string deck = cube_deck(10.0, 0.01, 2.0, 1.0, "*OUTPUT, FIELD\n*ELEMENT OUTPUT\nS, E\n");
  const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string& keyword : {"*OUTPUT", "*ELEMENT OUTPUT"})
    EXPECT_NE(r.output.find("cushion: warning: " + (dir / "model.inp").string() + ":" +
                            std::to_string(line_of(deck, keyword)) + ": keyword " + keyword + " skipped (output only"),
              std::string::npos)
        << keyword << "\n" << r.output;
}

TEST(Deck, UnsupportedKeywordOrParameterIsOneLineWithFileAndLineAndNothingIsWritten) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_");
  const struct {
    std::string extra, line_start, message;
  } cases[] = {
      {"*EQUATION\n2\n5, 3, 1.0, 6, 3, -1.0\n", "*EQUATION", "keyword *EQUATION is not supported by cushion run"},
      {"*PLASTIC\n1.0, 0.0\n", "*PLASTIC", "keyword *PLASTIC is not supported by cushion run"},
      {"*BUCKLE\n5\n", "*BUCKLE", "keyword *BUCKLE is not supported by cushion run"},
  };
  for (const auto& c : cases) {
    const std::string deck = cube_deck(10.0, 0.01, 2.0, 1.0, c.extra);
    const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out"));
    cli_test::expect_input_error(
        r, {(dir / "model.inp").string() + ":" + std::to_string(line_of(deck, c.line_start)) + ": " + c.message});
    EXPECT_FALSE(fs::exists(dir / "out")) << cli_test::listed(dir / "out");
  }
  // Linear perturbation steps appended after the two static steps.
  const struct {
    std::string step, line_start, message;
  } perturbations[] = {
      {"*STEP\n*STEADY STATE DYNAMICS\n100, 200\n*CLOAD\n7, 3, 1\n*END STEP\n", "*STEADY STATE DYNAMICS",
       "a modal steady state needs a preceding *FREQUENCY step (or give DIRECT)"},
      {"*STEP\n*STEADY STATE DYNAMICS, DIRECT\n100, 200\n*END STEP\n", "*END STEP\n*STEP\n*STEADY",
       "the *STEADY STATE DYNAMICS step has no *CLOAD"},
      {"*STEP\n*STEADY STATE DYNAMICS, DIRECT\n100, 200\n*BOUNDARY\nTOP, 3, 3, 0.1\n*CLOAD\n7, 3, 1\n*END STEP\n",
       "TOP, 3, 3, 0.1", "a prescribed motion in a linear perturbation step is not supported"},
      {"*STEP\n*STEADY STATE DYNAMICS, DIRECT\n0, 200\n*CLOAD\n7, 3, 1\n*END STEP\n", "0, 200",
       "need 0 < low <= high [Hz]"},
      {"*STEP\n*FREQUENCY\n0\n*END STEP\n", "0\n*END STEP", "the number of frequencies must be >= 1"},
  };
  for (const auto& c : perturbations) {
    const std::string deck = cube_deck(10.0, 0.01, 2.0, 1.0) + c.step;
    const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out"));
    int line = line_of(deck, c.line_start);
    if (c.line_start.rfind("*END STEP\n", 0) == 0) line = line_of(deck, c.step) + 3;  // the appended step's *END STEP
    cli_test::expect_input_error(r, {(dir / "model.inp").string() + ":" + std::to_string(line) + ": ", c.message});
    EXPECT_FALSE(fs::exists(dir / "out")) << c.message;
  }
  // Parameters: of the step, of a material form, of a boundary condition.
  const std::string base = cube_deck(10.0, 0.01, 2.0, 1.0);
  const struct {
    std::string from, to, message;
  } params[] = {
      {"*STEP, NLGEOM, INC=50", "*STEP, NLGEOM, INC=50, PERTURBATION", "parameter PERTURBATION of *STEP"},
      {"*HYPERFOAM, N=1\n0.010000, 10, 0", "*HYPERELASTIC, MOONEY-RIVLIN\n0.01, 0.0, 0.1",
       "parameter MOONEY-RIVLIN of *HYPERELASTIC"},
      {"*BOUNDARY\nBOTTOM", "*BOUNDARY, TYPE=VELOCITY\nBOTTOM", "parameter TYPE of *BOUNDARY"},
  };
  for (const auto& p : params) {
    std::string deck = base;
    const auto at = deck.find(p.from);
    ASSERT_NE(at, std::string::npos) << p.from;
    deck.replace(at, p.from.size(), p.to);
    const int line = line_of(deck, p.to.substr(0, p.to.find(',')));
    const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out"));
    cli_test::expect_input_error(r, {(dir / "model.inp").string() + ":" + std::to_string(line) + ": " + p.message +
                                     " is not supported by cushion run"});
    EXPECT_FALSE(fs::exists(dir / "out")) << cli_test::listed(dir / "out");
  }
}

TEST(Deck, ViscoDeckEqualsTheCaseFileOfTheSameModel) {
  // One analysis path: a deck with *VISCOELASTIC and two *VISCO steps (pull in 1 s, hold 2 s) and the case
  // file of the same cube, material and increments give the same top reaction at every increment (1e-9 relative).
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_");
  std::string deck = cube_deck(10.0, 0.01, 2.0, 2.0);
  auto replace = [&deck](const std::string& from, const std::string& to) { deck.replace(deck.find(from), from.size(), to); };
  replace("*SOLID SECTION", "*VISCOELASTIC, TIME=PRONY\n0.4, 0.4, 1.0\n*SOLID SECTION");
  replace("*STATIC\n0.25, 1.0", "*VISCO\n0.1, 1.0");
  replace("*STATIC\n0.5, 1.0", "*VISCO\n0.1, 2.0");
  write_text(dir, deck);
  std::ofstream(dir / "foam.json") << R"({"hyperfoam": {"terms": [{"mu_kPa": 10, "alpha": 10, "nu": 0}]},
    "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.4, "tau_s": 1.0}]}})";
  std::ofstream(dir / "case.json") << R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 1]}},
    "material": {"file": "foam.json"},
    "sets": {"bottom": "z == 0", "top": "z == 10", "x0": "x == 0", "y0": "y == 0"},
    "steps": [{"name": "pull", "type": "visco", "time_period_s": 1, "increment": {"initial_s": 0.1, "min_s": 1e-5, "max_s": 1},
               "boundary": [{"set": "bottom", "type": "symmetry_z"}, {"set": "x0", "type": "symmetry_x"},
                            {"set": "y0", "type": "symmetry_y"}, {"set": "top", "dof": "z", "value_mm": 2}],
               "output": {"history": [{"set": "top", "quantities": ["RF3"]}]}},
              {"name": "hold", "type": "visco", "time_period_s": 2, "increment": {"initial_s": 0.1, "min_s": 2e-5, "max_s": 2},
               "boundary": [{"set": "bottom", "type": "symmetry_z"}, {"set": "x0", "type": "symmetry_x"},
                            {"set": "y0", "type": "symmetry_y"}, {"set": "top", "dof": "z", "value_mm": 2}]}]})";
  const CommandRun d = run_cushion("run " + quoted(dir / "model.inp") + " -o " + quoted(dir / "deck") + " --quiet");
  const CommandRun c = run_cushion("run " + quoted(dir / "case.json") + " -o " + quoted(dir / "case") + " --quiet");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const cushion::CsvTable prints = cushion::read_csv(dir / "deck" / "node_print_TOP.csv");
  const cushion::CsvTable history = cushion::read_csv(dir / "case" / "history.csv");
  ASSERT_GT(history.rows(), 10u);
  for (std::size_t r = 0; r < history.rows(); ++r) {
    const double rf = history.col("top.RF3_N")[r];
    EXPECT_NEAR(reaction_at(prints, history.col("time_s")[r]), rf, 1e-9 * std::abs(rf) + 1e-14) << history.col("time_s")[r];
  }
  // The hold relaxes: the reaction at 3 s is below the one at 1 s.
  EXPECT_LT(reaction_at(prints, 3.0), reaction_at(prints, 1.0));
}
