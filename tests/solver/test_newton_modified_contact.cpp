// Requirement: modified Newton ("newton": "modified") shall complete a deep indentation wherever full
// Newton does: a correction with a reused factorization that the line search cannot take in full is
// redone with the tangent at the current iterate (logged) instead of being accepted as a short step
// or ending in a cut-back.
// Checks: a coarse quarter block (4 x 4 x 3 hex8, 100 x 100 x 40 mm, graded to the axis) pressed 30 mm
// (75 %) by a rigid sphere R = 50 mm. Without the fallback modified Newton stalled (16 iterations of
// 0.1 line-search steps after a short step with the old tangent) and stopped at 2.3 mm
// (increment below min_s); full Newton needs no cut-back. Now both finish, the forces agree within
// 0.2 % at 10, 20, 30 mm (same convergence tests), and solver.log shows the refreshed tangents.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "io/csv.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

std::string indentation_case(const std::string& newton) {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 100, 0, 100, 0, 40], "elements": [4, 4, 3],
      "grading": {"x": {"ratio": 2.5, "focus_mm": 0}, "y": {"ratio": 2.5, "focus_mm": 0}}}},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "base": "z == 0", "top": "z == 40"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1,
      "increment": {"initial_s": 0.05, "max_s": 0.05, "min_s": 1e-4, "max_increments": 300},
      "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                   {"set": "base", "type": "fixed"}],
      "contact": [{"name": "sphere", "set": "top", "indenter": {"type": "sphere", "centre_mm": [0, 0, 90],
                   "radius_mm": 50}, "motion_mm": [0, 0, -30], "penalty_MPa_per_mm": 0.1, "tolerance_mm": 0.05,
                   "force_factor": 4}]}],
    "solver": {"newton": ")" + newton + R"(", "threads": 1}})";
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(NewtonModifiedContact, DeepIndentationFinishesAsWithFullNewton) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  std::map<std::string, CsvTable> contact;
  std::map<std::string, RunSummary> summary;
  for (const std::string newton : {"full", "modified"}) {
    const auto file = test::write_text(dir / (newton + ".json"), indentation_case(newton));
    ASSERT_NO_THROW(summary[newton] = test::run_case(file, dir / newton)) << newton;
    contact.emplace(newton, read_csv(dir / newton / "contact_sphere.csv"));
  }
  auto force = [&](const std::string& newton, double depth) {
    std::vector<double> d;
    for (double u : contact.at(newton).col("sphere.U3_mm")) d.push_back(-u);
    return test::interpolate(d, contact.at(newton).col("sphere.F3_N"), depth);
  };
  for (double depth : {10.0, 20.0, 30.0})
    EXPECT_NEAR(force("modified", depth), force("full", depth), 2e-3 * std::abs(force("full", depth)))
        << depth << " mm";
  EXPECT_LT(summary["modified"].stats.factorizations, summary["full"].stats.factorizations);
  EXPECT_NE(read_file(dir / "modified" / "solver.log").find("K new (reused K failed the line search)"),
            std::string::npos);
}

}  // namespace
}  // namespace cushion::solver
