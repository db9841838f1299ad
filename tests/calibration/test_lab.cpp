// Virtual lab: measured dynamic modulus against the frequency-domain closed form, the platen that
// only pushes (lift-off), seeded noise, and bad truth files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "calibration/lab.hpp"
#include "material/hyperfoam.hpp"
#include "io/input_error.hpp"
#include "material/viscoelastic.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;

namespace {

std::shared_ptr<const mat::Hyperfoam> foam() {
  // nu = 0: uniaxial compression with free lateral faces keeps the lateral stretch at 1.
  return std::make_shared<mat::Hyperfoam>(std::vector<mat::HyperfoamTerm>{{0.004, 8.0, 0.0}, {0.002, -2.0, 0.0}});
}

}  // namespace

TEST(Lab, DynamicModulusMatchesFrequencyDomainAtRelaxedPreload) {
  // Fast Prony terms only (0.01, 0.1 s; paper Table 3 moduli), so the 40 s preload ramp leaves the base
  // state relaxed and the small-amplitude response is S11 + l^2 C1111_inf (1 + sum a_i i w tau_i/(1 + i w tau_i)).
  const auto terms = mat::prony_from_absolute(3.05, {23.9, 19.7}, {0.01, 0.1});
  const mat::Viscoelastic model(foam(), terms);
  cal::LabSpecimen specimen;
  cal::DynamicProtocol p;
  p.preload_strain = 0.25;
  p.acceleration_amplitude = 0.0025;  // small: about 0.03 mm at 1 Hz, linear regime
  p.frequencies_Hz = {1.0, 5.0, 20.0};
  p.cycles = 6;
  p.fit_cycles = 3;
  p.steps_per_cycle = 128;
  const cal::DynamicRecord rec = cal::run_dynamic(model, specimen, p, cal::LabNoise{}, 0);

  const double l = 0.75;
  cushion::Mat3 F = cushion::Mat3::Identity();
  F(0, 0) = l;
  const auto e = foam()->evaluate(F);
  for (std::size_t i = 0; i < rec.frequency_Hz.size(); ++i) {
    const double w = 2.0 * std::numbers::pi * rec.frequency_Hz[i];
    const std::complex<double> E = e.S(0) + l * l * e.dS_dE(0, 0) * mat::prony_complex_factor(terms, w);
    // 128 steps per cycle: interpolation error ~ (2 pi / 128)^2 / 12 = 2e-4; tolerance 0.5% and 0.2 deg.
    EXPECT_NEAR(rec.dynamic_modulus_kPa[i], std::abs(E) * 1000.0, 5e-3 * std::abs(E) * 1000.0) << rec.frequency_Hz[i];
    EXPECT_NEAR(rec.phase_deg[i], std::arg(E) * 180.0 / std::numbers::pi, 0.2) << rec.frequency_Hz[i];
  }
}

TEST(Lab, PlatenOnlyPushesAndForceIsNeverTensile) {
  // A slow-recovering foam unloaded fast: the platen leaves it behind and the machine reads zero.
  const auto terms = mat::prony_from_absolute(3.05, {23.9, 19.7, 8.99, 12.4, 8.14}, {0.01, 0.1, 1, 10, 100});
  const mat::Viscoelastic model(foam(), terms);
  cal::QuasiStaticProtocol p;
  p.rate_mm_min = 480.0;
  p.prior.preflex_cycles = 0;
  const auto rec = cal::run_quasi_static(model, cal::LabSpecimen{}, p);
  ASSERT_GT(rec.time_s.size(), 10u);
  bool lift_off = false;
  for (std::size_t k = 0; k < rec.force_N.size(); ++k) {
    EXPECT_GE(rec.force_N[k], 0.0) << "tensile force at t = " << rec.time_s[k];
    if (rec.force_N[k] == 0.0 && rec.displacement_mm[k] > 1.0) lift_off = true;
  }
  EXPECT_TRUE(lift_off) << "expected the foam to lag the platen on a 480 mm/min unload";
  EXPECT_NEAR(rec.displacement_mm.back(), 0.0, 1e-9);
}

