// Requirement: contact works inside a "dynamic" step (dynamic_step.hpp: the step's contacts are the
// same contributors as in static/visco steps). Checks, on a quarter block (4x4x3 hex8, visco foam with
// density) pressed 6 mm by a rigid sphere (R = 40 mm, from 0.5 mm above) in 1 s:
//  - a slow dynamic press (inertia forces ~1e-7 of the contact force) gives the contact force of the
//    same press in a visco step at every increment (2e-3 relative to the final force; the two differ
//    only by inertia and by the indenter's contact set evolving with the same increments);
//  - the energy account closes: |balance| <= 2e-3 of the external (contact) work, kinetic energy
//    negligible, and the contact set grows (more active nodes at the end than at the first contact).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

std::string sphere_press_case(const std::string& type, const std::string& extra) {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 40, 0, 40, 0, 30], "elements": [4, 4, 3]}},
    "material": {"file": "foam.json"},
    "sets": {"base": "z == 0", "top": "z == 30", "sym_x": "x == 0", "sym_y": "y == 0"},
    "solver": {"residual_tolerance": 1e-8, "correction_tolerance": 1e-8, "threads": 1},
    "steps": [{"name": "press", "type": ")" + type + R"(", "time_period_s": 1,
      "increment": {"initial_s": 0.05, "max_s": 0.05, "fixed": true, "max_increments": 100},
      "boundary": [{"set": "base", "type": "fixed"}, {"set": "sym_x", "type": "symmetry_x"},
                   {"set": "sym_y", "type": "symmetry_y"}],
      "contact": [{"name": "ball", "set": "top", "force_factor": 4, "tolerance_mm": 0.01,
                   "indenter": {"type": "sphere", "centre_mm": [0, 0, 70.5], "radius_mm": 40},
                   "motion_mm": [0, 0, -6.5]}],
      "output": {"frames_every_s": 1, "history": [{"set": "base", "quantities": ["RF3"]}]})" + extra + R"(}]})";
}

TEST(DynamicStepContact, SlowSpherePressEqualsViscoPressAndBalancesEnergy) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, true));
  test::run_case(test::write_text(dir / "visco.json", sphere_press_case("visco", "")), dir / "visco");
  test::run_case(test::write_text(dir / "dynamic.json", sphere_press_case("dynamic", "")), dir / "dynamic");
  const CsvTable a = read_csv(dir / "visco" / "contact_ball.csv"), b = read_csv(dir / "dynamic" / "contact_ball.csv");
  const auto& Fa = a.col("ball.F3_N");
  const auto& Fb = b.col("ball.F3_N");
  ASSERT_EQ(Fa.size(), 21u);
  ASSERT_EQ(Fb.size(), 21u);
  const double F_end = std::abs(Fa.back());
  EXPECT_GT(F_end, 1.0);  // the press is real
  double worst = 0.0;
  for (std::size_t i = 0; i < Fa.size(); ++i) worst = std::max(worst, std::abs(Fa[i] - Fb[i]));
  std::printf("  final contact force %.4f N (visco) %.4f N (dynamic), largest difference %.3e of the final\n",
              Fa.back(), Fb.back(), worst / F_end);
  EXPECT_LT(worst, 2e-3 * F_end);
  const auto& active = b.col("ball.active_nodes");
  std::size_t first = 0;
  while (first < active.size() && active[first] == 0) ++first;
  ASSERT_LT(first, active.size());
  EXPECT_GT(active.back(), active[first]);

  const CsvTable e = read_csv(dir / "dynamic" / "press_energy.csv");
  const double external = e.col("external_work_mJ").back(), balance = e.col("energy_balance_mJ").back();
  std::printf("  external work %.4e mJ, kinetic %.3e mJ, balance %.3e mJ\n", external,
              e.col("kinetic_energy_mJ").back(), balance);
  EXPECT_GT(external, 0.0);
  EXPECT_LT(std::abs(balance), 2e-3 * external);
  EXPECT_LT(e.col("kinetic_energy_mJ").back(), 1e-6 * external);
}

}  // namespace
}  // namespace cushion::solver
