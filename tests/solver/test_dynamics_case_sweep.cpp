// The steady_state step from a case file, end to end (load_case + run_analysis): a cube on rollers
// preloaded 20 % by a frictionless platen (static, long term), then a sweep with the platen shaken.
// Checks: the nominal dynamic modulus of <step>_sweep.csv equals the material's frequency-domain
// modulus E*(w) = S33 + l3^2 C*_c(w) (C* condensed to uniaxial stress, relaxed base) to 1e-6, with
// Rayleigh-beta and structural damping adding i (w beta + s) E(0) exactly; the displacement amplitude
// is a/2 / (2 pi f)^2 for a peak-to-peak acceleration; the .pvd over frequency (frames on the deformed base
// state, amplitudes and the stress perturbation against the closed form); bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <complex>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "material/viscoelastic.hpp"
#include "solver/output/vtu_reader.hpp"
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

/// Values of array `name` of a frame (point or cell data); fails the test if it is missing or not finite.
const std::vector<double>& values(const VtuContents& v, const std::string& name) {
  const auto p = v.point_data.find(name);
  const std::vector<double>& out = p != v.point_data.end() ? p->second.values : v.cell_data.at(name).values;
  for (double x : out) EXPECT_TRUE(std::isfinite(x)) << name;
  return out;
}

// The frames of the sweep sit on the DEFORMED base state: displacement_mm and the base stress arrays equal the
// preload's last frame (long-term static, so the relaxed base stress is the committed one); the harmonic
// amplitudes equal the closed form of the homogeneous uniaxial perturbation on rollers (lateral faces free):
// u_hat_z = U Z / L, u_hat_x = dl1 X with dl1 from dS11 = dS22 = 0, and the linearised Cauchy stress
// sigma_hat_zz = (dP33 - 2 P33 dl1 / l1) / l1^2, dP33 = (S33 + l3^2 C*_c) U / L; phases in (-180, 180].
TEST(DynamicsCase, SweepFramesCarryTheBaseStateAndTheClosedFormAmplitudes) {
  const fs::path dir = scratch_dir();
  const SweepRun run = run_sweep(dir, sweep_text("{}", "[1, 20]"));
  const fs::path out = dir / "out";
  const auto [F, S33] = uniaxial_long_term(*run.mat, 0.8);
  const double l1 = F(0, 0), l3 = F(2, 2), L = 10.0;
  const VtuContents preload = read_vtu(out / read_pvd(out / "results.pvd").back().file);
  const std::vector<PvdEntry> frames = read_pvd(out / "sweep_sweep.pvd");
  ASSERT_EQ(frames.size(), 2u);
  const double freq[] = {1, 20};
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_DOUBLE_EQ(frames[k].time, freq[k]) << "frame time = frequency [Hz]";
    const VtuContents v = read_vtu(out / frames[k].file);
    for (const char* name : {"displacement_mm", "cauchy_stress_kPa", "von_mises_kPa", "pressure_kPa", "log_strain", "J"}) {
      const std::vector<double>&a = values(v, name), &b = values(preload, name);
      ASSERT_EQ(a.size(), b.size()) << name;
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9 * std::abs(b[i]) + 1e-12) << name;
    }
    const double w = 2 * M_PI * freq[k], U = 125.0 / (w * w);
    const Mat6c C = run.mat->complex_tangent(F, w);
    const Eigen::Vector2cd dE_lateral = -C.block<2, 2>(0, 0).inverse() * C.block<2, 1>(0, 2) * cplx(l3 * U / L);
    const cplx dl1 = dE_lateral(0) / l1;
    const cplx dP33 = material_modulus(*run.mat, F, S33, w) * (U / L);
    const cplx dsigma33 = 1e3 * (dP33 - 2.0 * l3 * S33 * dl1 / l1) / (l1 * l1);  // [kPa]
    const std::vector<double>&amp = values(v, "U_amplitude_mm"), &phase = values(v, "U_phase_deg");
    ASSERT_EQ(phase.size(), v.points.size()) << "U_phase_deg is one scalar per node";
    for (std::size_t a = 0; a < v.points.size(); ++a) {
      EXPECT_NEAR(amp[3 * a + 2], U * v.points[a].z() / L, 1e-7 * U);
      EXPECT_NEAR(amp[3 * a], std::abs(dl1) * v.points[a].x(), 1e-7 * U);
      EXPECT_NEAR(phase[a], 0.0, 1e-6) << "u_hat_z in phase with the drive";
    }
    const std::vector<double>&re = values(v, "sigma_hat_real_kPa"), &im = values(v, "sigma_hat_imag_kPa");
    for (std::size_t e = 0; e < re.size() / 6; ++e) {
      EXPECT_LT(std::abs(cplx(re[6 * e + 2], im[6 * e + 2]) / dsigma33 - 1.0), 1e-6) << "element " << e;
      EXPECT_LT(std::abs(cplx(re[6 * e], im[6 * e])), 1e-6 * std::abs(dsigma33)) << "uniaxial: sigma_hat_xx = 0";
    }
    for (double p : values(v, "sigma_hat_phase_deg")) {
      EXPECT_GT(p, -180.0);
      EXPECT_LE(p, 180.0);
      EXPECT_NEAR(p, std::arg(dsigma33) * 180 / M_PI, 1e-4);
    }
    values(v, "sigma_hat_amplitude_kPa");
    std::printf("  %g Hz: U = %.4e mm, |dl1| = %.4e, sigma_hat_zz = %.6g kPa at %.4f deg\n", freq[k], U,
                std::abs(dl1), std::abs(dsigma33), std::arg(dsigma33) * 180 / M_PI);
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