TEST(Lab, NoiseIsSeededAndReproducible) {
  cal::QuasiStaticRecord a{{0, 1, 2}, {0, 1, 2}, {10.0, 20.0, 30.0}}, b = a, c = a;
  cal::LabNoise noise{7, 0.005, 0.0};
  cal::add_force_noise(a, noise, 3);
  cal::add_force_noise(b, noise, 3);
  cal::add_force_noise(c, noise, 4);
  EXPECT_EQ(a.force_N, b.force_N);
  EXPECT_NE(a.force_N, c.force_N);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_LT(std::abs(a.force_N[k] - 10.0 * (k + 1)), 0.1 * (k + 1));
}

TEST(Lab, BadTruthFilesNameTheKey) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "cushion_test_lab";
  fs::create_directories(dir);
  const auto expect_error = [&](const std::string& text, const std::string& key) {
    const fs::path f = dir / "truth.json";
    std::ofstream(f) << text;
    try {
      cal::read_lab_truth(f);
      FAIL() << "no error for " << text;
    } catch (const cushion::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("truth.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  const std::string specimen = R"("specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80})";
  expect_error(R"({"material": "m.json", )" + specimen + R"(, "quasi_static": [{"name": "a", "rate_mm_min": -5}]})",
               "quasi_static[0].rate_mm_min");
  expect_error(R"({"material": "m.json", )" + specimen + R"(, "dynamic": [{"name": "d", "preload_strain": 0.25,
               "acceleration_amplitude_m_s2": 0.25, "frequencies_Hz": [1, 2]}]})",
               "frequencies_Hz");
  expect_error(R"({"material": "m.json", )" + specimen + R"(, "quasi_static": [{"name": "a", "rate_mm_min": 5, "colour": 1}]})",
               "colour");
  expect_error(R"({"material": "m.json", )" + specimen + R"(})", "no test");
  expect_error(R"({"material": "m.json", "specimen": {"length_mm": 80}})", "width_mm");
  fs::remove_all(dir);
}

namespace {

/// A material file written to a temporary folder and read back.
cushion::material::MaterialDefinition material_from(const std::string& json, const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path f = fs::temp_directory_path() / ("cushion_test_lab_" + name + "_" + std::to_string(::getpid()) + ".json");
  std::ofstream(f) << json;
  auto def = cushion::material::read_material_file(f);
  fs::remove(f);
  return def;
}

const std::string visco_foam = R"({"name": "v", "hyperfoam": {"terms": [{"mu_kPa": 4, "alpha": 8, "nu": 0},
  {"mu_kPa": 2, "alpha": -2, "nu": 0}]}, "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.2, "tau_s": 0.05},
  {"g": 0.15, "tau_s": 1}, {"g": 0.1, "tau_s": 20}]}})";

}  // namespace

// amplitude_convention: peak_to_peak halves the acceleration, so a peak-to-peak 0.5 m/s^2 IS a peak 0.25 m/s^2.
TEST(LabProtocol, PeakToPeakHalvesTheAmplitude) {
  const auto m = material_from(visco_foam, "p2p");
  cal::DynamicProtocol a;
  a.frequencies_Hz = {1.0, 4.0, 12.0};
  a.cycles = 4, a.fit_cycles = 2;
  cal::DynamicProtocol b = a;
  a.acceleration_amplitude = 0.5, a.amplitude_peak_to_peak = true;
  b.acceleration_amplitude = 0.25, b.amplitude_peak_to_peak = false;
  EXPECT_DOUBLE_EQ(a.displacement_amplitude_mm(2.0), b.displacement_amplitude_mm(2.0));
  const auto ra = cal::run_dynamic(*m.model, cal::LabSpecimen{}, a, cal::LabNoise{}, 0);
  const auto rb = cal::run_dynamic(*m.model, cal::LabSpecimen{}, b, cal::LabNoise{}, 0);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(ra.dynamic_modulus_kPa[i], rb.dynamic_modulus_kPa[i], 1e-9 * rb.dynamic_modulus_kPa[i]);
    EXPECT_NEAR(ra.phase_deg[i], rb.phase_deg[i], 1e-9);
  }
  b.amplitude_peak_to_peak = true;  // the same number read peak-to-peak: half the strain, another modulus
  const auto rc = cal::run_dynamic(*m.model, cal::LabSpecimen{}, b, cal::LabNoise{}, 0);
  EXPECT_GT(std::abs(rc.dynamic_modulus_kPa[0] / rb.dynamic_modulus_kPa[0] - 1.0), 1e-4);
}

