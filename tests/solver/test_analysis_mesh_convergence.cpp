// Requirement: on a non-homogeneous problem the platen force shall converge as the mesh is refined,
// and hex8 and tet10 shall agree. Quarter of a 40 x 40 x 20 mm block (symmetry x = 0, y = 0), bottom
// fixed, top BONDED to a rigid platen (u_x = u_y = 0) pushed down 4 mm (20 %), so the sides bulge;
// hyperfoam with nu = 0.2, static step. Checked: successive differences of the reaction decrease
// with an observed order p = log2(d_coarse / d_fine) >= 1 (measured: hex8 1.39, tet10 1.26), and
// the finest hex8 (8^3) and tet10 (4^3 cells x 6) forces agree within 1 % (measured 0.3 %).
#include <cmath>

#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

double platen_force(const std::filesystem::path& dir, const std::string& type, int n) {
  const std::string tag = type + "_" + std::to_string(n);
  const auto case_file = test::write_text(dir / ("case_" + tag + ".json"), R"({
    "mesh": {"generate": {"type": ")" + type + R"(", "box_mm": [0, 20, 0, 20, 0, 20], "elements": [)" +
        std::to_string(n) + "," + std::to_string(n) + "," + std::to_string(n) + R"(]}},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 20"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.5},
      "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                   {"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "xy", "value_mm": 0},
                   {"set": "top", "dof": "z", "value_mm": -4}],
      "output": {"history": [{"set": "top", "quantities": ["RF3"]}]}}],
    "solver": {"residual_tolerance": 1e-7, "correction_tolerance": 1e-7}})");
  test::run_case(case_file, dir / ("out_" + tag));
  const CsvTable h = test::read_history(dir / ("out_" + tag));
  return h.col("top.RF3_N").back();  // [N], quarter model
}

TEST(AnalysisMeshConvergence, BondedPlatenHex8AndTet10) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.2, false));
  const double h2 = platen_force(dir, "hex8", 2), h4 = platen_force(dir, "hex8", 4), h8 = platen_force(dir, "hex8", 8);
  const double t1 = platen_force(dir, "tet10", 1), t2 = platen_force(dir, "tet10", 2),
               t4 = platen_force(dir, "tet10", 4);
  std::cout << "  hex8 2/4/8: " << h2 << " " << h4 << " " << h8 << " N; tet10 1/2/4: " << t1 << " " << t2 << " " << t4
            << " N\n";
  ASSERT_LT(h8, 0.0);  // compression
  const double dh1 = std::abs(h4 - h2), dh2 = std::abs(h8 - h4);
  const double dt1 = std::abs(t2 - t1), dt2 = std::abs(t4 - t2);
  EXPECT_LT(dh2, dh1);
  EXPECT_LT(dt2, dt1);
  const double p_hex = std::log2(dh1 / dh2), p_tet = std::log2(dt1 / dt2);
  std::cout << "  observed order hex8 " << p_hex << ", tet10 " << p_tet << "; hex8 - tet10 "
            << 100 * std::abs(h8 - t4) / std::abs(t4) << " %\n";
  EXPECT_GE(p_hex, 1.0);
  EXPECT_GE(p_tet, 1.0);
  EXPECT_LT(std::abs(h8 - t4), 0.01 * std::abs(t4));
}

}  // namespace
}  // namespace cushion::solver
