// diagnose.hpp on FOREIGN campaigns (foreign_campaign.hpp): each hides ONE effect written outside cushion's
// library, in another functional form and with other parameter values (power-law air dashpot, Bouc-Wen
// hysteresis, exponential damage on the maximum strain, exponentially preload-dependent Prony moduli,
// fractional f^0.5 damping), plus a base-mismatch control (4-term truth hyperfoam) and a plain control.
// 3 rates (30/120/480 mm/min), 2 preloads (25/40 %), 8 frequencies, 0.5 % + 0.002 N noise; the model side
// is the truth base (hyperfoam + Prony), as in test_diagnose.cpp. Criteria:
//  - effect cases: the baseline fails beyond noise; the winner's LEADING member and the best single are of the
//    right family; the winner lowers the worst test's error/noise by at least 2x; when it does not reach the
//    noise level the verdict says which tests remain beyond noise (our library need not represent the foreign
//    form exactly, it must name the family and be honest about the rest);
//  - base mismatch, and fractional damping (linear viscoelasticity, which the base Prony series represents):
//    no effect is named; the verdict points at the base calibration; the base refit alone (hyperfoam and
//    Prony moduli) reaches the noise level (error/noise <= 1.5);
//  - control: "No effect is missing";
//  - the realistic workflow: the baseline is `cushion fit`'s material fitted on the SAME campaign (with the options of
//    diagnose's raw path, diagnose_base_fit_options()), so the fit
//    has absorbed part of the hidden effect into the base moduli; with joint_base (effect and base moduli
//    fitted together) the right family leads the winner (Bouc-Wen -> friction, exponential preload Prony ->
//    strain_dependent_prony; without joint_base both gave "cannot tell from a base error"), chi2 falls by
//    2x, and the extended material carries the refitted base. Not met, so disabled with the measured outcome: a
//    power-law air dashpot (named friction) (README).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include "foreign_campaign.hpp"
#include "calibration/diagnose.hpp"
#include "calibration/fit_model.hpp"
#include "calibration/fit_pipeline.hpp"

namespace cc = cushion::calibration;
namespace cf = cushion::foreign;
namespace fs = std::filesystem;

namespace {

double worst_ratio(const cc::CompareResult& r) {
  double w = 0.0;
  for (const auto& t : r.tests) w = std::max(w, t.noise_ratio());
  return w;
}

struct ForeignRun {
  cc::Diagnosis d;
  cf::ForeignCampaign campaign;
};

ForeignRun run(cf::ForeignCase c, int max_iterations = 12, std::vector<std::string> candidates = {},
               bool refit_exponents = false) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_foreign_" + cf::to_string(c));
  ForeignRun r;
  r.campaign = cf::make_foreign_campaign(c, dir);
  cc::DiagnoseOptions o;
  o.pairs_from = 2;
  o.max_iterations = max_iterations;
  o.candidates = std::move(candidates);
  o.base_exponents = refit_exponents;
  std::ostringstream log;
  r.d = cc::diagnose(r.campaign.truth_base, cc::read_campaign(r.campaign.manifest), o, log);
  fs::remove_all(dir);
  // One line per case for the record (not a timed test).
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "foreign " << cf::to_string(c) << ": baseline worst error/noise " << worst_ratio(r.d.baseline);
  if (r.d.winner)
    std::cout << ", winner " << r.d.candidates[*r.d.winner].name() << " -> "
              << worst_ratio(r.d.candidates[*r.d.winner].compare);
  if (r.d.base_refit) std::cout << ", base refit -> " << worst_ratio(r.d.base_refit->compare);
  std::cout << ", " << s << " s\n  " << r.d.verdict << "\n";
  return r;
}

const cc::CandidateFit* best_single(const cc::Diagnosis& d) {
  for (const auto& c : d.candidates)
    if (c.kinds.size() == 1) return &c;
  return nullptr;
}

bool in(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

/// The winner must lower the worst test's error/noise by `fall`.
void expect_family_first(cf::ForeignCase c, const std::vector<std::string>& family, double fall = 2.0,
                         bool refit_exponents = false) {
  const ForeignRun r = run(c, 12, {}, refit_exponents);
  const cc::Diagnosis& d = r.d;
  EXPECT_FALSE(d.at_noise_level);
  ASSERT_TRUE(d.winner.has_value()) << d.verdict;
  const cc::CandidateFit& w = d.candidates[*d.winner];
  EXPECT_TRUE(in(family, w.kinds.front())) << "winner " << w.name();
  const cc::CandidateFit* single = best_single(d);
  ASSERT_NE(single, nullptr);
  EXPECT_TRUE(in(family, single->kinds.front())) << "best single " << single->name();
  EXPECT_LT(worst_ratio(w.compare), worst_ratio(d.baseline) / fall);
  if (!d.winner_at_noise_level) {
    EXPECT_NE(d.verdict.find("still beyond noise"), std::string::npos) << d.verdict;
  }
  EXPECT_TRUE(d.fragment.contains("effects"));
}

}  // namespace

