// The steady_state step from a case file, end to end (load_case + run_analysis): a cube on rollers
// preloaded 20 % by a frictionless platen (static, long term), then a sweep with the platen shaken.
// Checks: the nominal dynamic modulus of <step>_sweep.csv equals the material's frequency-domain
// modulus E*(w) = S33 + l3^2 C*_c(w) (C* condensed to uniaxial stress, relaxed base) to 1e-6, with
// Rayleigh-beta and structural damping adding i (w beta + s) E(0) exactly; the displacement amplitude
// is a/2 / (2 pi f)^2 for a peak-to-peak acceleration; the .pvd over frequency; bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <complex>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "material/viscoelastic.hpp"
#include "test_run_support.hpp"

namespace cushion::solver::test {
namespace {

using cplx = std::complex<double>;

/// Hyperfoam with nu = 0.1 and the paper's Prony series; density [kg/m^3] (< 0: none given).
std::string material_text(double density) {
  std::string text = foam_json(0.1, true);
  if (density < 0.0) return text.replace(text.find(R"("density_kg_m3": 65, )"), 21, "");
  return text.replace(text.find("65"), 2, io::format_double(density));
}

/// Case: 10 mm cube, 2x2x2 hex8, preload 2 mm (long term), then `sweep` (the steady_state object).
std::string case_text(const std::string& sweep, bool sweep_first = false) {
  const std::string preload = R"({"name": "preload", "type": "static", "long_term": true, "time_period_s": 1,
      "increment": {"initial_s": 0.25},
      "boundary": [{"set": "xmin", "type": "symmetry_x"}, {"set": "ymin", "type": "symmetry_y"},
                   {"set": "bottom", "type": "symmetry_z"}, {"set": "top", "dof": "z", "value_mm": -2}]})";
  const std::string steady = R"({"name": "sweep", "type": "steady_state", "steady_state": )" + sweep + "}";
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [2, 2, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"xmin": "x == 0", "ymin": "y == 0", "bottom": "z == 0", "top": "z == 10"},
    "solver": {"residual_tolerance": 1e-10, "correction_tolerance": 1e-10, "threads": 1},
    "steps": [)" + (sweep_first ? steady + ", " + preload : preload + ", " + steady) + "]}";
}

std::string sweep_text(const std::string& damping = "{}", const std::string& frequencies = "[0.5, 1, 5, 20]",
                       const std::string& excitation_set = "top", const std::string& extra = "") {
  return R"({"frequencies_Hz": )" + frequencies + R"(,
      "excitation": {"set": ")" + excitation_set + R"(", "dof": "z", "acceleration_amplitude_m_s2": 0.25},
      "held": [{"set": "xmin", "dof": "x"}, {"set": "ymin", "dof": "y"}, {"set": "bottom", "dof": "z"}],
      "measure": "top", "damping": )" + damping + R"(, "area_mm2": 100, "thickness_mm": 10)" + extra + "}";
}

fs::path write_case(const fs::path& dir, const std::string& sweep, double density = 1e-12, bool sweep_first = false) {
  write_text(dir / "foam.json", material_text(density));
  return write_text(dir / "case.json", case_text(sweep, sweep_first));
}

/// Nominal uniaxial-stress modulus of the material about F = diag(l1, l1, l3): S33 + l3^2 C*_c(w).
cplx material_modulus(const material::Material& mat, const Mat3& F, double S33, double omega) {
  const Mat6c C = mat.complex_tangent(F, omega);
  const Eigen::Matrix2cd Caa = C.block<2, 2>(0, 0);
  const Eigen::Vector2cd Ca3 = C.block<2, 1>(0, 2), C3a = C.block<1, 2>(2, 0).transpose();
  return S33 + F(2, 2) * F(2, 2) * (C(2, 2) - (C3a.transpose() * (Caa.inverse() * Ca3))(0));
}

