#pragma once
/// Tests that would separate two models which explain a campaign about equally well (diagnose: "when two families
/// explain the data equally, say so and name the test that would separate them"; docs/physics.md 9.4). No effect
/// is known by name here: every proposal is a test the campaign does not have, built from the campaign's own
/// protocols, and both models run it with the campaign's forward models (lab.hpp run_quasi_static, run_dynamic):
///   quasi-static (from the test at the middle rate, its preflex, hold and lift-off):
///     - at a tenth of the slowest rate, and at five times the fastest (rate dependence of the hysteresis);
///     - repeated at once on the same specimen (one more preflex cycle to its peak, no rest: a second loading);
///     - with a 300 s hold at the peak (relaxation at constant strain);
///     - to half its peak strain (strain dependence of the loop);
///   dynamic (from the first dynamic test: frequencies, amplitude, convention, ramp, dwell, cycles):
///     - at half the lowest preload and at the highest + 0.15 (at most 0.7): preload dependence;
///     - at a quarter and at four times the excitation amplitude: amplitude dependence.
/// Separation: the RMS over the record of the difference of the two predictions, in units of the campaign's noise
/// for that kind of test, as compare's error/noise: quasi-static, the median RMS stress noise of the campaign's
/// quasi-static tests; dynamic, sqrt((m^2 + p^2)/2) with m the RMS |E*| difference over the campaign's relative |E*|
/// noise (median over its dynamic tests, times the mean |E*| of the two predictions; at a quarter amplitude the
/// relative noise is taken four times larger, a load cell's floor weighing more on a smaller force) and p the RMS
/// phase difference over the campaign's phase noise. What one such test adds to the evidence: data made by one model
/// would give the other a chi2 larger by about n s^2 (n the test's noise-normalised residuals as diagnose counts them:
/// quasi_static_points for a quasi-static test, two per frequency for a sweep), to compare with the evidence
/// threshold (Delta-BIC 10).
#include <string>
#include <vector>

#include "calibration/compare.hpp"
#include "material/material.hpp"

namespace cushion::calibration {

struct SeparatingTest {
  std::string name;         ///< what to run, in words with units ("quasi-static at 1.2 mm/min (a tenth of ...)")
  double separation = 0.0;  ///< RMS difference of the two predictions over the noise [-]; NaN when a run failed
  int residuals = 0;        ///< n: noise-normalised residuals of such a test in diagnose's chi2
  std::string failure;      ///< why a run failed (empty when both ran)
  double delta_chi2() const { return residuals * separation * separation; }  ///< n s^2 [-]
};

/// Every proposal the campaign allows (none of a kind without a test of that kind with a noise estimate), run with
/// `a` and `b`, largest delta_chi2 first (failed runs last). quasi_static_points: diagnose's residual samples per
/// quasi-static test.
std::vector<SeparatingTest> separating_tests(const material::Material& a, const material::Material& b,
                                             const Campaign& campaign, const std::vector<TestNoise>& noise,
                                             const CompareOptions& options, int quasi_static_points);

}  // namespace cushion::calibration
