// diagnose.hpp on campaigns with a hidden effect (cases/hidden_effects, made by `cushion lab` from the
// base material plus ONE effect, 0.5% + 0.002 N noise) and on a control with none. The model side is the
// base material (the base calibration assumed right). For each effect: the baseline fails beyond noise,
// diagnose ranks the hidden effect first (alone or as the leading member of the winning candidate), and
// with the fitted effect every test is within 1.5x its noise, and the winner predicts each test left out of
// its fit better than the base refit (held-out check). Control: "no effect is missing".
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include "calibration/diagnose.hpp"
#include "material/io/material_file.hpp"

namespace cc = cushion::calibration;
namespace fs = std::filesystem;

namespace {

fs::path hidden() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects"; }

cc::Diagnosis run(const std::string& effect, const cushion::material::MaterialSpec& base) {
  const cc::Campaign campaign = cc::read_campaign(hidden() / ("campaign_" + effect) / "campaign.json");
  cc::DiagnoseOptions o;
  o.pairs_from = 2;
  o.held_out = true;  // the out-of-sample check is tested here (off by default)
  std::ostringstream log;
  return cc::diagnose(base, campaign, o, log);
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

class HiddenEffect : public ::testing::TestWithParam<std::string> {};

TEST_P(HiddenEffect, RankedFirstAndErrorFallsToNoise) {
  const std::string effect = GetParam();
  const auto base = cushion::material::read_material_file(hidden() / "base_material.json");
  const cc::Diagnosis d = run(effect, base.spec);
  EXPECT_FALSE(d.at_noise_level);
  if (effect == "stiffness_damping") {
    // The weakest hidden effect (beta_s = 1e-4 s, the paper's value): the baseline is at chi2/N 1.15, and the base
    // refit alone brings every test within 1.5x its noise (chi2/N 0.669). An effect is then not named (diagnose.cpp
    // rank_candidates; the rule that keeps a base-form mismatch, DiagnoseForeign.BaseMismatchInventsNoEffect, from
    // being called friction), although stiffness_damping leads the candidates (dBIC 117.4 against the base refit's
    // 87.3, measured 2026-11-24). Checked: it is ranked first and the verdict says why nothing is named.
    ASSERT_FALSE(d.candidates.empty());
    EXPECT_EQ(d.candidates.front().kinds.front(), effect);
    EXPECT_FALSE(d.winner.has_value());
    EXPECT_EQ(d.verdict.rfind("No effect is missing: refitting only the base", 0), 0u) << d.verdict;
    return;
  }
  ASSERT_TRUE(d.winner.has_value()) << d.verdict;
  const cc::CandidateFit& w = d.candidates[*d.winner];
  EXPECT_TRUE(contains(w.kinds, effect)) << "winner " << w.name();
  // The best SINGLE candidate is the hidden effect.
  for (const auto& c : d.candidates)
    if (c.kinds.size() == 1) {
      EXPECT_EQ(c.kinds.front(), effect);
      break;
    }
  std::cout << effect << ": winner " << w.name() << ", dBIC " << w.delta_bic << ", error/noise:";  // for the record
  for (const auto& t : w.compare.tests) std::cout << " " << t.name << " " << t.noise_ratio();
  std::cout << " (" << d.seconds << " s)\n";
  for (const auto& t : w.compare.tests) EXPECT_LE(t.noise_ratio(), 1.5) << t.name;
  EXPECT_TRUE(d.winner_at_noise_level);
  EXPECT_TRUE(d.fragment.contains("effects"));
  // Out of sample: the winner, refitted without each test in turn, predicts that test better than the base
  // refit does (the check that named it is the last one made).
  ASSERT_FALSE(d.held_out.empty());
  const cc::HeldOutCheck& h = d.held_out.back();
  EXPECT_EQ(h.candidate, w.name());
  EXPECT_TRUE(h.confirmed) << h.failure;
  EXPECT_EQ(h.tests.size(), d.baseline.tests.size());
  for (std::size_t i = 0; i < h.tests.size(); ++i) EXPECT_TRUE(std::isfinite(h.chi2_candidate[i])) << h.tests[i];
  EXPECT_LT(h.total_candidate, h.total_reference - 10.0);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, HiddenEffect,
                         ::testing::Values("pneumatic", "friction", "mullins", "strain_dependent_prony",
                                           "stiffness_damping"));

TEST(Diagnose, ControlSaysNoEffectIsMissing) {
  const auto base = cushion::material::read_material_file(hidden() / "base_material.json");
  const cc::Diagnosis d = run("control", base.spec);
  EXPECT_TRUE(d.at_noise_level);
  EXPECT_FALSE(d.winner.has_value());
  EXPECT_NE(d.verdict.find("No effect is missing"), std::string::npos) << d.verdict;
  EXPECT_TRUE(d.fragment.is_null());
}
