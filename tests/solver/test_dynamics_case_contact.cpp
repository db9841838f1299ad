// The steady_state step about a base state WITH CONTACT, end to end from case files: a 10 mm cube on
// rollers pressed 2 mm by a frictionless rigid plane (static, long term), then the base shaken with
// the indenter held. Checks: the nominal modulus equals the prescribed-platen sweep's in series with
// the penalty springs, 1/E_c = 1/E_p + H / (penalty A) (1e-4: the base states differ by the remaining
// penetration <= 1e-4 mm and the foam's inertia); "area_mm2": "contact" is the closed area; GMRES and
// the direct LU agree to 1e-8; a measured indenter without contact and an unknown contact are
// InputErrors naming the key, with no sweep file written.
#include <gtest/gtest.h>

#include <complex>

#include "io/input_error.hpp"
#include "test_run_support.hpp"

namespace cushion::solver::test {
namespace {

using cplx = std::complex<double>;

constexpr const char* supports = R"([{"set": "xmin", "type": "symmetry_x"}, {"set": "ymin", "type": "symmetry_y"},
                   {"set": "bottom", "type": "symmetry_z"})";

/// Sweep object: base shaken in z, rollers held, measuring `measure`.
std::string sweep(const std::string& name, const std::string& measure, const std::string& extra = "") {
  return R"({"name": ")" + name + R"(", "type": "steady_state", "steady_state": {"frequencies_Hz": [1, 20],
      "excitation": {"set": "bottom", "dof": "z", "acceleration_amplitude_m_s2": 0.25},
      "held": [{"set": "xmin", "dof": "x"}, {"set": "ymin", "dof": "y"}, {"set": "top", "dof": "z"}],
      "measure": )" + measure + R"(, "area_mm2": 100, "thickness_mm": 10, "output": {"vtk": false})" + extra + "}}";
}

/// Cube case: a preload step (`preload_extra` = its boundary/contact) and the given sweeps.
fs::path write_case(const fs::path& dir, const std::string& preload_extra, const std::string& sweeps) {
  write_text(dir / "foam.json", foam_json(0.1, true));
  return write_text(dir / "case.json", R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [2, 2, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"xmin": "x == 0", "ymin": "y == 0", "bottom": "z == 0", "top": "z == 10"},
    "solver": {"residual_tolerance": 1e-10, "correction_tolerance": 1e-10, "threads": 1},
    "steps": [{"name": "preload", "type": "static", "long_term": true, "time_period_s": 1,
               "increment": {"initial_s": 0.125}, )" + preload_extra + "}, " + sweeps + "]}");
}

std::string contact_preload(double plane_z) {
  return R"("boundary": )" + std::string(supports) + R"(],
      "contact": [{"name": "plate", "set": "top", "motion_mm": [0, 0, -2], "penalty_MPa_per_mm": 1,
                   "tolerance_mm": 1e-4, "max_augmentations": 40,
                   "indenter": {"type": "plane", "point_mm": [0, 0, )" + std::to_string(plane_z) + R"(], "normal": [0, 0, -1]}}])";
}

/// The held-set sweep rows would include the top z DOFs: drop them from the contact sweep's held list.
std::string without_top(std::string s) {
  const std::string held_top = R"(, {"set": "top", "dof": "z"})";
  return s.replace(s.find(held_top), held_top.size(), "");
}

cplx modulus(const CsvTable& t, std::size_t row) {
  return {t.col("storage_modulus_kPa").at(row), t.col("loss_modulus_kPa").at(row)};
}

