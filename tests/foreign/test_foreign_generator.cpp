// Test-data generation for the diagnose benchmark (issue 15), independent of cushion's material/ and
// calibration/: checks of the foreign 1D test machine against closed forms (label `foreign`).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <numbers>
#include <set>

#include "foreign_campaign.hpp"

namespace foreign_bench {
namespace {

BaseFoam sample_foam(const std::string& family, std::uint64_t seed) {
  Random random(seed);
  return draw_base_foam(family, random);
}

TEST(ForeignFoam, StressIsTheStrainDerivativeOfTheEnergyAndTangentItsDerivative) {
  for (const std::string family : {"soft_plateau_50", "stiff_65", "random"})
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const BaseFoam foam = sample_foam(family, seed);
      const double stress_50 = foam.elastic_stress_kPa(0.5);
      EXPECT_GE(stress_50, 1.0) << family;
      EXPECT_LE(stress_50, 10.0) << family;
      for (double e = 0.02; e <= 0.8; e += 0.06) {
        const double h = 1e-6;
        const double energy_fd = (foam.energy_kPa(e + h) - foam.energy_kPa(e - h)) / (2 * h);
        const double stress_fd = (foam.elastic_stress_kPa(e + h) - foam.elastic_stress_kPa(e - h)) / (2 * h);
        EXPECT_GT(foam.elastic_stress_kPa(e), 0.0) << family << " e = " << e;
        EXPECT_NEAR(foam.elastic_stress_kPa(e), energy_fd, 1e-6 * std::abs(energy_fd)) << family << " e = " << e;
        EXPECT_NEAR(foam.elastic_tangent_kPa(e), stress_fd, 1e-6 * std::abs(stress_fd)) << family << " e = " << e;
      }
    }
}

TEST(ForeignFoam, PronyRelaxationAfterAStepIsASumOfExponentials) {
  const BaseFoam foam = sample_foam("stiff_65", 3);
  FoamSpecimen specimen(foam, {});
  const double e0 = 0.3, step_s = 1e-9;
  specimen.step(e0, step_s);
  const double elastic = foam.elastic_stress_kPa(e0);
  double t = 0.0;
  for (double dt : {0.001, 0.004, 0.02, 0.1, 0.5, 2.0, 10.0, 40.0, 150.0}) {
    const double stress = specimen.step(e0, dt);
    t += dt;
    double expected = elastic;
    for (const auto& p : foam.prony) expected += p.g / (1.0 - foam.prony_sum()) * elastic * std::exp(-t / p.tau_s);
    EXPECT_NEAR(stress, expected, 1e-6 * elastic) << "t = " << t;
  }
}

TEST(ForeignMachine, SineFitRecoversSineCosineOffsetAndDrift) {
  const double f = 3.7, omega = 2 * std::numbers::pi * f;
  std::vector<double> t, y;
  for (int k = 0; k < 640; ++k) {
    t.push_back(1.234 + k / (64.0 * f));
    y.push_back(2.5 * std::sin(omega * t.back()) - 1.2 * std::cos(omega * t.back()) + 3.0 + 0.7 * t.back());
  }
  const SineFit fit = fit_sine(t, y, f);
  EXPECT_NEAR(fit.sine, 2.5, 1e-9);
  EXPECT_NEAR(fit.cosine, -1.2, 1e-9);
  EXPECT_NEAR(fit.offset, 3.0, 1e-9);
  EXPECT_NEAR(fit.drift, 0.7, 1e-9);
  EXPECT_NEAR(std::abs(fit.phasor()), std::hypot(2.5, 1.2), 1e-9);
}

TEST(ForeignMachine, AcceleratedAmplitudeFollowsThePeakToPeakConvention) {
  EXPECT_NEAR(displacement_amplitude_mm(0.25, 1.0), 3.1663, 1e-4);  // 0.125/(2 pi)^2 m
  EXPECT_NEAR(displacement_amplitude_mm(0.25, 20.0), 3.1663 / 400.0, 1e-6);
}

TEST(ForeignMachine, PlatenLiftsOffWhenTheViscoelasticForceReachesZero) {
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("soft_plateau_50", 2);
  const QuasiStaticProtocol fast = plan.quasi_static.back();  // 600 mm/min
  const QuasiStaticRecord rec = run_quasi_static(foam, {}, plan.specimen, fast);
  ASSERT_TRUE(rec.lifted_off);
  double peak = 0.0;
  for (double f : rec.force_N) peak = std::max(peak, f);
  EXPECT_GT(rec.displacement_mm.back(), 0.1);   // the record ends before the crosshead is back
  EXPECT_LT(rec.displacement_mm.back(), 60.0);
  for (std::size_t k = 1; k < rec.force_N.size(); ++k) EXPECT_GT(rec.force_N[k], 0.0) << "sample " << k;
  EXPECT_LT(rec.force_N.back(), 0.02 * peak);   // the force was about to reach zero
  // One more sample of unloading would give a force <= 0: rerun the history past the end.
  FoamSpecimen specimen(foam, {});
  double u_prev = 0.0, t_prev = 0.0, last_stress = 1.0;
  for (std::size_t k = 1; k < rec.time_s.size(); ++k) {
    const int sub = 10;
    for (int s = 1; s <= sub; ++s)
      last_stress = specimen.step((u_prev + (rec.displacement_mm[k] - u_prev) * s / sub) / 80.0, (rec.time_s[k] - t_prev) / sub);
    u_prev = rec.displacement_mm[k], t_prev = rec.time_s[k];
  }
  EXPECT_NEAR(plan.specimen.force_N(last_stress), rec.force_N.back(), 1e-9 * peak);
  const double sample_mm = 0.2, sample_s = sample_mm / (fast.rate_mm_min / 60.0);
  EXPECT_LE(specimen.step((u_prev - sample_mm) / 80.0, sample_s), 0.0);
  // Without viscosity the platen stays in contact back to zero displacement.
  BaseFoam elastic = foam;
  elastic.prony.clear();
  const QuasiStaticRecord back = run_quasi_static(elastic, {}, plan.specimen, fast);
  EXPECT_FALSE(back.lifted_off);
  EXPECT_NEAR(back.displacement_mm.back(), 0.0, 1e-12);
  EXPECT_EQ(back.time_s.size(), 2 * 300 + 100 + 1);  // 0.2 mm a sample, 2 s hold at 50 Hz
}

TEST(ForeignMachine, FractionalBankGivesTheSpringPotModulus) {
  // The bank is linear and additive: E*(with) - E*(without) = c (i w)^q.
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("stiff_65", 4);
  const double c = 2.0, q = 0.45;
  EffectSpec bank{"stiffness_damping", "fractional", {{"coefficient_kPa_s_pow_q", c}, {"order_q", q}}};
  const DynamicProtocol& p = plan.dynamic.front();
  const DynamicRecord without = run_dynamic(foam, {}, plan.specimen, p, plan.noise, nullptr);
  const DynamicRecord with = run_dynamic(foam, {bank}, plan.specimen, p, plan.noise, nullptr);
  for (std::size_t i = 0; i < p.frequencies_Hz.size(); ++i) {
    auto phasor = [&](const DynamicRecord& r) { return std::polar(r.dynamic_modulus_kPa[i], r.phase_deg[i] * std::numbers::pi / 180); };
    const std::complex<double> expected = c * std::pow(std::complex<double>(0, 2 * std::numbers::pi * p.frequencies_Hz[i]), q);
    EXPECT_LT(std::abs(phasor(with) - phasor(without) - expected), 0.02 * std::abs(expected)) << p.frequencies_Hz[i] << " Hz";
  }
}

TEST(ForeignMachine, SweepSubstepsShrinkTheDashpotLagOfTheSecantRate) {
  // A linear dashpot (Darcy air flow, permeability exponent -1: s = C e') adds C i w to E* in the continuous limit.
  // Its secant rate over a sample interval dt, sampled at the interval's end, lags by w dt / 2 = pi / 64 (4.9 %) at
  // one step a sample; 8 steps a sample leave an eighth of that (docs/physics.md 9.39).
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("stiff_65", 4);
  const double c = 0.05;
  EffectSpec dashpot{"pneumatic", "darcy", {{"resistance_kPa_s", c}, {"permeability_exponent", -1.0}}};
  DynamicProtocol p = plan.dynamic.front();
  const DynamicRecord without = run_dynamic(foam, {}, plan.specimen, p, plan.noise, nullptr);
  double worst[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    p.integration_substeps = k == 0 ? 1 : 8;
    const DynamicRecord with = run_dynamic(foam, {dashpot}, plan.specimen, p, plan.noise, nullptr);
    for (std::size_t i = 0; i < p.frequencies_Hz.size(); ++i) {
      auto phasor = [&](const DynamicRecord& r) {
        return std::polar(r.dynamic_modulus_kPa[i], r.phase_deg[i] * std::numbers::pi / 180);
      };
      const std::complex<double> expected(0.0, c * 2 * std::numbers::pi * p.frequencies_Hz[i]);
      worst[k] = std::max(worst[k], std::abs(phasor(with) - phasor(without) - expected) / std::abs(expected));
    }
  }
  std::cout << "relative error of the dashpot's E*: " << worst[0] << " (1 step a sample), " << worst[1] << " (8)\n";
  EXPECT_NEAR(worst[0], std::numbers::pi / 64, 0.01);
  EXPECT_NEAR(worst[1], std::numbers::pi / 512, 0.003);
}

TEST(ForeignCampaign, EveryFormIsScaledTo10To50TimesTheNoise) {
  const TestPlan plan = standard_plan();
  std::uint64_t seed = 11;
  for (const auto& form : effect_forms()) {
    const CampaignTruth truth = draw_truth("t", {{form.family}, {form.form}}, seed++, plan);
    const double ratio = largest(truth.effect_over_noise.at(form.family));
    EXPECT_GE(ratio, 10.0) << form.family << "/" << form.form;
    EXPECT_LE(ratio, 50.0) << form.family << "/" << form.form;
  }
}

TEST(ForeignBaseRefit, RecoversTheBaseFromAPerturbedStartWhenTheDataHaveNoEffect) {
  // Records of a base alone, the refit started from that base with every mu_i 15 % up, the Prony weights a_j 25 %
  // down and the times 0.1 decade later: the refit must reach the records within 2 % of the noise on every test
  // (the Levenberg-Marquardt of the generator has nothing else to find).
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("stiff_65", 4);
  BaseFoam start = foam;
  for (auto& t : start.hyperfoam) t.mu_kPa *= 1.15;
  const double sum_a = foam.prony_sum() / (1.0 - foam.prony_sum()) * 0.75;
  for (auto& p : start.prony) p.g = p.g / (1.0 - foam.prony_sum()) * 0.75 / (1.0 + sum_a), p.tau_s *= 1.26;
  const PlanRecords data = simulate_noise_free(foam, {}, plan);
  const double chi2_start = normalised_differences(simulate_noise_free(start, {}, plan), data, plan).squaredNorm();
  const BaseRefit refit = refit_base(foam, {}, plan, &start);
  EXPECT_GT(largest(ratios_between(simulate_noise_free(start, {}, plan), data, plan)), 5.0) << "the start is not off";
  EXPECT_LT(largest(refit.ratio_after), 0.02);
  EXPECT_LT(refit.chi2_after, 1e-4 * chi2_start);
  EXPECT_EQ(refit.chi2_before, 0.0);
}

/// A Jenkins slider of random shape on `foam`, sized to 20x noise in the plan's most sensitive test.
EffectSpec jenkins_sized_20x(const BaseFoam& foam, const TestPlan& plan, Random& random) {
  return scale_effect(draw_effect_shape(find_form("friction", "jenkins"), foam, random), foam, plan, 20.0);
}

TEST(ForeignBaseRefit, RateIndependentFrictionIsNotAbsorbedAndTheRefitNeverEndsAboveItsStart) {
  // A Jenkins slider gives the same hysteresis at 12 and 600 mm/min, which no Prony base can: most of it stays
  // (campaign c042 of seed 2025: 14.9x noise against the true base, 10.4x after the refit). Any effect: the refit
  // ends at or below the true base's chi2.
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("soft_plateau_50", 7);
  Random random(3);
  const EffectSpec jenkins = jenkins_sized_20x(foam, plan, random);
  const BaseRefit refit = refit_base(foam, {jenkins}, plan);
  EXPECT_LE(refit.chi2_after, refit.chi2_before);
  EXPECT_GT(largest(refit.ratio_after), 0.3 * largest(refit.ratio_before));
  const EffectSpec damage =
      scale_effect(draw_effect_shape(find_form("mullins", "exponential_damage"), foam, random), foam, plan, 20.0);
  const BaseRefit absorbed = refit_base(foam, {damage}, plan);
  EXPECT_LE(absorbed.chi2_after, absorbed.chi2_before);
  std::cout << "jenkins " << largest(refit.ratio_before) << " -> " << largest(refit.ratio_after) << "x noise ("
            << refit.iterations << " iterations), exponential damage " << largest(absorbed.ratio_before) << " -> "
            << largest(absorbed.ratio_after) << "x\n";
}

TEST(ForeignBaseRefit, AKeptEffectStartedAtHalfItsMagnitudeIsRefittedToTheRecordsAndAnotherOneIsNot) {
  // Records of the base + a Jenkins slider. (1) The model base + the same slider at half its magnitude (kept, the
  // magnitude refitted from there): the refit must find the magnitude within 1 % and leave under 0.05x noise on
  // every test. (2) Kept is an Ogden-Roxburgh Mullins instead (the pair measure of a member against a wrong partner):
  // it must leave most of the slider, as the base alone does (0.7-1.1x what the refit without it leaves).
  const TestPlan plan = standard_plan();
  const BaseFoam foam = sample_foam("soft_plateau_50", 7);
  Random random(3);
  const EffectSpec jenkins = jenkins_sized_20x(foam, plan, random);
  const std::string magnitude = find_form("friction", "jenkins").magnitude;
  EffectSpec half = jenkins;
  half.parameters[magnitude] *= 0.5;
  const BaseRefit same = refit_base(foam, {jenkins}, plan, nullptr, base_refit_iterations, {half});
  ASSERT_EQ(same.kept.size(), 1u);
  EXPECT_NEAR(same.kept.front().parameters.at(magnitude), jenkins.parameters.at(magnitude),
              0.01 * jenkins.parameters.at(magnitude));
  EXPECT_LT(largest(same.ratio_after), 0.05);
  const EffectSpec mullins =
      scale_effect(draw_effect_shape(find_form("mullins", "ogden_roxburgh"), foam, random), foam, plan, 20.0);
  const double alone = largest(refit_base(foam, {jenkins}, plan).ratio_after);
  const double beside_mullins =
      largest(refit_base(foam, {jenkins}, plan, nullptr, base_refit_iterations, {mullins}).ratio_after);
  EXPECT_GT(beside_mullins, 0.7 * alone);
  EXPECT_LE(beside_mullins, 1.1 * alone);  // the Mullins it starts with, not in the data, is stepped down
  std::cout << "jenkins left by a base refit " << alone << "x noise, with a Mullins partner refitted " << beside_mullins
            << "x\n";
}

TEST(ForeignCampaign, ScaledBeyondTheBaseRefitAnAbsorbedMullinsFormIsLeftAt10To50TimesTheNoise) {
  // Ogden-Roxburgh softening sized against the true base (campaign c002 of seed 2025: 18.6x noise) is mostly taken up
  // by a refitted base (1.84x). Sized by what the refit leaves, the effect must grow beyond its size against the true
  // base, and a fresh refit from the true base must leave 10-50x noise of it (the target 14-36x within the factor 1.25
  // of the scaling and a refit started elsewhere).
  const TestPlan plan = standard_plan();
  const CampaignTruth truth =
      draw_truth("t", {{"mullins"}, {"ogden_roxburgh"}}, mix_seed(2025, 2), plan, BaseRefitUse::scale);
  ASSERT_EQ(truth.sized_by.at("mullins"), sized_by_base_refit);
  const double left = largest(truth.effect_after_base_refit.at("mullins"));
  EXPECT_GE(left, 10.0);
  EXPECT_LE(left, 50.0);
  EXPECT_GT(largest(truth.effect_over_noise.at("mullins")), 2.0 * left);
  EXPECT_NEAR(largest(truth.all_effects_after_base_refit), left, 1e-9 * left);
}

TEST(ForeignCampaign, APairRecordsEachMemberBeyondItsPartnerAndOnlyAPairDoes) {
  // --base-refit report on a pair (Jenkins friction + Ogden-Roxburgh Mullins): each member gets what a base refitted
  // with the other member leaves, on every test of the plan, finite; the rate-independent slider, which no Prony base
  // and no softening takes up (ForeignBaseRefit above), stays beyond 3x noise beside its Mullins partner. A single
  // records none. truth.json carries one record per member.
  const TestPlan plan = standard_plan();
  const CampaignTruth pair = draw_truth("p", {{"friction", "mullins"}, {"jenkins", "ogden_roxburgh"}},
                                        mix_seed(2026, 55), plan, BaseRefitUse::report);
  ASSERT_EQ(pair.member_beyond_partner.size(), 2u);
  const double together = largest(pair.all_effects_after_base_refit);
  for (const auto& [family, ratios] : pair.member_beyond_partner) {
    EXPECT_EQ(ratios.size(), pair.all_effects_after_base_refit.size()) << family;
    for (const auto& [test, r] : ratios) EXPECT_TRUE(std::isfinite(r) && r >= 0.0) << family << " " << test;
    std::cout << family << " beyond its partner " << largest(ratios) << "x noise (both beyond the base: " << together
              << "x)\n";
  }
  EXPECT_GT(largest(pair.member_beyond_partner.at("friction")), 3.0);
  const CampaignTruth single =
      draw_truth("s", {{"friction"}, {"jenkins"}}, mix_seed(2026, 56), plan, BaseRefitUse::report);
  EXPECT_TRUE(single.member_beyond_partner.empty());
  const auto dir = std::filesystem::temp_directory_path() / "cushion_foreign_pair_truth";
  write_campaign(pair, plan, dir);
  std::ifstream in(dir / "truth.json");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  int records = 0;
  for (auto at = text.find("beyond_partner_refit"); at != std::string::npos;
       at = text.find("beyond_partner_refit", at + 1))
    ++records;
  EXPECT_EQ(records, 2);
  std::filesystem::remove_all(dir);
}

TEST(ForeignCampaign, OnlyFormsWithoutARandomShapeParameterDrawTheSameShapeTwice) {
  // draw_truth stops redrawing a shape the base refit absorbs when the next draw is the same shape (docs/physics.md
  // 9.17): that must happen exactly for the forms whose only parameter is the magnitude, never for a form with a
  // random shape parameter, which would then lose its redraws.
  const BaseFoam foam = sample_foam("soft_plateau_50", 5);
  std::set<std::string> repeating;
  for (const auto& form : effect_forms()) {
    Random random(23);
    const EffectSpec first = draw_effect_shape(form, foam, random);
    if (draw_effect_shape(form, foam, random).parameters == first.parameters)
      repeating.insert(form.family + "/" + form.form);
  }
  const std::set<std::string> without_shape{"stiffness_damping/stiffness_proportional",
                                            "stiffness_damping/secant_proportional", "strain_dependent_prony/power_law",
                                            "strain_dependent_prony/exponential"};
  EXPECT_EQ(repeating, without_shape);
}

TEST(ForeignCampaign, MixIsBalancedAndDeterministic) {
  const auto kinds = campaign_mix(60, 10, 10, 5);
  const auto again = campaign_mix(60, 10, 10, 5);
  std::map<std::string, int> singles, forms;
  int pairs = 0, controls = 0;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    EXPECT_EQ(kinds[i].forms, again[i].forms);
    if (kinds[i].families.empty()) ++controls;
    else if (kinds[i].families.size() == 2) {
      ++pairs;
      EXPECT_NE(kinds[i].families[0], kinds[i].families[1]);
    } else ++singles[kinds[i].families[0]], ++forms[kinds[i].forms[0]];
  }
  EXPECT_EQ(pairs, 10);
  EXPECT_EQ(controls, 10);
  for (const auto& family : effect_families()) EXPECT_EQ(singles[family], 8) << family;
  for (const auto& [form, n] : forms) EXPECT_GE(n, 2) << form;
}

