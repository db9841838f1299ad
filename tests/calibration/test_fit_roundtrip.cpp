// Acceptance of `cushion fit` (issue "Calibration"): round trip through the virtual lab. A campaign is
// generated in the test from a known solver material (the truth) with calibration::run_quasi_static /
// run_dynamic, fitted by fit_pipeline, and the result compared with the truth.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/fit_pipeline.hpp"
#include "calibration/lab.hpp"
#include "material/hyperfoam.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;

namespace {

/// Truth: the shipped synthetic truth (cases/campaign_synthetic/truth_material.json): assumed hyperfoam,
/// nu = 0, with the paper's Table 3 Prony moduli made relative to its tangent at the 25 % preload.
cal::ViscoHyperfoam truth() {
  return {{{0.010, 10.0, 0.0}, {0.0001, -2.0, 0.0}, {0.0005, 3.0, 0.0}},
          {{0.283893, 0.01}, {0.234004, 0.1}, {0.106786, 1.0}, {0.147292, 10.0}, {0.096690, 100.0}}};
}

/// A campaign from the lab as the shipped one (cases/campaign_synthetic): quasi-static 120 mm/min (10 Hz), 30 mm/min
/// (4 Hz) and 480 mm/min (40 Hz) to 75 %, 2 s hold, no preflex, all three marked for calibration (the first carries
/// the paper's method); dynamic at 25 % preload, 0.25 m/s^2 peak to peak, 10 frequencies 1..20 Hz, 20 cycles, the
/// last 10 sine-fitted, 256 steps per cycle. Noise (seeded): `noise` of the force reading (quasi-static) and of
/// the oscillating force amplitude (dynamic), plus 0.02 N.
cal::Campaign lab_campaign(double noise, int rates = 3) {
  const auto model = cal::build_model(truth());
  const cal::LabSpecimen specimen;
  cal::LabNoise lab_noise;
  lab_noise.seed = 7;
  lab_noise.force_relative = noise;
  lab_noise.force_floor = noise > 0.0 ? 0.02 : 0.0;
  cal::Campaign c;
  c.specimen = {80.0, 80.0, 80.0, 6.5e-11};
  const double rate_mm_min[] = {120.0, 30.0, 480.0}, sample_hz[] = {10.0, 4.0, 40.0};
  for (int k = 0; k < rates; ++k) {
    cal::QuasiStaticProtocol q;
    q.rate_mm_min = rate_mm_min[k];
    q.sample_hz = sample_hz[k];
    q.prior.preflex_cycles = 0;
    cal::QuasiStaticRecord r = cal::run_quasi_static(*model, specimen, q);
    cal::add_force_noise(r, lab_noise, k);
    cal::QuasiStaticTest t;
    t.name = "qs_" + std::to_string(int(rate_mm_min[k]));
    t.use = cal::TestUse::calibration;
    t.rate = rate_mm_min[k] / 60.0;
    t.record = cal::to_nominal(t.name + ".csv", r.time_s, r.displacement_mm, r.force_N, c.specimen);
    c.quasi_static.push_back(t);
  }
  cal::DynamicProtocol d;
  d.frequencies_Hz = {1, 2, 3, 4, 6, 8, 10, 13, 16, 20};
  d.steps_per_cycle = 256;
  const cal::DynamicRecord dr = cal::run_dynamic(*model, specimen, d, lab_noise, 10);
  cal::DynamicTest dt;
  dt.name = "dyn";
  dt.use = cal::TestUse::calibration;
  dt.preload_strain = 0.25;
  dt.acceleration_amplitude = 250.0;  // mm/s^2, peak to peak
  for (std::size_t i = 0; i < dr.frequency_Hz.size(); ++i) {
    const double E = dr.dynamic_modulus_kPa[i] * 1e-3, ph = dr.phase_deg[i] * M_PI / 180.0;
    dt.moduli.frequency.push_back(dr.frequency_Hz[i]);
    dt.moduli.storage.push_back(E * std::cos(ph));
    dt.moduli.loss.push_back(E * std::sin(ph));
  }
  c.dynamic.push_back(dt);
  return c;
}

/// max |model - truth| of the long-term hyperfoam curves over the tested strain range / truth peak.
double curve_error(const cal::ViscoHyperfoam& m, double peak_strain) {
  std::vector<double> e;
  for (int i = 0; i <= 100; ++i) e.push_back(peak_strain * i / 100.0);
  const auto t = cal::hyperfoam_uniaxial_stress(truth().terms, 0.0, cal::Lateral::free, e);
  const auto f = cal::hyperfoam_uniaxial_stress(m.terms, m.terms.front().nu, cal::Lateral::free, e);
  double err = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) err = std::max(err, std::abs(f[i] - t[i]));
  return err / t.back();
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

std::ostringstream quiet;

/// max over the frequencies of the relative error of E' and E'' of `m` about the 25 % preload (small
/// amplitude, relaxed) against the truth's.
double dynamic_curve_error(const cal::ViscoHyperfoam& m) {
  std::vector<double> f;
  for (int i = 1; i <= 20; ++i) f.push_back(i);
  const auto T = cal::model_dynamic_moduli(*cal::build_model(truth()), mat::Hyperfoam(truth().terms), 0.25, f);
  const auto M = cal::model_dynamic_moduli(*cal::build_model(m), mat::Hyperfoam(m.terms), 0.25, f);
  double err = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i)
    err = std::max({err, std::abs(M.storage[i] / T.storage[i] - 1.0), std::abs(M.loss[i] / T.loss[i] - 1.0)});
  return err;
}

}  // namespace

