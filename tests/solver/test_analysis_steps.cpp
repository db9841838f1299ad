// Requirements on the step semantics (analysis.hpp, step.hpp), each against an independent result:
//  - a "static" step gives the instantaneous response of a visco material (dt = 0): nominal stress
//    of a homogeneous uniaxial block = run_point with the base scaled by 1 + sum a_i (1e-9 relative);
//  - "static" with long_term gives the fully relaxed response = run_point with the long-term base;
//  - a DOF released in a later step gets its reaction ramped to zero: the elastic block returns to
//    u = 0 at the end of the release step (1e-8 mm); at half the step its displacement lies between
//    the loading states whose reaction brackets half the released reaction;
//  - increment control hits targets exactly, grows after easy increments, cuts back and gives up;
//  - "newton": "modified" (tangent reuse) reaches the same converged history as full Newton on a
//    non-homogeneous visco problem (bonded platen, bulging sides) to 1e-6 relative, with fewer
//    factorizations and more iterations; "fixed" increments give exactly period / initial_s increments.
#include <cmath>

#include "material/io/material_file.hpp"
#include "material/point_driver.hpp"
#include "solver/analysis/increment_control.hpp"
#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

std::string uniaxial_case(bool long_term, const std::string& second_step = "") {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 1]}},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 10", "side": "x == 10"},
    "steps": [{"name": "press", "type": "static", "long_term": )" + std::string(long_term ? "true" : "false") + R"(,
               "time_period_s": 1, "increment": {"initial_s": 0.25, "max_s": 0.25},
               "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                            {"set": "bottom", "type": "symmetry_z"}, {"set": "top", "dof": "z", "value_mm": -3}],
               "output": {"history": [{"set": "top", "quantities": ["U3", "RF3"]}]}})" + second_step + R"(],
    "solver": {"residual_tolerance": 1e-10, "correction_tolerance": 1e-10}})";
}

/// Nominal stress at 30 % compression from the point driver with an elastic material [MPa].
double point_stress(const material::Material& m) {
  material::History h;
  h.time = {0.0, 1.0};
  h.control = {0.0, -0.3};
  return material::run_point(m, material::LoadMode::uniaxial_free, h).P.back()(0, 0);
}

double fe_stress(bool long_term) {
  const auto dir = test::scratch_dir(long_term ? "_long" : "_inst");
  test::write_text(dir / "foam.json", test::foam_json(0.2, true));
  test::run_case(test::write_text(dir / "case.json", uniaxial_case(long_term)), dir / "out");
  return test::read_history(dir / "out").col("top.RF3_N").back() / 100.0;  // 10 x 10 mm face
}

material::Viscoelastic visco_material() {
  const auto dir = test::scratch_dir("_mat");
  const auto m = material::read_material_file(test::write_text(dir / "foam.json", test::foam_json(0.2, true)));
  return dynamic_cast<const material::Viscoelastic&>(*m.model);
}

TEST(AnalysisSteps, StaticStepIsInstantaneousResponse) {
  const material::Viscoelastic v = visco_material();
  double sum_a = 0.0;
  for (double a : v.relative_to_long_term()) sum_a += a;
  const double expected = point_stress(*v.long_term_base().scaled(1.0 + sum_a));
  EXPECT_NEAR(fe_stress(false), expected, 1e-9 * std::abs(expected));
}

TEST(AnalysisSteps, LongTermStaticStepIsRelaxedResponse) {
  const material::Viscoelastic v = visco_material();
  const double expected = point_stress(v.long_term_base());
  EXPECT_NEAR(fe_stress(true), expected, 1e-9 * std::abs(expected));
}

TEST(AnalysisSteps, ReleasedDofRampsItsReactionToZero) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.2, false));
  const std::string release = R"(,
      {"name": "release", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.25, "max_s": 0.25},
       "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                    {"set": "bottom", "type": "symmetry_z"}]})";
  test::run_case(test::write_text(dir / "case.json", uniaxial_case(false, release)), dir / "out");
  const CsvTable h = test::read_history(dir / "out");
  ASSERT_EQ(h.rows(), 9u);  // t = 0, 4 + 4 increments
  const double rf_end_press = h.col("top.RF3_N")[4];
  EXPECT_LT(rf_end_press, 0.0);
  EXPECT_NEAR(h.col("top.U3_mm")[8], 0.0, 1e-8);  // elastic: back to the reference shape
  EXPECT_EQ(h.col("top.RF3_N")[8], 0.0);          // free DOFs carry no reaction
  // At t = 1.5 s the free top carries half the reaction as a load; the elastic block is then where
  // the press step had a reaction of half that size: between the press rows bracketing R/2.
  const double u_half = h.col("top.U3_mm")[6];
  bool bracketed = false;
  for (std::size_t k = 0; k < 4; ++k) {
    const double rf_a = h.col("top.RF3_N")[k], rf_b = h.col("top.RF3_N")[k + 1];
    if (rf_a >= 0.5 * rf_end_press && 0.5 * rf_end_press >= rf_b) {
      EXPECT_LE(u_half, h.col("top.U3_mm")[k]);
      EXPECT_GE(u_half, h.col("top.U3_mm")[k + 1]);
      bracketed = true;
    }
  }
  EXPECT_TRUE(bracketed);
}

