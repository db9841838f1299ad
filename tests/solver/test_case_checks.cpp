// Input errors that need the built mesh or material are raised by load_case, before the first step
// runs and before any output file is written: a steady-state set missing from an .inp mesh, a
// measured set whose nodes are all driven, a dynamic step without a mass density, a steady-state step on a material
// without a small-amplitude tangent (a power-law air flow).
#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "test_run_support.hpp"

namespace cushion::solver::test {
namespace {

/// One 10 mm hex8 element with node sets BOTTOM (z = 0) and TOP (z = 10).
const char* const kInp = R"(*NODE
1, 0, 0, 0
2, 10, 0, 0
3, 10, 10, 0
4, 0, 10, 0
5, 0, 0, 10
6, 10, 0, 10
7, 10, 10, 10
8, 0, 10, 10
*ELEMENT, TYPE=C3D8, ELSET=FOAM
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=BOTTOM
1, 2, 3, 4
*NSET, NSET=TOP
5, 6, 7, 8
)";

/// A preload (static) then a sweep of `excitation` in z with TOP held and measured, on `mesh`.
std::string sweep_case(const std::string& mesh, const std::string& sets, const std::string& excitation,
                       const std::string& held = "TOP") {
  return R"({"mesh": )" + mesh + R"(, "material": {"file": "foam.json"}, "sets": )" + sets + R"(,
    "steps": [{"name": "preload", "type": "static", "time_period_s": 1,
               "boundary": [{"set": "BOTTOM", "type": "fixed"}, {"set": "TOP", "dof": "z", "value_mm": -1}]},
              {"name": "sweep", "type": "steady_state", "steady_state": {"frequencies_Hz": [1],
               "excitation": {"set": ")" + excitation + R"(", "dof": "z", "displacement_amplitude_mm": 0.01},
               "held": [{"set": ")" + held + R"(", "dof": "z"}], "measure": "TOP", "area_mm2": 100,
               "thickness_mm": 10}}]})";
}

/// The InputError of running `case_text` (with the foam `material`) into dir/out; "" if none.
std::string run_error(const fs::path& dir, const std::string& case_text, const std::string& material) {
  write_text(dir / "foam.json", material);
  write_text(dir / "mesh.inp", kInp);
  try {
    run_case(write_text(dir / "case.json", case_text), dir / "out");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CaseChecks, SteadyStateSetMissingFromTheMeshIsFoundBeforeAnythingIsWritten) {
  const fs::path dir = scratch_dir();
  const std::string m = run_error(dir, sweep_case(R"({"inp": "mesh.inp"})", "{}", "PLATE"), foam_json(0.1, false));
  EXPECT_NE(m.find("case.json: steps[1].steady_state.excitation.set: unknown node set \"PLATE\""), std::string::npos)
      << m;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CaseChecks, MeasuredSetNeitherDrivenNorHeldIsFoundBeforeAnythingIsWritten) {
  // TOP is held in z, but every node of it is driven (ALL is excited): nothing is measured.
  const fs::path dir = scratch_dir();
  const std::string generate = R"({"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 1]}})";
  const std::string sets = R"({"ALL": "all", "BOTTOM": "z == 0", "TOP": "z == 10"})";
  const std::string m = run_error(dir, sweep_case(generate, sets, "ALL"), foam_json(0.1, false));
  EXPECT_NE(m.find("steps[1].steady_state.measure: set \"TOP\" is neither driven nor held"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CaseChecks, MissingDensityIsFoundBeforeAnythingIsWritten) {
  const fs::path dir = scratch_dir();
  std::string no_density = foam_json(0.1, false);
  no_density.replace(no_density.find(R"("density_kg_m3": 65, )"), 21, "");
  const std::string m = run_error(dir, sweep_case(R"({"inp": "mesh.inp"})", "{}", "BOTTOM"), no_density);
  EXPECT_NE(m.find("steps[1].steady_state: a steady_state step needs the mass density of material"), std::string::npos)
      << m;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CaseChecks, SteadyStateOnAPowerLawAirFlowIsFoundBeforeAnythingIsWritten) {
  const fs::path dir = scratch_dir();
  std::string air = foam_json(0.1, false);
  air.insert(air.size() - 1, R"(, "effects": [{"kind": "pneumatic", "rate_exponent": 0.6}])");
  const std::string m = run_error(dir, sweep_case(R"({"inp": "mesh.inp"})", "{}", "BOTTOM"), air);
  EXPECT_NE(m.find("case.json: steps[1].steady_state: the steady_state step cannot linearise material \"foam\""),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("rate exponent != 1"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // The same material with Darcy flow (q = 1) passes the check.
  air.replace(air.find("0.6"), 3, "1.0");
  EXPECT_EQ(run_error(scratch_dir(), sweep_case(R"({"inp": "mesh.inp"})", "{}", "BOTTOM"), air), "");
}

}  // namespace
}  // namespace cushion::solver::test