/// Long-term uniaxial-stress state at l3 (lateral stretch by bisection on S11 = 0): F and S33 [MPa].
std::pair<Mat3, double> uniaxial_long_term(const material::Viscoelastic& mat, double l3) {
  std::vector<double> scratch;
  auto S = [&](double l1) {
    const Mat3 F = Vec3(l1, l1, l3).asDiagonal();
    return mat.long_term_base().integrate(F, F, 0.0, {}, scratch).S;
  };
  double lo = 0.9, hi = 1.2;  // S11 < 0 at lo, > 0 at hi
  for (int i = 0; i < 100; ++i) (S(0.5 * (lo + hi))(0) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double l1 = 0.5 * (lo + hi);
  return {Mat3(Vec3(l1, l1, l3).asDiagonal()), S(l1)(2)};
}

struct SweepRun {
  CsvTable table;
  std::shared_ptr<const material::Viscoelastic> mat;
};

SweepRun run_sweep(const fs::path& dir, const std::string& sweep) {
  const fs::path file = write_case(dir, sweep);
  run_case(file, dir / "out");
  SweepRun r{read_csv(dir / "out" / "sweep_sweep.csv"), nullptr};
  r.mat = std::dynamic_pointer_cast<const material::Viscoelastic>(load_case(file).material.model);
  return r;
}

double column(const CsvTable& t, const std::string& name, std::size_t row) { return t.col(name).at(row); }

TEST(DynamicsCase, CubeSweepModulusEqualsMaterialModulus) {
  const fs::path dir = scratch_dir();
  const SweepRun run = run_sweep(dir, sweep_text());
  ASSERT_TRUE(run.mat);
  const auto [F, S33] = uniaxial_long_term(*run.mat, 0.8);
  ASSERT_LT(S33, -1e-3);
  const double freq[] = {0.5, 1, 5, 20};
  ASSERT_EQ(run.table.rows(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const double f = freq[k], w = 2 * M_PI * f;
    EXPECT_DOUBLE_EQ(column(run.table, "frequency_Hz", k), f);
    // 0.25 m/s^2 peak-to-peak = 125 mm/s^2 peak: U = 125 / w^2 [mm].
    EXPECT_NEAR(column(run.table, "U_real_mm", k) / (125.0 / (w * w)), 1.0, 1e-9);
    const cplx E(column(run.table, "storage_modulus_kPa", k), column(run.table, "loss_modulus_kPa", k));
    const cplx E_mat = 1e3 * material_modulus(*run.mat, F, S33, w);
    EXPECT_LT(std::abs(E / E_mat - 1.0), 1e-6) << f << " Hz: " << E << " vs " << E_mat;
    std::printf("  %5.2f Hz: |E*| = %.6g kPa, phase %.4f deg, relative error %.2e\n", f, std::abs(E),
                std::arg(E) * 180 / M_PI, std::abs(E / E_mat - 1.0));
    EXPECT_NEAR(column(run.table, "phase_deg", k), std::arg(E_mat) * 180 / M_PI, 1e-4);
  }
  // One frame per frequency in their own series; the quasi-static series is untouched.
  EXPECT_TRUE(fs::exists(dir / "out" / "sweep_sweep.pvd"));
  EXPECT_TRUE(fs::exists(dir / "out" / "sweep_sweep_0003.vtu") || fs::exists(dir / "out" / "sweep_sweep_0004.vtu"));
  EXPECT_TRUE(fs::exists(dir / "out" / "results.pvd"));
  EXPECT_FALSE(fs::exists(dir / "out" / "sweep_sweep.csv.tmp"));
}

TEST(DynamicsCase, RayleighBetaAndStructuralDampingAddToTheModulus) {
  const fs::path dir = scratch_dir();
  const double beta = 1e-3, s = 0.05;
  const SweepRun run = run_sweep(dir, sweep_text(R"({"rayleigh_beta_s": 0.001, "structural": 0.05})", "[1, 20]"));
  const auto [F, S33] = uniaxial_long_term(*run.mat, 0.8);
  const double freq[] = {1, 20};
  for (std::size_t k = 0; k < 2; ++k) {
    const double w = 2 * M_PI * freq[k];
    // D = K*(w) + i (s + w beta) K_R(0): the modulus gains i (s + w beta) E(0), E(0) real (long term).
    const cplx E0 = material_modulus(*run.mat, F, S33, 0.0);
    const cplx expected = 1e3 * (material_modulus(*run.mat, F, S33, w) + cplx(0.0, s + w * beta) * E0.real());
    const cplx E(column(run.table, "storage_modulus_kPa", k), column(run.table, "loss_modulus_kPa", k));
    EXPECT_LT(std::abs(E / expected - 1.0), 1e-6) << freq[k];
    std::printf("  damped %5.2f Hz: relative error %.2e\n", freq[k], std::abs(E / expected - 1.0));
  }
}

/// The InputError message of loading and running `sweep`, "" if none.
std::string error_of(const fs::path& dir, const std::string& sweep, double density = 1e-12, bool first = false) {
  try {
    run_case(write_case(dir, sweep, density, first), dir / "out");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DynamicsCase, BadInputNamesTheKeyAndWritesNoSweep) {
  const fs::path dir = scratch_dir();
  EXPECT_NE(error_of(dir, sweep_text("{}", "[0, 1]")).find("steps[1].steady_state.frequencies_Hz[0]"),
            std::string::npos);
  EXPECT_NE(error_of(dir, sweep_text("{}", "[-2]")).find("> 0 Hz"), std::string::npos);
  const std::string unknown_set = error_of(dir, sweep_text("{}", "[1]", "plate"));
  EXPECT_NE(unknown_set.find("steady_state.excitation.set"), std::string::npos) << unknown_set;
  EXPECT_NE(unknown_set.find("plate"), std::string::npos);
  EXPECT_NE(error_of(dir, sweep_text("{}", "[1]", "top", R"(, "colour": 1)")).find("colour"), std::string::npos);
  EXPECT_NE(error_of(dir, sweep_text(R"({"rayleigh_alpha_1_s": -1})")).find("rayleigh_alpha_1_s"), std::string::npos);
  EXPECT_NE(error_of(dir, sweep_text(), 1e-12, true).find("needs a preceding static or visco step"),
            std::string::npos);
  // Missing density: found by load_case, before the preload runs; nothing is written.
  const std::string density = error_of(dir, sweep_text(), -1.0);
  EXPECT_NE(density.find("steps[1].steady_state"), std::string::npos) << density;
  EXPECT_NE(density.find("density_kg_m3"), std::string::npos) << density;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(DynamicsCase, MeasuredSetMustBeHeldOrExcited) {
  const fs::path dir = scratch_dir();
  const std::string text = R"({"frequencies": {"start_Hz": 1, "end_Hz": 3, "step_Hz": 1},
      "excitation": {"set": "bottom", "dof": "z", "displacement_amplitude_mm": 0.01},
      "held": [{"set": "xmin", "dof": "x"}], "measure": "top", "area_mm2": 100, "thickness_mm": 10})";
  EXPECT_NE(error_of(dir, text).find("steady_state.measure"), std::string::npos);
}

}  // namespace
}  // namespace cushion::solver::test