// Not met from 2026-11-24 (the dynamic noise estimated per frequency) to session 26: friction was named (worst test
// 67.6 -> 10.4x noise). At the small strain amplitudes of the sweeps (1e-4 at 20 Hz) a power-law dashpot's equivalent
// linear damping grows as v^-0.4, which friction follows and a linear dashpot cannot. Met since the air flow's dashpot
// start fits its rate exponent (docs/physics.md 9.9; measured 2026-11-28: air flow named, worst test 67.3 -> 0.97x).
TEST(DiagnoseForeign, PowerLawAirDashpotIsNamedAsRateDependentDamping) {
  // q = 0.6 rate exponent, (1/(1-e))^1.5: between a linear dashpot and friction; both of our viscous
  // (rate-dependent, linear-dashpot) effects are the right family.
  expect_family_first(cf::ForeignCase::power_law_dashpot, {"pneumatic", "stiffness_damping"});
}

TEST(DiagnoseForeign, BoucWenHysteresisIsNamedAsFriction) {
  expect_family_first(cf::ForeignCase::bouc_wen, {"friction"});
}

// With --refit-exponents the base refit runs twice (exponents fixed, then free) and the candidates start from its
// first run. Started from the refit with its exponents moved (the session-22 code), every candidate stayed at 8.6-12.5x
// noise and strain-dependent Prony + friction was named (best single strain-dependent Prony, worst test 161 -> 9.4x);
// now friction is named and the worst test falls 161 -> 2.5x (measured 2026-11-28): `fall` 20 fails the old code.
TEST(DiagnoseForeign, BoucWenHysteresisIsNamedAsFrictionWithTheExponentsRefitted) {
  expect_family_first(cf::ForeignCase::bouc_wen, {"friction"}, 20.0, true);
}

TEST(DiagnoseForeign, ExponentialDamageIsNamedAsMullins) {
  expect_family_first(cf::ForeignCase::exponential_damage, {"mullins"});
}

TEST(DiagnoseForeign, ExponentialPreloadPronyIsNamedAsStrainDependentProny) {
  expect_family_first(cf::ForeignCase::exponential_prony, {"strain_dependent_prony"});
}

/// No effect named; the verdict points at the base; the base refit alone reaches the noise level.
void expect_base_explains(cf::ForeignCase c) {
  const ForeignRun r = run(c);
  const cc::Diagnosis& d = r.d;
  EXPECT_FALSE(d.at_noise_level);
  EXPECT_FALSE(d.winner.has_value()) << d.candidates.front().name();
  EXPECT_TRUE(d.fragment.is_null());
  EXPECT_NE(d.verdict.find("base calibration"), std::string::npos) << d.verdict;
  ASSERT_TRUE(d.base_refit.has_value());
  EXPECT_LE(worst_ratio(d.base_refit->compare), 1.5);
}

TEST(DiagnoseForeign, FractionalDampingIsExplainedByTheBasePronySeries) {
  // c D^0.5 (loss and storage growing like f^0.5) is LINEAR viscoelasticity: a Prony series spanning the
  // decades of the tests represents it, so the honest answer is "recalibrate the base", not a new effect
  // (before the base-refit reference, diagnose named friction or pneumatic damping here).
  expect_base_explains(cf::ForeignCase::fractional_damping);
}

TEST(DiagnoseForeign, BaseMismatchInventsNoEffect) {
  expect_base_explains(cf::ForeignCase::base_off);  // a 4th hyperfoam term the truth has and the model lacks
}

TEST(DiagnoseForeign, ControlSaysNoEffectIsMissing) {
  const ForeignRun r = run(cf::ForeignCase::control);
  EXPECT_TRUE(r.d.at_noise_level);
  EXPECT_FALSE(r.d.winner.has_value());
  EXPECT_NE(r.d.verdict.find("No effect is missing"), std::string::npos) << r.d.verdict;
}

