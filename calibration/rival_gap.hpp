#pragma once
/// How firmly a campaign prefers one fitted candidate to another when the noise estimates that weight its tests are
/// themselves uncertain (diagnose step 7, Rival; docs/physics.md 9.31).
///
/// diagnose ranks candidates by BIC = chi2 + k ln N, chi2 = sum over tests t of chi2_t, each residual divided by the
/// test's noise estimated from the data (compare_metrics.hpp). An estimate sigma_t that is off by a factor c_t scales
/// chi2_t by 1/c_t^2. With every c_t anywhere in [1/u_t, u_t] (u_t >= 1 the estimate's uncertainty as a factor on the
/// RMS noise), the smallest BIC advantage of a winner w over another candidate o is
///
///   gap = P + sum_t s_t (chi2_t(o) - chi2_t(w)),   s_t = u_t^2 where chi2_t(o) < chi2_t(w), else 1/u_t^2,
///
/// P the difference of their parameter penalties (BIC_o - BIC_w - (chi2_o - chi2_w)): each test's weight is pushed to
/// the end of its range that favours o. With every u_t = 1 the gap is BIC_o - BIC_w, the plain dBIC difference.
#include <string>
#include <vector>

namespace cushion::calibration {

/// Uncertainty of a test's estimated noise, as a factor on the RMS noise, by kind of test (>= 1) [-]. Measured
/// (docs/physics.md 9 and 9.1): the quasi-static RMS estimate within 15 % of the true noise on seeded lab records
/// (CompareNoise.ReadingNoise...), the sweep's per-frequency estimate with its median within 0.6-1.6x of the true
/// sigma on smooth spectra (CompareNoise.SpectrumNoisePerFrequency...). On the foreign benchmark sets the sweep
/// estimate is 5-11x the drawn noise at 1-3 Hz (median) and about right at 11-20 Hz (docs/physics.md 9.32), so 1.6 is
/// the accuracy where the spectrum is smooth, not a bound.
struct NoiseUncertainty {
  double quasi_static = 1.15;  ///< quasi-static and indentation records
  double dynamic = 1.6;        ///< dynamic sweeps (|E*| and phase, or |K*| and phase)
  /// The factor for a test of `kind` (compare.hpp TestCompare::kind).
  double of(const std::string& kind) const;
};

/// The smallest BIC advantage of the winner over the other candidate [-] (formula above): chi2 per test of each
/// (same tests, same order), the uncertainty factor u_t of each test (>= 1), and the penalty difference P. Throws
/// std::invalid_argument when the three vectors differ in length or a factor is below 1 or not finite.
double least_bic_gap(const std::vector<double>& chi2_winner, const std::vector<double>& chi2_other,
                     const std::vector<double>& uncertainty, double penalty_difference);

}  // namespace cushion::calibration
