// Requirement: contact is declared in case files and runs in the step driver: the indenter force
// equals the base reaction, the contact history and frame arrays are written, and bad contact
// input is reported clearly with the frames written so far intact.
// Checks: a 2x2x2 block pressed 10 mm by a frictionless flat platen (symmetric model): contact
// F3 = -(base RF3) to 1e-6 relative, penetration within tolerance_mm, contact_<name>.csv rows at
// every increment, the "<name>_pressure_kPa" array in the frames; unknown keys/sets rejected with
// the key path; indenter starting inside -> InputError naming the node; penalty too low ->
// AnalysisError naming the penalty, frames so far readable; the SIT-BAR quarter model (symmetry
// planes, force_factor 4) and the full model on the mirrored mesh give the same force (1e-6 relative; measured 1e-13).
#include <gtest/gtest.h>

#include <cstdio>

#include "io/input_error.hpp"
#include "solver/case/case_file.hpp"
#include "solver/output/vtu_reader.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

std::string platen_case(const std::string& contact_extra, double start_z = 20.0) {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 20, 0, 20, 0, 20], "elements": [2, 2, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"base": "z == 0", "top": "z == 20", "sym_x": "x == 0", "sym_y": "y == 0"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1,
      "increment": {"initial_s": 0.25, "max_s": 0.25},
      "boundary": [{"set": "base", "type": "symmetry_z"}, {"set": "sym_x", "type": "symmetry_x"},
                   {"set": "sym_y", "type": "symmetry_y"}],
      "contact": [{"name": "platen", "set": "top",
                   "indenter": {"type": "plane", "point_mm": [0, 0, )" +
         std::to_string(start_z) + R"(], "normal": [0, 0, -1]},
                   "motion_mm": [0, 0, -10])" + contact_extra + R"(}],
      "output": {"history": [{"set": "base", "quantities": ["RF3"]}]}}]})";
}

TEST(ContactCase, PlatenForceEqualsBaseReaction) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  const auto file = test::write_text(dir / "case.json", platen_case(R"(, "tolerance_mm": 0.001)"));
  const RunSummary s = test::run_case(file, dir / "out");
  EXPECT_EQ(s.stats.increments, 4);
  const CsvTable contact = read_csv(dir / "out" / "contact_platen.csv");
  const CsvTable history = test::read_history(dir / "out");
  const auto& F3 = contact.col("platen.F3_N");
  const auto& RF3 = history.col("base.RF3_N");
  ASSERT_EQ(F3.size(), 5u);
  ASSERT_EQ(RF3.size(), 5u);
  EXPECT_LT(F3.back(), 0.0);
  for (std::size_t i = 1; i < F3.size(); ++i) EXPECT_NEAR(F3[i], -RF3[i], 1e-6 * std::abs(RF3.back()));
  for (double pen : contact.col("platen.max_penetration_mm")) EXPECT_LE(pen, 0.001);
  EXPECT_NEAR(contact.col("platen.U3_mm").back(), -10.0, 1e-12);
  EXPECT_NEAR(contact.col("platen.area_mm2").back(), 400.0, 1e-9);
  const VtuContents last = read_vtu(dir / "out" / "results_0004.vtu");
  ASSERT_TRUE(last.point_data.count("platen_pressure_kPa"));
}

TEST(ContactCase, BadInputIsReported) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  auto message_of = [&](const std::string& text) {
    const auto file = test::write_text(dir / "case.json", text);
    try {
      test::run_case(file, dir / "out");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string m = message_of(platen_case(R"(, "penalty_MPa": 1)"));
  EXPECT_NE(m.find("steps[0].contact[0].penalty_MPa"), std::string::npos) << m;
  m = message_of(platen_case("", 19.0));  // platen 1 mm inside the block at t = 0
  EXPECT_NE(m.find("starts inside"), std::string::npos) << m;
  EXPECT_NE(m.find("steps[0].contact[0]"), std::string::npos) << m;
  m = message_of(platen_case(R"(, "penalty_MPa_per_mm": 1e-6, "tolerance_mm": 1e-4, "max_augmentations": 2)"));
  EXPECT_NE(m.find("penalty"), std::string::npos) << m;
  EXPECT_NE(m.find("too low"), std::string::npos) << m;
  EXPECT_NE(m.find("frames written so far are complete"), std::string::npos) << m;
  EXPECT_NO_THROW(read_vtu(dir / "out" / "results_0000.vtu"));
  std::string text = platen_case("");
  text.replace(text.find("\"set\": \"top\""), 12, "\"set\": \"lid\"");
  m = message_of(text);
  EXPECT_NE(m.find("unknown set \"lid\""), std::string::npos) << m;
}


/// The SIT-BAR block pressed 20 mm (static, coarse mesh) as a quarter or a full model.
std::string sitbar_case(bool quarter) {
  const std::string box = quarter ? "[0, 200, 0, 200, 0, 80]" : "[-200, 200, -200, 200, 0, 80]";
  const std::string n = quarter ? "[4, 4, 2]" : "[8, 8, 2]";
  const std::string bc = quarter ? R"({"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"}, )" : "";
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": )" + box + R"(, "elements": )" + n +
         R"(, "grading": {"x": {"ratio": 2, "focus_mm": 0}, "y": {"ratio": 2, "focus_mm": 0}}}},
    "material": {"file": "foam.json"},
    "sets": {"base": "z == 0", "top": "z == 80", "sym_x": "x == 0", "sym_y": "y == 0"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1,
      "increment": {"initial_s": 0.5, "max_s": 0.5},
      "boundary": [)" + bc + R"({"set": "base", "type": "fixed"}],
      "contact": [{"name": "sitbar", "set": "top", "indenter": {"type": "sitbar"},
                   "motion_mm": [0, 0, -20], "force_factor": )" + (quarter ? "4" : "1") + R"(}]}]})";
}

TEST(ContactCase, SitBarQuarterModelGivesTheFullModelForce) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  double F[2];
  for (int quarter = 0; quarter < 2; ++quarter) {
    const auto file = test::write_text(dir / "case.json", sitbar_case(quarter));
    const auto out = dir / (quarter ? "quarter" : "full");
    test::run_case(file, out);
    F[quarter] = read_csv(out / "contact_sitbar.csv").col("sitbar.F3_N").back();
  }
  std::printf("   SIT-BAR 20 mm: full %.4f N, quarter x 4 %.4f N, difference %.2e\n", F[0], F[1], F[1] / F[0] - 1);
  EXPECT_LT(F[0], 0.0);
  EXPECT_NEAR(F[1], F[0], 1e-6 * std::abs(F[0])) << "full " << F[0] << " N, quarter x 4 " << F[1] << " N";
}

}  // namespace
}  // namespace cushion::solver