TEST(DynamicsCaseContact, HeldIndenterSweepEqualsPrescribedPlatenInSeriesWithPenalty) {
  const fs::path dir = scratch_dir();
  fs::create_directories(dir / "contact");
  fs::create_directories(dir / "platen");
  const std::string contact_sweeps =
      without_top(sweep("gmres", R"({"contact": "plate"})", R"(, "linear_solver": "iterative")")) + ", " +
      without_top(sweep("lu", R"({"contact": "plate"})", R"(, "linear_solver": "direct")"));
  const fs::path with_contact = write_case(dir / "contact", contact_preload(10.0), contact_sweeps);
  run_case(with_contact, dir / "contact" / "out");
  const std::string platen = R"("boundary": )" + std::string(supports) + R"(, {"set": "top", "dof": "z", "value_mm": -2}])";
  run_case(write_case(dir / "platen", platen, sweep("platen", R"("top")")), dir / "platen" / "out");
  const CsvTable gmres = read_csv(dir / "contact" / "out" / "gmres_sweep.csv");
  const CsvTable lu = read_csv(dir / "contact" / "out" / "lu_sweep.csv");
  const CsvTable prescribed = read_csv(dir / "platen" / "out" / "platen_sweep.csv");
  ASSERT_EQ(gmres.rows(), 2u);
  const cplx E_pen = 1e3 * 1.0 * 100.0 * 10.0 / 100.0;  // penalty x area x H / A [kPa]
  for (std::size_t k = 0; k < 2; ++k) {
    const cplx Ep = modulus(prescribed, k), Ec = modulus(gmres, k);
    const cplx expected = 1.0 / (1.0 / Ep + 1.0 / E_pen);
    EXPECT_LT(std::abs(Ec / expected - 1.0), 1e-4) << k << ": " << Ec << " vs " << expected;
    EXPECT_LT(std::abs(Ec / modulus(lu, k) - 1.0), 1e-8) << k;
    std::printf("  row %zu: E_platen = %.6g kPa, E_contact = %.6g kPa (series %.6g), GMRES vs LU %.1e\n", k,
                std::abs(Ep), std::abs(Ec), std::abs(expected), std::abs(Ec / modulus(lu, k) - 1.0));
  }
}

TEST(DynamicsCaseContact, AreaFromContactIsTheClosedArea) {
  const fs::path dir = scratch_dir();
  std::string s = without_top(sweep("area", R"({"contact": "plate"})"));
  s.replace(s.find(R"("area_mm2": 100)"), 15, R"("area_mm2": "contact")");
  const std::string fixed = without_top(sweep("fixed", R"({"contact": "plate"})"));
  run_case(write_case(dir, contact_preload(10.0), s + ", " + fixed), dir / "out");
  const CsvTable a = read_csv(dir / "out" / "area_sweep.csv"), f = read_csv(dir / "out" / "fixed_sweep.csv");
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(modulus(a, k).real() / modulus(f, k).real(), 1.0, 1e-10);
}

std::string error_of(const fs::path& case_file, const fs::path& out) {
  try {
    run_case(case_file, out);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DynamicsCaseContact, IndenterWithoutContactOrUnknownIsAnInputError) {
  const fs::path dir = scratch_dir();
  // The plane starts 10 mm above the block and moves 2 mm: never touches.
  const std::string none =
      error_of(write_case(dir, contact_preload(20.0), without_top(sweep("s", R"({"contact": "plate"})"))), dir / "out");
  EXPECT_NE(none.find("steps[1].steady_state"), std::string::npos) << none;
  EXPECT_NE(none.find("no closed node"), std::string::npos) << none;
  EXPECT_NE(none.find("measure nothing"), std::string::npos) << none;
  EXPECT_FALSE(fs::exists(dir / "out" / "s_sweep.csv"));
  const std::string unknown =
      error_of(write_case(dir, contact_preload(10.0), without_top(sweep("s", R"({"contact": "sitbar"})"))), dir / "out");
  EXPECT_NE(unknown.find("steps[1].steady_state.measure.contact"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("'plate'"), std::string::npos) << unknown;
  EXPECT_FALSE(fs::exists(dir / "out" / "s_sweep.csv"));
}

}  // namespace
}  // namespace cushion::solver::test
