// Requirement: the solver shall reproduce the homogeneous cube test (frictionless platens: symmetry
// planes, rollers at the bottom, top driven in z with x/y free) exactly as the material-point
// driver does: nominal stress RF3 / A0 and lateral stretch equal run_point(uniaxial_free) to 1e-6
// of the peak stress (1e-9 mm laterally) at every time of the load (30 s to 75 %), hold (2 s) and
// unload (30 s) history, for hyperfoam + the paper's Prony series. The increments are fixed
// (initial = max) so the time points of both computations coincide. Coarse 2 x 2 x 2 quarter model.
#include <cmath>

#include "material/io/material_file.hpp"
#include "material/point_driver.hpp"
#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

using material::Segment;

std::string cube_case(const std::string& material_file) {
  const std::string bc = R"([{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                             {"set": "bottom", "type": "symmetry_z"}, {"set": "top", "dof": "z", "value_mm": )";
  const std::string out = R"("output": {"frames_every_s": 10, "history": [{"set": "top", "quantities": ["U3", "RF3"]},
                                                                           {"set": "side", "quantities": ["U1"]}]})";
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 40, 0, 40, 0, 80], "elements": [2, 2, 2]}},
    "material": {"file": ")" + material_file + R"("},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 80", "side": "x == 40"},
    "steps": [
      {"name": "load", "type": "visco", "time_period_s": 30, "increment": {"initial_s": 0.5, "max_s": 0.5},
       "boundary": )" + bc + R"(-60}], )" + out + R"(},
      {"name": "hold", "type": "visco", "time_period_s": 2, "increment": {"initial_s": 0.1, "max_s": 0.1},
       "boundary": )" + bc + R"(-60}], )" + out + R"(},
      {"name": "unload", "type": "visco", "time_period_s": 30, "increment": {"initial_s": 0.5, "max_s": 0.5},
       "boundary": )" + bc + R"(0}], )" + out + R"(}],
    "solver": {"residual_tolerance": 1e-10, "correction_tolerance": 1e-10}})";
}

void expect_cube_equals_point(const std::string& material_file, const std::filesystem::path& dir) {
  const auto case_file = test::write_text(dir / "case.json", cube_case(material_file));
  const RunSummary summary = test::run_case(case_file, dir / "out");
  EXPECT_EQ(summary.stats.cutbacks, 0);
  const CsvTable h = test::read_history(dir / "out");

  const material::MaterialDefinition m = material::read_material_file(material_file);
  const material::History history = material::build_history(
      {Segment{Segment::Kind::ramp, -0.75, 30.0, 0, 0, 0, 60}, Segment{Segment::Kind::hold, 0, 2.0, 0, 0, 0, 20},
       Segment{Segment::Kind::ramp, 0.0, 30.0, 0, 0, 0, 60}});
  const material::PointResult point = material::run_point(*m.model, material::LoadMode::uniaxial_free, history);

  ASSERT_EQ(h.rows(), point.time.size());
  double peak = 0.0;
  for (const Mat3& P : point.P) peak = std::max(peak, std::abs(P(0, 0)));
  ASSERT_GT(peak, 1e-3);  // [MPa]: the test is not trivially zero
  double worst_stress = 0.0, worst_lateral = 0.0;
  for (std::size_t i = 0; i < h.rows(); ++i) {
    ASSERT_NEAR(h.col("time_s")[i], point.time[i], 1e-9);
    EXPECT_NEAR(h.col("top.U3_mm")[i], 80.0 * point.control[i], 1e-9);
    const double P_fe = h.col("top.RF3_N")[i] / (40.0 * 40.0);  // quarter of the 80 x 80 mm face [MPa]
    worst_stress = std::max(worst_stress, std::abs(P_fe - point.P[i](0, 0)));
    worst_lateral = std::max(worst_lateral, std::abs(h.col("side.U1_mm")[i] - 40.0 * (point.F[i](1, 1) - 1.0)));
  }
  EXPECT_LE(worst_stress, 1e-6 * peak) << "peak " << peak << " MPa";
  EXPECT_LE(worst_lateral, 1e-9);
  std::cout << "  max |P_FE - P_point| = " << worst_stress << " MPa (peak " << peak << " MPa), lateral "
            << worst_lateral << " mm\n";
}

TEST(AnalysisCubeVsPoint, ShippedMaterialLoadHoldUnload) {
  expect_cube_equals_point(std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json", test::scratch_dir());
}

TEST(AnalysisCubeVsPoint, LateralExpansionWithPoissonRatio) {
  // nu = 0.2: the sides move, so the free lateral DOFs must find the point driver's lateral stretch.
  const auto dir = test::scratch_dir();
  const auto material = test::write_text(dir / "foam.json", test::foam_json(0.2, true));
  expect_cube_equals_point(material.string(), dir);
}

}  // namespace
}  // namespace cushion::solver
