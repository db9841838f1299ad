#pragma once
/// Test support: seeded random plausible seat foams and their noise-free lab campaigns, for the
/// round trip of `cushion fit` over many materials (test_fit_random_foams.cpp).
///
/// A foam (make_random_foam(seed), identical on every platform: mt19937_64 and own uniform draws):
///   hyperfoam, N = 2..4 terms, nu = 0: the first term a plateau term alpha in [2, 25]; every other term
///     with equal odds a densification term alpha in [-8, -1] or another alpha in [2, 25]. The terms'
///     shares of the stress at 50 % compression are drawn (log-uniform; densification terms smaller), the
///     stress at 50 % is 1..10 kPa (log-uniform), mu_i follow. A positive-alpha term other than the first
///     may be negative (a softening correction, 1 in 6). A draw is kept when the foam is plausible
///     (stress at 75 % / stress at 50 % in [1.3, 30]) and Drucker-stable over nominal strain [-0.9, 0.5]
///     (material/stability.hpp), else drawn again from the same stream.
///   Prony series at tau = 0.01, 0.1, 1, 10, 100 s (the fit's preset times): each decade present with
///     probability 3/4 (at least one), weights log-uniform in [0.1, 1], total g in [0.2, 0.6].
///   density 30..80 kg/m^3.
/// The campaign: the material file is written and `cushion lab` (calibration::run_lab) runs the paper's
/// protocols as the shipped cases/campaign_synthetic/truth.json does, NOISE-FREE: quasi-static 120 mm/min
/// (10 Hz), 30 mm/min (4 Hz), 480 mm/min (40 Hz) to 75 %, 2 s hold, no preflex, all for calibration;
/// dynamic about a 25 % preload (30 mm/min ramp), 0.25 m/s^2 peak to peak, 1..20 Hz, 20 cycles, the last
/// 10 sine-fitted, 64 steps per cycle.
#include <filesystem>
#include <string>

#include "calibration/fit_model.hpp"

namespace cushion::random_foam {

struct RandomFoam {
  unsigned long long seed = 0;
  calibration::ViscoHyperfoam material;  ///< long-term hyperfoam + relative Prony moduli g_i
  double density_kg_m3 = 0.0;
  int draws = 0;                         ///< draws until plausible and stable
  std::string describe() const;          ///< one line: terms and Prony
};

RandomFoam make_random_foam(unsigned long long seed);

/// Writes DIR/truth_material.json and runs the lab into DIR/campaign (DIR created, overwritten);
/// returns the campaign manifest DIR/campaign/campaign.json.
std::filesystem::path make_random_foam_campaign(const RandomFoam& foam, const std::filesystem::path& dir);

}  // namespace cushion::random_foam
