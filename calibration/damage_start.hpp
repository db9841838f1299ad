#pragma once
/// The start of a damage that softens the first loading too (catalogue: EffectInfo::damage_limit_parameter; mullins
/// damage_limit d_inf and damage_strain e_d, d = d_inf (1 - exp(-e_max/e_d))), docs/physics.md 9.27 and 9.28.
///
/// `cushion fit` and the base refit read a damaged foam's first loading as the base's curve, so the base a damage is
/// fitted on is already softened by 1 - d(e): a joint fit from there has to raise the base by up to 1/(1 - d_inf) along
/// the strain while it switches the damage on, which the factors on mu_i (within a decade) do not follow (seed-2027
/// c017, d_inf 0.95: chi2/N 43.5 after). The start made here instead:
///   1. (d_inf, e_d) from one quasi-static test (the slowest rate: the least viscous hysteresis): with the specimen's
///      undamaged curve s_e, its first loading is (1 - d(e)) s_e(e) and its unloading from the peak e_p is
///      (1 - d(e_p)) s_e(e), so the unloading over the loading at the same strain is (1 - d(e_p))/(1 - d(e)); the pair
///      of a grid (e_d 0.03-3 in 25 log steps, d_inf 0-0.98 in steps of 0.02) with the least squared difference of
///      predicted and measured unloading stress; where the base refit reproduces that test within 3x noise, the
///      prediction is also multiplied by the base refit's own unloading over loading (its viscous hysteresis, which the
///      record alone would take for damage; docs/physics.md 9.28);
///   2. the base's hyperfoam refitted (calibration/refit.hpp, its global exponent search, no dynamic test) to the
///      first loadings of the quasi-static tests whose specimen has no preflex, each measured stress divided by
///      1 - d(e) of step 1 and weighed by its noise; the base's Prony series is kept (a refit on first loadings alone
///      cannot place it). With d = 0 this is the hyperfoam of the first loadings (a virgin curve).
/// Units: nominal strain [-], MPa; compression positive.
#include <optional>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "material/io/material_file.hpp"

namespace cushion::calibration {

/// d = limit (1 - exp(-e_max/strain)).
struct LoadingDamage {
  double limit = 0.0;                 ///< d_inf [-]
  double strain = 0.3;                ///< e_d [-]
  double factor(double e_max) const;  ///< 1 - d(e_max)
};

/// Error over noise of the slowest quasi-static test up to which a reference model's hysteresis is read as the viscous
/// one (estimate_loading_damage). Further off, the reference (a base refit without damage) has stretched its Prony
/// series over a damage's hysteresis: relative to it, seed-2027 c017 (d_inf 0.95, base refit 30.7x noise) gave d_inf
/// 0.56 and its named Mullins left 5.15x noise instead of 3.9x; within it, seed-2026 c014 (d_inf 0.11, 1.99x) gave
/// 0.04 instead of 0.92 and Mullins was named instead of friction (docs/physics.md 9.28).
constexpr double reference_noise_ratio = 3.0;

/// Step 1 on the campaign's slowest quasi-static test; nullopt without a quasi-static test. With `reference` (a
/// comparison of a model without damage with the campaign, the base refit's) that reproduces that test within
/// reference_noise_ratio of its noise, the unloading over the loading is read relative to that model's own at the same
/// strain (its viscous hysteresis): (1 - d(e_p))/(1 - d(e)) times the model's unloading over its loading, so that the
/// hysteresis the model already has is not taken for damage (the estimate on the record alone reads 0.84-0.98 on
/// friction and control-like campaigns).
std::optional<LoadingDamage> estimate_loading_damage(const Campaign& campaign,
                                                     const CompareResult* reference = nullptr);

/// Step 2: `base` (a hyperfoam base with a Prony series, long-term convention) with its hyperfoam refitted to the first
/// loadings over 1 - d(e); nullopt when no quasi-static test qualifies or the refit is not usable (not converged or
/// Drucker-unstable).
std::optional<material::MaterialSpec> damaged_loading_base(const material::MaterialSpec& base, const Campaign& campaign,
                                                           const std::vector<TestNoise>& noise,
                                                           const LoadingDamage& damage);

}  // namespace cushion::calibration