// dwell_before_sweep_s: the base stress relaxes during the dwell, which moves the modulus measured at the first
// frequencies (geometric term) and not at all once the dwell is long against every relaxation time.
TEST(LabProtocol, DwellBeforeTheSweepRelaxesTheBase) {
  const auto m = material_from(visco_foam, "dwell");
  cal::DynamicProtocol p;
  p.frequencies_Hz = {1.0, 2.0, 4.0};
  p.cycles = 4, p.fit_cycles = 2;
  const auto none = cal::run_dynamic(*m.model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  p.dwell_s = 30.0;
  const auto dwell = cal::run_dynamic(*m.model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  p.dwell_s = 2000.0;
  const auto long_dwell = cal::run_dynamic(*m.model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  p.dwell_s = 4000.0;
  const auto longer_dwell = cal::run_dynamic(*m.model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  EXPECT_GT(std::abs(dwell.dynamic_modulus_kPa[0] / none.dynamic_modulus_kPa[0] - 1.0), 1e-3);
  EXPECT_NEAR(long_dwell.dynamic_modulus_kPa[0], longer_dwell.dynamic_modulus_kPa[0], 1e-6 * long_dwell.dynamic_modulus_kPa[0]);
}

// preflex_cycles: a Mullins foam loaded after a preflex to the test's strain is softer on loading than the virgin
// foam; a viscoelastic foam after a preflex and a long rest is back to its virgin record.
TEST(LabProtocol, PreflexSoftensAMullinsFoamAndALongRestErasesViscousMemory) {
  const auto mullins = material_from(R"({"name": "m", "hyperfoam": {"terms": [{"mu_kPa": 4, "alpha": 8, "nu": 0},
    {"mu_kPa": 2, "alpha": -2, "nu": 0}]}, "effects": [{"kind": "mullins", "r": 1.5, "m_kPa": 0.5, "beta": 0.1}]})",
                                     "mullins");
  cal::QuasiStaticProtocol p;
  p.rate_mm_min = 120.0, p.sample_hz = 4.0;
  const auto virgin = cal::run_quasi_static(*mullins.model, cal::LabSpecimen{}, p);
  p.prior = {2, 0.75, 60.0};
  const auto flexed = cal::run_quasi_static(*mullins.model, cal::LabSpecimen{}, p);
  ASSERT_EQ(virgin.force_N.size(), flexed.force_N.size());
  const std::size_t mid = virgin.force_N.size() / 4;  // on loading, about 37 % strain
  EXPECT_NEAR(flexed.time_s[mid], virgin.time_s[mid], 1e-9);
  EXPECT_LT(flexed.force_N[mid], 0.99 * virgin.force_N[mid]);

  const auto visco = material_from(visco_foam, "rest");
  p.prior = {};
  const auto fresh = cal::run_quasi_static(*visco.model, cal::LabSpecimen{}, p);
  p.prior = {1, 0.75, 1e5};
  const auto rested = cal::run_quasi_static(*visco.model, cal::LabSpecimen{}, p);
  p.prior = {1, 0.75, 5.0};
  const auto short_rest = cal::run_quasi_static(*visco.model, cal::LabSpecimen{}, p);
  double worst_rested = 0.0, worst_short = 0.0, peak = 0.0;
  for (std::size_t k = 0; k < fresh.force_N.size(); ++k) {
    worst_rested = std::max(worst_rested, std::abs(rested.force_N[k] - fresh.force_N[k]));
    worst_short = std::max(worst_short, std::abs(short_rest.force_N[k] - fresh.force_N[k]));
    peak = std::max(peak, fresh.force_N[k]);
  }
  EXPECT_LT(worst_rested, 1e-6 * peak);
  EXPECT_GT(worst_short, 1e-3 * peak);
}

