// Requirement: the contact CSV reports full-model values a user can trust and the frames show what the
// contact does (issue 16).
// A quarter block (symmetry planes x = 0 and y = 0 through the contact surface, base on rollers = symmetry_z)
// pressed 3 mm by a frictionless flat punch of radius R = 30 mm (edge radius 1 mm) with force_factor 4:
//  - F1_N = F2_N = 0 in every row (normal to the two mirror planes: they cancel in the full model), F3_N < 0
//    (the rollers' symmetry_z does not cut the contact surface, so it is no mirror plane), and the CSV header
//    says so;
//  - area_mm2 (full model) of the fully pressed punch: at least 0.9 pi R^2 (contact ends where the 1 mm edge
//    rounding starts: (29/30)^2 = 0.93) and at most the footprint plus the tolerance band around its edge,
//    pi R^2 + 2 pi R tolerance (the former sum of the closed nodes' tributary areas gave 1.13 x pi R^2 on
//    this mesh: nodes just outside the edge counted whole);
//  - <name>_status in the last frame: only -1 (not in the set), 0 (open) and 2 (closed: frictionless nodes
//    slide), never 1 (stick), and some nodes closed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "solver/analysis/contact_contributor.hpp"
#include "solver/output/vtu_reader.hpp"
#include "test_run_support.hpp"

namespace cushion::solver::test {
namespace {

constexpr double kR = 30.0;  // punch radius [mm]

fs::path write_punch_case(const fs::path& dir) {
  write_text(dir / "foam.json", foam_json(0.0, false));
  return write_text(dir / "case.json", R"({
    "mesh": {"generate": {"type": "hex8", "box_mm": [0, 60, 0, 60, 0, 20], "elements": [10, 10, 4]}},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "base": "z == 0", "top": "z == 20"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.5},
      "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                   {"set": "base", "type": "symmetry_z"}],
      "contact": [{"name": "punch", "set": "top",
                   "indenter": {"type": "flat_punch", "centre_mm": [0, 0], "bottom_z_mm": 20, "radius_mm": 30,
                                "edge_radius_mm": 1},
                   "motion_mm": [0, 0, -3], "tolerance_mm": 0.01, "force_factor": 4}],
      "output": {"frames_every_s": 1}}]})");
}

TEST(ContactOutput, QuarterPunchFullModelForcesAreaAndStatus) {
  const fs::path dir = scratch_dir();
  run_case(write_punch_case(dir), dir / "out");
  const CsvTable c = read_csv(dir / "out" / "contact_punch.csv");
  for (double F : c.col("punch.F1_N")) EXPECT_EQ(F, 0.0);
  for (double F : c.col("punch.F2_N")) EXPECT_EQ(F, 0.0);
  EXPECT_LT(c.col("punch.F3_N").back(), 0.0);
  const double disc = std::numbers::pi * kR * kR, area = c.col("punch.area_mm2").back();
  std::printf("  punch area %.1f mm^2 = %.4f x pi R^2 (%.1f mm^2)\n", area, area / disc, disc);
  EXPECT_LE(area, disc + 2.0 * std::numbers::pi * kR * 0.01);  // tolerance_mm 0.01
  EXPECT_GE(area, 0.9 * disc);
  std::ifstream in(dir / "out" / "contact_punch.csv");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("F1, F2 = 0"), std::string::npos) << text.substr(0, 600);
  EXPECT_NE(text.find("force_factor 4"), std::string::npos);

  const std::vector<PvdEntry> frames = read_pvd(dir / "out" / "results.pvd");
  const VtuContents last = read_vtu(dir / "out" / frames.back().file);
  const std::vector<double>& status = last.point_data.at("punch_status").values;
  EXPECT_EQ(std::count(status.begin(), status.end(), 1.0), 0) << "frictionless nodes never stick";
  EXPECT_GT(std::count(status.begin(), status.end(), 2.0), 0);
  for (double s : status) EXPECT_TRUE(s == -1.0 || s == 0.0 || s == 2.0) << s;
}

// full_model_factors: mirror planes through the contact surface zero their component; a factor of 1 reports
// the model as it is.
TEST(ContactOutput, FullModelFactorsZeroOnlyMirrorPlanesThroughTheContact) {
  const fs::path dir = scratch_dir();
  const LoadedCase model = load_case(write_punch_case(dir));
  const StepSpec& step = model.spec.steps.at(0);
  const std::vector<int>& top = model.mesh.node_sets.at("top");
  EXPECT_EQ(full_model_factors(4.0, step, model.mesh, top), Vec3(0.0, 0.0, 4.0));
  EXPECT_EQ(full_model_factors(1.0, step, model.mesh, top), Vec3(1.0, 1.0, 1.0));
  EXPECT_EQ(full_model_factors(4.0, step, model.mesh, model.mesh.node_sets.at("base")), Vec3(0.0, 0.0, 0.0));
}

}  // namespace
}  // namespace cushion::solver::test
