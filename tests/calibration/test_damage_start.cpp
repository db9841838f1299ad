// Requirement: the damage start of diagnose (calibration/damage_start.hpp, docs/physics.md 9.27) recovers a damage
// d = d_inf (1 - exp(-e_max/e_d)) from a quasi-static test's loading and unloading, and the undamaged curve of the
// specimen from its first loadings. The records are made here by the test's own closed form, independent of cushion's
// material code: a two-term hyperfoam at nu = 0 on free laterals, s_e(e) = -sum 2 mu_i/alpha_i (l^(alpha_i - 1) - 1/l),
// l = 1 - e, scaled by 1 - d(e_max) (no viscosity, or a given unloading over loading ratio standing for one), along a
// strain-controlled triangle 0 -> 0.75 -> 0.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "calibration/compare.hpp"
#include "calibration/damage_start.hpp"
#include "calibration/difference_stress.hpp"
#include "calibration/hyperfoam_fit.hpp"

namespace cushion::calibration {
namespace {

constexpr double kThickness = 50.0;  // [mm]
constexpr double kRate = 0.2;        // [mm/s] (12 mm/min)

/// The specimen's undamaged nominal stress [MPa] at nominal strain e (compression positive): mu 2 kPa / alpha 2 and
/// 8 kPa / alpha 12 (a foam's plateau and densification).
double undamaged(double e) {
  const double l = 1.0 - e;
  double s = 0.0;
  for (const auto& [mu, alpha] : {std::pair{2e-3, 2.0}, std::pair{8e-3, 12.0}})
    s -= 2.0 * mu / alpha * (std::pow(l, alpha - 1.0) - 1.0 / l);
  return s;
}

/// A campaign with one quasi-static test of the damaged specimen, and the noise estimate diagnose would pass
/// (1e-5 MPa everywhere: the records are exact). With `viscous_ratio`, the unloading is multiplied by it too (a
/// hysteresis that is not damage: the unloading over the loading of an undamaged viscous foam).
struct DamagedCampaign {
  Campaign campaign;
  std::vector<TestNoise> noise;
};
DamagedCampaign damaged_campaign(const LoadingDamage& d, double (*viscous_ratio)(double) = nullptr) {
  DamagedCampaign c;
  c.campaign.specimen = {100.0, 100.0, kThickness, 5e-11};
  QuasiStaticTest t;
  t.name = "qs_12";
  t.rate = kRate;
  const ProtocolHistory h = triangle_history(0.75, kRate / kThickness, 0.0, 0.25);
  t.record.source = "damaged.csv";
  t.record.time = h.time;
  t.record.strain = h.strain;
  double e_max = 0.0;
  for (double e : h.strain) {
    const double unloading = viscous_ratio && e < e_max ? viscous_ratio(e) : 1.0;
    e_max = std::max(e_max, e);
    t.record.stress.push_back((1.0 - d.limit * (1.0 - std::exp(-e_max / d.strain))) * unloading * undamaged(e));
  }
  t.record.line.assign(h.time.size(), 0);
  c.campaign.quasi_static.push_back(t);
  TestNoise n;
  n.known = true;
  n.stress = 1e-5;
  n.stress_local.assign(h.time.size(), 1e-5);
  c.noise.push_back(n);
  return c;
}

/// A base whose hyperfoam is off (one term, the wrong shape) with a Prony series that hardly relaxes.
material::MaterialSpec rough_base() {
  material::MaterialSpec s;
  s.hyperfoam = {{5e-3, 4.0, 0.0}, {1e-3, -2.0, 0.0}, {1e-3, 8.0, 0.0}};
  s.prony = {{1e-6, 1.0}};
  return s;
}

TEST(DamageStart, TheDamageOfALoadingAndUnloadingIsEstimatedOnItsGrid) {
  // d_inf 0.6 and e_d = 0.03 * 100^(12/24) = 0.3 lie on the estimate's grid: found exactly (1e-12); an undamaged record
  // gives d_inf 0.
  const LoadingDamage truth{0.6, 0.3};
  const std::optional<LoadingDamage> d = estimate_loading_damage(damaged_campaign(truth).campaign);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->limit, 0.6, 1e-12);
  EXPECT_NEAR(d->strain, 0.3, 1e-12);
  const std::optional<LoadingDamage> none = estimate_loading_damage(damaged_campaign({0.0, 0.3}).campaign);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->limit, 0.0);
}

/// An unloading over loading of a viscous foam without damage: 0.6 at zero strain, 1 at the peak (0.75).
double viscous_ratio(double e) { return 0.6 + 0.4 * e / 0.75; }