// lift_off false: bonded platens pull the lagging foam on a fast unload (tensile force); true: clipped at zero.
TEST(LabProtocol, LiftOffFalseBondsThePlatens) {
  const auto terms = mat::prony_from_absolute(3.05, {23.9, 19.7, 8.99, 12.4, 8.14}, {0.01, 0.1, 1, 10, 100});
  const mat::Viscoelastic model(foam(), terms);
  cal::QuasiStaticProtocol p;
  p.rate_mm_min = 480.0;
  p.lift_off = false;
  const auto bonded = cal::run_quasi_static(model, cal::LabSpecimen{}, p);
  EXPECT_LT(*std::min_element(bonded.force_N.begin(), bonded.force_N.end()), 0.0);
  p.lift_off = true;
  const auto platen = cal::run_quasi_static(model, cal::LabSpecimen{}, p);
  EXPECT_GE(*std::min_element(platen.force_N.begin(), platen.force_N.end()), 0.0);
}

// transient_steps_per_cycle: the cycles before the fitted ones only set the state the fitted cycles start from, so
// running them coarser (compare and diagnose: 32 steps a cycle against 64 in the fitted cycles) leaves |E*| and the
// phase within a fraction of the fitted cycles' own time-step error (64 against 256 steps everywhere). A foam with
// slow Prony terms (memory across the sweep), friction, trapped air and Mullins softening: the change stays below a
// third of that error at every frequency (measured: printed).
TEST(LabProtocol, CoarseTransientCyclesLeaveTheFittedCyclesAsTheyWere) {
  const auto m = material_from(R"({"name": "t", "hyperfoam": {"terms": [{"mu_kPa": 4, "alpha": 8, "nu": 0},
    {"mu_kPa": 2, "alpha": -2, "nu": 0}]}, "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.2, "tau_s": 0.05},
    {"g": 0.15, "tau_s": 1}, {"g": 0.1, "tau_s": 20}]}, "effects": [
    {"kind": "friction", "stiffness_kPa": 2, "yield_stress_kPa": 0.02},
    {"kind": "pneumatic", "permeability_mm2": 2e-5, "air_modulus_kPa": 3},
    {"kind": "mullins", "m_kPa": 5, "r": 2}]})", "transient");
  cal::DynamicProtocol fine;
  fine.frequencies_Hz = {1.0, 5.0, 20.0};
  fine.cycles = 20, fine.fit_cycles = 10, fine.steps_per_cycle = 64;
  cal::DynamicProtocol coarse = fine, reference = fine;
  coarse.transient_steps_per_cycle = 32;
  reference.steps_per_cycle = 256;
  const auto run = [&](const cal::DynamicProtocol& p) {
    return cal::run_dynamic(*m.model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  };
  const cal::DynamicRecord a = run(fine), b = run(coarse), r = run(reference);
  for (std::size_t i = 0; i < a.frequency_Hz.size(); ++i) {
    const double step_error = std::abs(a.dynamic_modulus_kPa[i] - r.dynamic_modulus_kPa[i]);
    const double phase_error = std::abs(a.phase_deg[i] - r.phase_deg[i]);
    const double change = std::abs(b.dynamic_modulus_kPa[i] - a.dynamic_modulus_kPa[i]);
    const double phase_change = std::abs(b.phase_deg[i] - a.phase_deg[i]);
    std::printf("  %4.1f Hz: |E*| %.5f kPa, 64-step error %.2e kPa, coarse-transient change %.2e kPa; phase %.3f deg, "
                "error %.2e, change %.2e deg\n", a.frequency_Hz[i], a.dynamic_modulus_kPa[i], step_error, change,
                a.phase_deg[i], phase_error, phase_change);
    EXPECT_LT(change, step_error / 3.0) << a.frequency_Hz[i] << " Hz";
    EXPECT_LT(phase_change, phase_error / 3.0) << a.frequency_Hz[i] << " Hz";
  }
}