TEST(DiagnoseForeign, CandidateThatDoesNotConvergeIsReportedAndTheRestStillRuns) {
  // One Ceres iteration: the refits stop before convergence. Each says so in a warning naming the candidate;
  // the baseline, the ranking and a verdict are still reported.
  const ForeignRun r = run(cf::ForeignCase::bouc_wen, 1, {"friction", "stiffness_damping"});
  const cc::Diagnosis& d = r.d;
  bool warned = false;
  for (const auto& w : d.warnings)
    if (w.find("candidate ") != std::string::npos && w.find("did not converge within 1 iterations") != std::string::npos)
      warned = true;
  EXPECT_TRUE(warned) << ::testing::PrintToString(d.warnings);
  EXPECT_EQ(d.baseline.tests.size(), 5u);
  ASSERT_GE(d.candidates.size(), 2u);
  for (const auto& c : d.candidates) EXPECT_EQ(c.compare.tests.size(), 5u) << c.name();
  EXPECT_FALSE(d.verdict.empty());
}

namespace {

/// The fitted-baseline workflow on a foreign campaign: fit_pipeline (as `cushion fit`), then diagnose with
/// joint_base.
void expect_family_from_fitted_baseline(cf::ForeignCase c, const std::vector<std::string>& family) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_foreign_fitted_" + cf::to_string(c));
  const cf::ForeignCampaign fc = cf::make_foreign_campaign(c, dir);
  const cc::Campaign campaign = cc::read_campaign(fc.manifest);
  std::ostringstream log;
  const cc::FitResult fit = cc::fit_pipeline(campaign, cc::diagnose_base_fit_options(), log);
  const cushion::material::MaterialSpec fitted =
      cc::to_spec(fit.default_material, "foam", "fitted on the foreign campaign", campaign.specimen.density);
  cc::DiagnoseOptions o;
  o.pairs_from = 2;
  o.joint_base = true;
  const cc::Diagnosis d = cc::diagnose(fitted, campaign, o, log);
  fs::remove_all(dir);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "foreign " << cf::to_string(c) << " (fitted baseline, joint): baseline worst error/noise "
            << worst_ratio(d.baseline);
  if (d.winner)
    std::cout << ", winner " << d.candidates[*d.winner].name() << " -> " << worst_ratio(d.candidates[*d.winner].compare);
  if (d.base_refit) std::cout << ", base refit -> " << worst_ratio(d.base_refit->compare);
  std::cout << ", " << s << " s\n  " << d.verdict << "\n";
  EXPECT_FALSE(d.at_noise_level);
  ASSERT_TRUE(d.winner.has_value()) << d.verdict;
  const cc::CandidateFit& w = d.candidates[*d.winner];
  EXPECT_TRUE(in(family, w.kinds.front())) << "winner " << w.name();
  EXPECT_TRUE(w.base_refitted);
  // The fitted baseline is off everywhere (it absorbed the effect), so the worst single test need not halve;
  // the penalised misfit over all tests must.
  EXPECT_LT(w.chi2, d.baseline_chi2 / 2.0);
  EXPECT_NE(d.verdict.find("material_extended.json"), std::string::npos) << d.verdict;
  bool base_changed = false;
  for (std::size_t t = 0; t < fitted.hyperfoam.size(); ++t)
    base_changed = base_changed || d.extended.hyperfoam[t].mu != fitted.hyperfoam[t].mu;
  EXPECT_TRUE(base_changed);
}

}  // namespace

// Met again since the base is fitted as diagnose fits it from raw data (diagnose_base_fit_options: noise-weighted on
// every test, free Prony times; measured 2026-11-24): friction named, chi2/N 14.5 -> 6.53, worst test 12.0 -> 6.03x
// noise (the base refit alone 9.48x); the foreign Bouc-Wen form is not our elasto-plastic branch, so the verdict lists
// the tests still beyond noise. Before (the fit's default options) no effect was named. Also the case for continuing
// only the BEST polished single with Mullins' beta free (DiagnoseOptions::fit_polished_only): friction polished 3292,
// Mullins polished 3138 and, continued with beta, 3353; with every polished Mullins continued (2026-12-07) Mullins
// was named here and this test failed (docs/physics.md 9.42).
TEST(DiagnoseForeignFittedBaseline, BoucWenIsNamedAsFriction) {
  expect_family_from_fitted_baseline(cf::ForeignCase::bouc_wen, {"friction"});
}

TEST(DiagnoseForeignFittedBaseline, ExponentialPreloadPronyIsNamedAsStrainDependentProny) {
  expect_family_from_fitted_baseline(cf::ForeignCase::exponential_prony, {"strain_dependent_prony"});
}