/// The comparison a base refit without damage but with that viscous hysteresis would give on the test (model: the
/// undamaged curve, its unloading times viscous_ratio), within `noise_ratio` of its noise.
CompareResult viscous_reference(const QuasiStaticTest& t, double noise_ratio) {
  TestCompare c;
  c.name = t.name;
  c.kind = "quasi_static";
  c.noise.known = true;
  RegionError all;
  all.region = "all";
  all.rms = noise_ratio * 1e-5;
  all.noise = 1e-5;
  c.regions.push_back(all);
  double e_max = 0.0;
  for (double e : t.record.strain) {
    if (e < e_max && c.unload_begin == 0) c.unload_begin = c.x.size();
    c.model.push_back((e < e_max ? viscous_ratio(e) : 1.0) * undamaged(e));
    e_max = std::max(e_max, e);
    c.x.push_back(e);
  }
  c.measured = t.record.stress;
  CompareResult r;
  r.tests.push_back(c);
  return r;
}

TEST(DamageStart, AReferenceModelsHysteresisIsNotTakenForDamage) {
  // The record's unloading is also lowered by a viscous ratio 0.6-1: on the record alone the estimate takes that for
  // damage (d_inf off by more than 0.2); relative to a reference model with that hysteresis (within 3x noise) it finds
  // d_inf 0.2 and e_d 0.3 of the grid (1e-12). A reference 10x noise off is not used (the same as without it).
  const LoadingDamage truth{0.2, 0.3};
  const DamagedCampaign c = damaged_campaign(truth, viscous_ratio);
  const std::optional<LoadingDamage> alone = estimate_loading_damage(c.campaign);
  ASSERT_TRUE(alone);
  EXPECT_GT(std::abs(alone->limit - 0.2), 0.2) << "the record alone: d_inf " << alone->limit;
  const CompareResult close = viscous_reference(c.campaign.quasi_static[0], 1.0);
  const std::optional<LoadingDamage> relative = estimate_loading_damage(c.campaign, &close);
  ASSERT_TRUE(relative);
  EXPECT_NEAR(relative->limit, 0.2, 1e-12);
  EXPECT_NEAR(relative->strain, 0.3, 1e-12);
  const CompareResult far = viscous_reference(c.campaign.quasi_static[0], 10.0);
  const std::optional<LoadingDamage> ignored = estimate_loading_damage(c.campaign, &far);
  ASSERT_TRUE(ignored);
  EXPECT_EQ(ignored->limit, alone->limit);
  EXPECT_EQ(ignored->strain, alone->strain);
}

TEST(DamageStart, TheBaseOfTheDamageStartFollowsTheUndamagedCurve) {
  // From the rough base, the hyperfoam refitted to the first loading over 1 - d(e) follows the undamaged curve within
  // 1 % of its peak stress from 0 to 0.75 (the rough base is off by more than 20 %), and the base's Prony series is kept.
  const LoadingDamage truth{0.6, 0.3};
  const DamagedCampaign c = damaged_campaign(truth);
  const std::optional<material::MaterialSpec> base = damaged_loading_base(rough_base(), c.campaign, c.noise, truth);
  ASSERT_TRUE(base);
  std::vector<double> strain;
  for (int k = 1; k <= 75; ++k) strain.push_back(0.01 * k);
  const std::vector<double> fitted = hyperfoam_uniaxial_stress(base->hyperfoam, 0.0, Lateral::free, strain);
  const std::vector<double> rough = hyperfoam_uniaxial_stress(rough_base().hyperfoam, 0.0, Lateral::free, strain);
  const double peak = undamaged(0.75);
  double worst = 0.0, worst_rough = 0.0;
  for (std::size_t k = 0; k < strain.size(); ++k) {
    worst = std::max(worst, std::abs(fitted[k] - undamaged(strain[k])) / peak);
    worst_rough = std::max(worst_rough, std::abs(rough[k] - undamaged(strain[k])) / peak);
  }
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(worst_rough, 0.2);
  ASSERT_EQ(base->prony.size(), 1u);
  EXPECT_EQ(base->prony[0].g, 1e-6);
}

TEST(DamageStart, NoStartWithoutAQuasiStaticTestOrAHyperfoamBase) {
  EXPECT_FALSE(estimate_loading_damage(Campaign{}));
  const DamagedCampaign c = damaged_campaign({0.6, 0.3});
  material::MaterialSpec neo = rough_base();
  neo.base = material::MaterialSpec::Base::neo_hookean;
  EXPECT_FALSE(damaged_loading_base(neo, c.campaign, c.noise, {0.6, 0.3}));
}

}  // namespace
}  // namespace cushion::calibration