/// A 10 mm cube on 3x3x2 elements pressed 3 mm by a bonded platen over 1 s (visco, Prony): the
/// sides bulge, so the field is not homogeneous and Newton needs several iterations per increment.
std::string bonded_case(const std::string& solver_extra, const std::string& increment) {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [3, 3, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "visco", "time_period_s": 1, "increment": )" + increment + R"(,
               "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                            {"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "xy", "value_mm": 0},
                            {"set": "top", "dof": "z", "value_mm": -3}],
               "output": {"history": [{"set": "top", "quantities": ["U3", "RF3"]}]}}],
    "solver": {"residual_tolerance": 1e-9, "correction_tolerance": 1e-9, "max_iterations": 60)" + solver_extra + "}}";
}

TEST(AnalysisSteps, ModifiedNewtonReachesTheFullNewtonSolutionWithFewerFactorizations) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.2, true));
  const std::string increment = R"({"initial_s": 0.25, "max_s": 0.25})";
  const RunSummary full = test::run_case(test::write_text(dir / "full.json", bonded_case("", increment)), dir / "full");
  const RunSummary modified = test::run_case(
      test::write_text(dir / "modified.json", bonded_case(R"(, "newton": "modified", "max_contraction": 0.5)", increment)),
      dir / "modified");
  const CsvTable a = test::read_history(dir / "full"), b = test::read_history(dir / "modified");
  ASSERT_EQ(a.rows(), 5u);
  ASSERT_EQ(b.rows(), 5u);
  for (std::size_t k = 1; k < 5; ++k) {
    const double rf = a.col("top.RF3_N")[k];
    EXPECT_LT(rf, 0.0);
    EXPECT_NEAR(b.col("top.RF3_N")[k], rf, 1e-6 * std::abs(rf)) << "increment " << k;
  }
  EXPECT_LT(modified.stats.factorizations, full.stats.factorizations);
  EXPECT_GT(modified.stats.iterations, full.stats.iterations);
  EXPECT_EQ(modified.stats.cutbacks, 0);
}

TEST(AnalysisSteps, FixedIncrementsAreNeverGrownOrCut) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.2, true));
  const RunSummary s = test::run_case(
      test::write_text(dir / "case.json", bonded_case("", R"({"initial_s": 0.125, "max_s": 0.5, "fixed": true})")),
      dir / "out");
  EXPECT_EQ(s.stats.increments, 8);  // automatic incrementation would grow 0.125 -> 0.1875 -> ...
  const CsvTable h = test::read_history(dir / "out");
  ASSERT_EQ(h.rows(), 9u);
  for (std::size_t k = 0; k < 9; ++k) EXPECT_NEAR(h.col("time_s")[k], 0.125 * k, 1e-12);
}

TEST(AnalysisIncrementControl, HitsTargetsGrowsAndCutsBack) {
  IncrementLimits l;
  l.period = 10.0;
  l.initial = 1.0;
  l.min = 0.01;
  l.max = 4.0;
  l.max_cutbacks = 2;
  IncrementControl c(l, {2.5, 7.0, -1.0, 12.0});
  EXPECT_EQ(c.next_end(), 1.0);
  EXPECT_TRUE(c.accept(1.0, 3, 1.0));  // easy: grows to 1.5
  EXPECT_EQ(c.next_end(), 2.5);         // exactly the target
  EXPECT_TRUE(c.is_target(2.5));
  EXPECT_TRUE(c.accept(2.5, 8, 1.0));  // hard: stays 1.5
  EXPECT_DOUBLE_EQ(c.increment(), 1.5);
  EXPECT_DOUBLE_EQ(c.next_end(), 4.0);
  EXPECT_TRUE(c.cut_back(1.0));        // 1.5 * 0.25
  EXPECT_DOUBLE_EQ(c.increment(), 0.375);
  EXPECT_TRUE(c.cut_back(0.1));        // the material asks for less than the cut-back factor
  EXPECT_DOUBLE_EQ(c.increment(), 0.0375);
  EXPECT_FALSE(c.cut_back(1.0));       // third in a row > max_cutbacks = 2
  // Period 9 s, increment 4 s (max): 4 s, then 5 s remain < 1.5 x 4 s: two halves of 2.5 s, no sliver.
  l.period = 9.0;
  l.initial = 4.0;
  IncrementControl d(l, {});
  EXPECT_EQ(d.next_end(), 4.0);
  d.accept(4.0, 1, 1.0);
  EXPECT_DOUBLE_EQ(d.next_end(), 6.5);
  d.accept(6.5, 1, 1.0);
  EXPECT_EQ(d.next_end(), 9.0);
  d.accept(9.0, 1, 1.0);
  EXPECT_TRUE(d.finished());
}

}  // namespace
}  // namespace cushion::solver