TEST(ForeignCampaign, ExtraTestsLeaveTheTruthAndThePlanRecordsUnchanged) {
  // The same campaign written without and with an extra rate and preload (unrecorded protocol, so the extra sweep
  // must follow the campaign's drawn protocol too): identical truth.json and plan CSV files, byte for byte; the
  // extra files exist and the manifest lists them.
  const auto dir = std::filesystem::temp_directory_path() / "cushion_foreign_extra";
  std::filesystem::remove_all(dir);
  TestPlan plan = standard_plan();
  plan.unrecorded_protocol = true;
  write_campaign_set(dir / "plain", 1, 0, 0, 3, plan, std::cout);
  plan.extra_quasi_static.push_back(extra_rate(3000.0));
  plan.extra_dynamic.push_back(extra_preload(plan, 0.65));
  write_campaign_set(dir / "extra", 1, 0, 0, 3, plan, std::cout);
  auto text = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* f : {"truth.json", "qs_12.csv", "qs_120.csv", "qs_600.csv", "dyn_25.csv", "dyn_50.csv"})
    EXPECT_EQ(text(dir / "plain" / "c000" / f), text(dir / "extra" / "c000" / f)) << f;
  EXPECT_TRUE(std::filesystem::exists(dir / "extra" / "c000" / "qs_3000_extra.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "extra" / "c000" / "dyn_65_extra.csv"));
  const std::string manifest = text(dir / "extra" / "c000" / "campaign.json");
  EXPECT_NE(manifest.find("qs_3000_extra.csv"), std::string::npos);
  EXPECT_NE(manifest.find("dyn_65_extra.csv"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(ForeignCampaign, OneCampaignWrittenAloneIsTheSameAsInTheWholeSet) {
  // --only: campaigns c002 and c004 of a 6-campaign set written alone are byte for byte those of the whole set, and
  // nothing else is written; an unknown name is refused before anything is written.
  const auto dir = std::filesystem::temp_directory_path() / "cushion_foreign_only";
  std::filesystem::remove_all(dir);
  const TestPlan plan = standard_plan();
  write_campaign_set(dir / "all", 6, 1, 1, 11, plan, std::cout);
  write_campaign_set(dir / "only", 6, 1, 1, 11, plan, std::cout, BaseRefitUse::none, {"c002", "c004"});
  auto text = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* c : {"c002", "c004"})
    for (const char* f : {"campaign.json", "truth.json", "qs_12.csv", "qs_600.csv", "dyn_50.csv"})
      EXPECT_EQ(text(dir / "all" / c / f), text(dir / "only" / c / f)) << c << "/" << f;
  EXPECT_FALSE(std::filesystem::exists(dir / "only" / "c000"));
  EXPECT_THROW(write_campaign_set(dir / "bad", 6, 1, 1, 11, plan, std::cout, BaseRefitUse::none, {"c006"}),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace foreign_bench