TEST(FitRoundTrip, NoiseFreeRecoversTheTruth) {
  const cal::Campaign c = lab_campaign(0.0);
  const cal::FitResult R = cal::fit_pipeline(c, cal::FitOptions{}, quiet);
  EXPECT_NEAR(R.segments.peak_strain, 0.75, 1e-9);
  // Step 3: the hereditary difference stress, RMSE below 1 % of its peak (acceptance).
  EXPECT_LT(R.hereditary.rmse, 0.01 * max_abs(R.hereditary.measured));
  // Step 8 on the three calibration rates: the long-term curve within 0.5 % of its peak over the tested
  // strain range and every Prony modulus within 1 % (acceptance; reached: 0.005 % and 0.08 %).
  ASSERT_TRUE(R.refit.has_value());
  EXPECT_TRUE(R.refit->accepted()) << R.refit->report;
  EXPECT_EQ(R.default_choice, cal::DefaultMaterial::refit);
  EXPECT_LT(curve_error(R.refit->material, R.segments.peak_strain), 0.005);
  const auto a_truth = cal::long_term_ratios(truth().prony);
  const auto a_fit = cal::long_term_ratios(R.refit->material.prony);
  ASSERT_EQ(a_fit.size(), a_truth.size());
  for (std::size_t i = 0; i < a_truth.size(); ++i) EXPECT_NEAR(a_fit[i], a_truth[i], 0.01 * a_truth[i]) << "term " << i;
  // The solver's model after the refit is closer to every test than the paper's material.
  for (const auto& t : R.comparisons) EXPECT_LT(t.error_refit, t.error_paper) << t.name;
}

TEST(FitRoundTrip, OneRateLeavesTheSlowTermsAndTheLongTermCurveTradingOff) {
  // With only the 120 mm/min test (the default method) the refit fits both tests to 0.1 % but the
  // 100 s term and the long-term curve trade off: the recovery misses the 1 % / 0.5 % targets. This is why
  // the shipped campaign calibrates on three rates (README); the figures are in the h4c report.
  const cal::Campaign c = lab_campaign(0.0, 1);
  const cal::FitResult R = cal::fit_pipeline(c, cal::FitOptions{}, quiet);
  ASSERT_TRUE(R.refit.has_value());
  EXPECT_LT(R.refit->quasi_static_rms, 0.002);
  EXPECT_LT(R.refit->dynamic_rms, 0.002);
  const auto a_truth = cal::long_term_ratios(truth().prony);
  const auto a_fit = cal::long_term_ratios(R.refit->material.prony);
  EXPECT_GT(std::abs(a_fit[4] / a_truth[4] - 1.0) + curve_error(R.refit->material, R.segments.peak_strain), 0.01);
}

TEST(FitRoundTrip, HalfPercentNoiseStaysWithinTwoPercentAndIsRepeatable) {
  const cal::FitResult R1 = cal::fit_pipeline(lab_campaign(0.005), cal::FitOptions{}, quiet);
  const cal::FitResult R2 = cal::fit_pipeline(lab_campaign(0.005), cal::FitOptions{}, quiet);
  ASSERT_TRUE(R1.refit && R2.refit);
  EXPECT_TRUE(R1.refit->accepted()) << R1.refit->report;
  // Recovered curves within 2 %: the long-term curve (of its peak) and E', E'' about the preload.
  EXPECT_LT(curve_error(R1.refit->material, R1.segments.peak_strain), 0.02);
  EXPECT_LT(dynamic_curve_error(R1.refit->material), 0.02);
  EXPECT_LT(R1.hereditary.rmse, 0.02 * max_abs(R1.hereditary.measured));
  // Identical on every run (seeded noise, deterministic fits).
  for (std::size_t i = 0; i < R1.refit->material.terms.size(); ++i) {
    EXPECT_EQ(R1.refit->material.terms[i].mu, R2.refit->material.terms[i].mu);
    EXPECT_EQ(R1.refit->material.terms[i].alpha, R2.refit->material.terms[i].alpha);
    EXPECT_EQ(R1.hyperfoam.terms[i].mu, R2.hyperfoam.terms[i].mu);
  }
  for (std::size_t i = 0; i < R1.refit->material.prony.size(); ++i)
    EXPECT_EQ(R1.refit->material.prony[i].g, R2.refit->material.prony[i].g);
  EXPECT_EQ(R1.hereditary.rmse, R2.hereditary.rmse);
  EXPECT_EQ(R1.prony.E_inf, R2.prony.E_inf);
}
