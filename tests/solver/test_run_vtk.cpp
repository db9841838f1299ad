// Requirement: a run's .pvd/.vtu files shall read back with VTK's own readers with the frame times
// the steps asked for and the fields of the solution. A 2 x 2 x 2 hex8 block (bottom fixed, top
// pushed 2 mm down and fixed in x, y) in a 1 s static step with frames every 0.25 s, then a 0.5 s
// visco hold with a frame every increment: times 0, 0.25, 0.5, 0.75, 1, 1.25, 1.5 s (exact); top
// displacement = the prescribed ramp (1e-12 mm); reactions of the last frame sum to the history's
// RF3 (1e-9 relative); stress, J and viscous stress norm present with one value per cell.
#include "solver/output/vtu_reader.hpp"
#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

TEST(RunVtk, FramesReadBackWithTimesAndFields) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, true));
  const std::string bc = R"([{"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "xy", "value_mm": 0},
                             {"set": "top", "dof": "z", "value_mm": -2}])";
  const auto file = test::write_text(dir / "case.json", R"({
    "mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [2, 2, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.1},
               "boundary": )" + bc + R"(, "output": {"frames_every_s": 0.25, "history": [{"set": "top", "quantities": ["RF3"]}]}},
              {"name": "hold", "type": "visco", "time_period_s": 0.5, "increment": {"initial_s": 0.25},
               "boundary": )" + bc + R"(, "output": {"frame_every_increments": 1}}]})");
  const RunSummary summary = test::run_case(file, dir / "out");
  const auto entries = read_pvd(dir / "out" / "results.pvd");
  ASSERT_EQ(entries.size(), 7u);
  EXPECT_EQ(summary.frames, 7u);
  const double times[] = {0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    EXPECT_EQ(entries[i].time, times[i]);
    const VtuContents vtu = read_vtu(dir / "out" / entries[i].file);
    ASSERT_TRUE(vtu.time.has_value());
    EXPECT_EQ(*vtu.time, times[i]);
    ASSERT_EQ(vtu.points.size(), 27u);
    const NamedField& u = vtu.point_data.at("displacement_mm");
    const double expected_top = -2.0 * std::min(times[i], 1.0);
    for (std::size_t a = 0; a < vtu.points.size(); ++a)
      if (vtu.points[a](2) > 10 - 1e-9) EXPECT_NEAR(u.values[3 * a + 2], expected_top, 1e-12);
    for (const char* name : {"cauchy_stress_kPa", "J", "viscous_stress_norm_kPa", "von_mises_kPa"})
      ASSERT_TRUE(vtu.cell_data.count(name)) << name;
    EXPECT_EQ(vtu.cell_data.at("J").values.size(), 8u);
  }
  // Reactions of the last frame of "press" (t = 1) summed over the top = history RF3 at t = 1.
  const VtuContents last = read_vtu(dir / "out" / entries[4].file);
  double rf3 = 0.0;
  for (std::size_t a = 0; a < last.points.size(); ++a)
    if (last.points[a](2) > 10 - 1e-9) rf3 += last.point_data.at("reaction_force_N").values[3 * a + 2];
  const CsvTable h = test::read_history(dir / "out");
  double history_rf3 = NAN;
  for (std::size_t r = 0; r < h.rows(); ++r)
    if (h.col("time_s")[r] == 1.0) history_rf3 = h.col("top.RF3_N")[r];
  ASSERT_LT(history_rf3, 0.0);
  EXPECT_NEAR(rf3, history_rf3, 1e-9 * std::abs(history_rf3));
  // The hold relaxes: the viscous stress of the static step (instantaneous response) decays.
  const VtuContents end = read_vtu(dir / "out" / entries[6].file);
  EXPECT_LT(end.cell_data.at("viscous_stress_norm_kPa").values[0], last.cell_data.at("viscous_stress_norm_kPa").values[0]);
}

}  // namespace
}  // namespace cushion::solver
