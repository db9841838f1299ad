// Difference-stress method and hereditary fit: pairing with a hold and with truncated unloading,
// recovery of known parameters from a synthetic record, and the decomposition.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/decomposition.hpp"
#include "calibration/hereditary_fit.hpp"
#include "synthetic_records.hpp"

namespace cal = cushion::calibration;
using cal::cplx;
using cal::testing::known_modes;
using cal::testing::synthetic_record;

TEST(DifferenceStress, PairsAtEqualStrainWithHold) {
  const auto r = synthetic_record(known_modes(), 2.0);
  const auto s = cal::detect_segments(r);
  const auto p = cal::pair_loading_unloading(r, s, 1.0);
  // The synthetic unloading stress reaches ~0 near eps = 0.07 (the viscous stress is tensile there),
  // so the last loading seconds are unpaired: 27 of the 30 pairs remain.
  ASSERT_GE(p.t1.size(), 27u);
  for (std::size_t i = 0; i < p.t1.size(); ++i) {
    // With a hold t1 + t2 = 2T + hold (not T); strains equal to round-off.
    EXPECT_NEAR(p.t1[i] + p.t2[i], 62.0, 1e-9);
    EXPECT_NEAR(cal::interpolate(r.time, r.strain, p.t2[i]), p.strain[i], 1e-12);
  }
}

TEST(DifferenceStress, TruncatedUnloadingPairsOnlyThePairedPart) {
  auto r = synthetic_record(known_modes(), 2.0);
  // Foam lifts off at strain 0.2: force ~0 from there on while the platen keeps retracting.
  for (std::size_t i = 0; i < r.time.size(); ++i)
    if (r.time[i] > 32.0 && r.strain[i] < 0.2) r.stress[i] = 0.0;
  const auto s = cal::detect_segments(r);
  ASSERT_TRUE(s.lift_off);
  const auto p = cal::pair_loading_unloading(r, s, 1.0);
  ASSERT_FALSE(p.t1.empty());
  for (double e : p.strain) EXPECT_GE(e, s.lift_off_strain);
  EXPECT_EQ(p.t1.size(), 23u);  // t1 = 8 .. 30 s (eps = 0.2 .. 0.75)
}

TEST(DifferenceStress, FitRecoversKnownParametersNoiseFree) {
  const auto truth = cal::canonical(known_modes());
  const auto r = synthetic_record(truth, 2.0);
  const auto s = cal::detect_segments(r);
  const auto p = cal::pair_loading_unloading(r, s, 1.0);
  const auto fit = cal::fit_hereditary(r, s, p);
  // Noise-free: RMSE below 1e-6 of the peak stress.
  EXPECT_LT(fit.rmse_relative, 1e-6) << fit.report;
  ASSERT_EQ(fit.modes.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    // All 8 parameters identifiable here (distinct decay rates, Im beta != 0): 1e-4 relative.
    EXPECT_NEAR(fit.modes[i].alpha.real(), truth[i].alpha.real(), 1e-4 * std::abs(truth[i].alpha.real()));
    EXPECT_NEAR(fit.modes[i].alpha.imag(), truth[i].alpha.imag(), 1e-4 * std::abs(truth[i].alpha.imag()));
    EXPECT_NEAR(fit.modes[i].beta.real(), truth[i].beta.real(), 1e-4 * std::abs(truth[i].beta.real()));
    EXPECT_NEAR(fit.modes[i].beta.imag(), truth[i].beta.imag(), 1e-4 * std::abs(truth[i].beta.imag()));
  }
}

TEST(DifferenceStress, DecompositionWithTrueModesRecoversTheElasticCurve) {
  const auto r = synthetic_record(known_modes(), 2.0);
  const auto s = cal::detect_segments(r);
  const auto d = cal::decompose(r, s, known_modes());
  // sigma_e = sigma - sigma_v is f(eps) to round-off on both branches.
  for (std::size_t i = 0; i < d.time.size(); ++i)
    EXPECT_NEAR(d.sigma_e[i], cal::testing::elastic_f(d.strain[i]), 1e-14);
  // Branch agreement exact up to time interpolation of f (second order in dt = 0.05 s): < 1e-5 of peak.
  EXPECT_LT(d.branch_mismatch, 1e-5);
  // Elastic curve: linear interpolation between pairs 0.15 s (strain 0.00375) apart, error
  // h^2/8 max f'' = 2.4e-7 MPa = 2.3e-5 of the peak: tolerance 3e-5 of the peak.
  for (std::size_t k = 0; k < d.elastic.strain.size(); ++k)
    EXPECT_NEAR(d.elastic.stress[k], cal::testing::elastic_f(d.elastic.strain[k]), 3e-5 * s.peak_stress);
  // A wrong model (no viscous stress) leaves a clear branch mismatch.
  EXPECT_GT(cal::decompose(r, s, {}).branch_mismatch, 1e-2);
}
