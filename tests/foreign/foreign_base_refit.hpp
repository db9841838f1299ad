#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: how much of an effect a base of the generator's OWN family can absorb.
///
/// The base foam's parameters (hyperfoam ln mu_i and alpha_i, Prony ln a_j and ln tau_j, a_j = g_j/(1 - sum g); the
/// term counts of the truth's base kept) are refitted by Levenberg-Marquardt (forward-difference Jacobian, Eigen) to
/// the noise-free records of the plan made with the effects, minimising the sum of squared noise-normalised
/// differences (normalised_differences). What the best base leaves is the part of the effects that no base of this
/// family can take up: an effect that a refitted base reproduces within the noise cannot be told from a base on
/// these tests by any method, whatever its size against the TRUE base. Linked to nothing of cushion: the verdict of
/// cushion's own fit never decides which effects count as visible.
#include <map>
#include <string>
#include <vector>

#include "foreign_foam.hpp"
#include "foreign_plan.hpp"

namespace foreign_bench {

struct BaseRefit {
  BaseFoam base;                                ///< the refitted base
  std::vector<EffectSpec> kept;                 ///< the kept effects with their refitted magnitudes
  std::map<std::string, double> ratio_before;   ///< per test: the effects over noise against the true base [-]
  std::map<std::string, double> ratio_after;    ///< per test: what the refitted base leaves, in noise units [-]
  double chi2_before = 0.0, chi2_after = 0.0;   ///< sums of squared noise-normalised differences [-]
  int iterations = 0;                           ///< Levenberg-Marquardt iterations taken
};

/// Refits `truth_base` (from `start`, the truth's base when null) to the noise-free plan records of truth_base +
/// effects. Never ends above its start's chi2. With `kept`, the model is the base plus those effects, each with its
/// form's magnitude refitted too (a log factor, from 1, the shape parameters as given): what is left is then the part
/// of the data that neither the base nor the kept effects can take up, e.g. the weaker member of a pair beyond the
/// stronger one (CampaignTruth::member_beyond_partner).
constexpr int base_refit_iterations = 25;  ///< Levenberg-Marquardt iterations of a refit by default
BaseRefit refit_base(const BaseFoam& truth_base, const std::vector<EffectSpec>& effects, const TestPlan& plan,
                     const BaseFoam* start = nullptr, int max_iterations = base_refit_iterations,
                     const std::vector<EffectSpec>& kept = {});

}  // namespace foreign_bench
