// The forward models of compare and diagnose follow the whole protocol a campaign describes (issue 15):
//  - compare and diagnose run ONE schedule: the same material and campaign give the same error/noise;
//  - on campaigns made by an independent generator (tests/foreign, run as its own program) with the exact
//    truth material, the dynamic error/noise falls once the model runs the campaign's protocol (20 cycles per
//    frequency, the last 10 fitted, the 5 s dwell before the sweep) instead of the former cheap schedule
//    (6 cycles, 3 fitted, 48 steps a cycle, no dwell), and every test is at the noise level (error/noise <= 1.5)
//    once the dynamic noise is estimated per frequency (a constant-acceleration sweep: the force amplitude falls as
//    1/f^2, the load cell's floor dominates at 20 Hz and is 10-100 x smaller at 1 Hz).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "calibration/compare.hpp"
#include "calibration/diagnose.hpp"
#include "foreign_program.hpp"
#include "material/io/material_file.hpp"

namespace cc = cushion::calibration;
namespace fs = std::filesystem;

namespace {

fs::path hidden() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects"; }

/// Three foreign control campaigns (no effect), generated once per process.
fs::path foreign_controls() {
  static const fs::path dir = cushion::foreign_program::generate("forward", 3, 11, 0, 3);
  return dir;
}

using cushion::foreign_program::exact_material;

}  // namespace

// The same material and campaign through compare and through diagnose's baseline: every test's error/noise and
// every region's RMS error identical (one schedule, one function).
TEST(ForwardModel, CompareAndDiagnoseGiveTheSameFigures) {
  const auto base = cushion::material::read_material_file(hidden() / "base_material.json");
  const cc::Campaign campaign = cc::read_campaign(hidden() / "campaign_friction" / "campaign.json");
  const cc::CompareResult compared = cc::compare_campaign(*base.model, campaign, cc::CompareOptions{});
  cc::DiagnoseOptions o;
  o.candidates = {"friction"};
  o.max_iterations = 1;
  std::ostringstream log;
  const cc::Diagnosis d = cc::diagnose(base.spec, campaign, o, log);
  ASSERT_EQ(d.baseline.tests.size(), compared.tests.size());
  for (std::size_t i = 0; i < compared.tests.size(); ++i) {
    SCOPED_TRACE(compared.tests[i].name);
    EXPECT_NEAR(d.baseline.tests[i].noise_ratio(), compared.tests[i].noise_ratio(), 1e-9);
    for (std::size_t r = 0; r < compared.tests[i].regions.size(); ++r)
      EXPECT_NEAR(d.baseline.tests[i].regions[r].rms, compared.tests[i].regions[r].rms, 1e-9);
  }
}

TEST(ForwardModel, ExactMaterialOfForeignControlsFollowsTheirProtocol) {
  for (const char* name : {"c000", "c001", "c002"}) {
    const fs::path dir = foreign_controls() / name;
    const auto exact = exact_material(dir);
    const cc::Campaign campaign = cc::read_campaign(dir / "campaign.json");
    ASSERT_EQ(campaign.dynamic.size(), 2u);
    EXPECT_EQ(campaign.dynamic[0].cycles, 20);
    EXPECT_DOUBLE_EQ(campaign.dynamic[0].dwell_s, 5.0);
    const cc::CompareResult after = cc::compare_campaign(*exact.model, campaign);
    cc::Campaign cheap = campaign;  // the former schedule of diagnose
    for (auto& t : cheap.dynamic) t.cycles = 6, t.fit_cycles = 3, t.dwell_s = 0.0;
    cc::CompareOptions cheap_options;
    cheap_options.dynamic_steps_per_cycle = 48;
    const cc::CompareResult before = cc::compare_campaign(*exact.model, cheap, cheap_options);
    double sum_before = 0.0, sum_after = 0.0;
    for (std::size_t i = 0; i < after.tests.size(); ++i) {
      const cc::TestCompare &a = after.tests[i], &b = before.tests[i];
      ASSERT_TRUE(a.failure.empty()) << a.failure;
      std::cout << name << " " << a.name << ": error/noise " << b.noise_ratio() << " (former schedule) -> " << a.noise_ratio()
                << "\n";
      if (a.kind != "dynamic") continue;
      sum_before += b.noise_ratio(), sum_after += a.noise_ratio();
      EXPECT_LT(a.noise_ratio(), b.noise_ratio()) << name << " " << a.name;
    }
    EXPECT_LT(sum_after, 0.8 * sum_before) << name;
    // The exact material leaves the measurement noise only: every test within 1.5 x its noise. (A band of a sweep
    // holds 3-4 frequencies, and its noise is estimated from one sweep: its ratio scatters more and is not asserted.)
    EXPECT_TRUE(after.at_noise_level(1.5)) << name;
  }
}

// The foreign generator's Mullins forms soften the long-term stress and let the softened stress drive the Prony
// memory (tests/foreign/foreign_machine.cpp). With the TRUE parameters of its Ogden-Roxburgh single-effect campaigns
// (seed 2025, the benchmark's), cushion's Mullins with relaxation_share 1 (the same order) leaves every test at the
// noise level (error/noise <= 1.5; measured 1.49 at most), while relaxation_share 0 (eta times the whole stress)
// leaves a sweep beyond 3x (measured 4.7-5.9): the order is what differs (docs/physics.md 5.2).
TEST(ForwardModel, ExactMullinsOfForeignCampaignsNeedsTheSoftenedStressToDriveTheMemory) {
  const fs::path dir = cushion::foreign_program::generate("mullins_order", 60, 2025, 10, 10);
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!fs::exists(entry.path() / "truth.json")) continue;
    std::ifstream in(entry.path() / "truth.json");
    const nlohmann::json truth = nlohmann::json::parse(in);
    const nlohmann::json& parameters = truth.at("parameters");
    if (parameters.size() != 1 || !parameters.contains("mullins") ||
        parameters.at("mullins").at("form") != "ogden_roxburgh")
      continue;
    exact_material(entry.path());  // writes exact_material.json: the base
    nlohmann::json m = nlohmann::json::parse(std::ifstream(entry.path() / "exact_material.json"));
    const nlohmann::json& p = parameters.at("mullins");
    const cc::Campaign campaign = cc::read_campaign(entry.path() / "campaign.json");
    double worst[2] = {0.0, 0.0};
    for (int share : {1, 0}) {
      m["effects"] = {{{"kind", "mullins"}, {"r", p.at("r")}, {"m_kPa", p.at("m_kPa")}, {"beta", p.at("beta")},
                       {"relaxation_share", share}}};
      std::ofstream(entry.path() / "exact_mullins.json") << m.dump(1);
      const auto exact = cushion::material::read_material_file(entry.path() / "exact_mullins.json");
      const cc::CompareResult r = cc::compare_campaign(*exact.model, campaign);
      for (const cc::TestCompare& t : r.tests) {
        ASSERT_TRUE(t.failure.empty()) << t.failure;
        worst[share] = std::max(worst[share], t.noise_ratio());
      }
    }
    std::cout << entry.path().filename().string() << ": worst error/noise " << worst[1] << " (relaxation_share 1), "
              << worst[0] << " (0)\n";
    EXPECT_LE(worst[1], 1.5) << entry.path();
    EXPECT_GT(worst[0], 3.0) << entry.path();
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

namespace {

/// RMS change of the model's |E*| and phase between two comparisons of one dynamic test, in noise units at each
/// frequency, |E*| and phase combined as TestCompare::noise_ratio (computed here from the local noises, not through
/// compare's regions).
double model_change(const cc::TestCompare& a, const cc::TestCompare& b) {
  double modulus = 0.0, phase = 0.0;
  const std::size_t n = a.x.size();
  for (std::size_t i = 0; i < n; ++i) {
    modulus += std::pow((a.model[i] - b.model[i]) / a.noise.modulus_local[i], 2);
    phase += std::pow((a.model_phase[i] - b.model_phase[i]) / a.noise.phase_local[i], 2);
  }
  return std::sqrt((modulus / n + phase / n) / 2.0);
}

/// The campaign and material of cases/hidden_effects for `effect` compared at 64 steps a cycle with the step check,
/// and at 512 without it (the reference the check is measured against).
struct StepChecked {
  cc::CompareResult checked, fine;
};

StepChecked step_checked(const std::string& effect) {
  const auto m = cushion::material::read_material_file(hidden() / ("truth_material_" + effect + ".json"));
  const cc::Campaign campaign = cc::read_campaign(hidden() / ("campaign_" + effect) / "campaign.json");
  cc::CompareOptions o;
  o.step_check = true;
  cc::CompareOptions fine;
  fine.dynamic_steps_per_cycle = 512;
  fine.dynamic_transient_steps_per_cycle = 256;
  return {cc::compare_campaign(*m.model, campaign, o), cc::compare_campaign(*m.model, campaign, fine)};
}

}  // namespace

// The step check (CompareOptions::step_check, docs/physics.md 9.39) on a Darcy air flow, whose dashpot rate is first
// order in the step: the change from 64 to 32 steps a cycle estimates the error of the 64-step sweep, which the change
// from 64 to 512 steps measures as 7/8 of it (first order: e(64) - e(512) = (1 - 1/8) e(64)). Measured estimate over
// that error 1.00 (1.18 and 1.82 noise units); asserted within 15 %. A sweep beyond one noise unit is warned
// about, naming the test and the finer step.
TEST(StepCheck, EstimatesTheSweepErrorOfAFirstOrderDashpot) {
  const StepChecked r = step_checked("pneumatic");
  int warned = 0;
  for (std::size_t i = 0; i < r.checked.tests.size(); ++i) {
    const cc::TestCompare& t = r.checked.tests[i];
    if (t.kind != "dynamic") {
      EXPECT_LT(t.step_error, 0.0) << t.name << ": only sweeps are checked";
      continue;
    }
    ASSERT_TRUE(t.failure.empty()) << t.failure;
    const double error_at_64 = model_change(t, r.fine.tests[i]) * 8.0 / 7.0;
    std::cout << t.name << ": step error estimate " << t.step_error << " noise units, error at 64 steps " << error_at_64
              << "\n";
    EXPECT_GT(error_at_64, 0.5) << t.name << ": the check needs a visible step error";
    EXPECT_NEAR(t.step_error / error_at_64, 1.0, 0.15) << t.name;
    EXPECT_EQ(t.steps_per_cycle, 64);
    for (const auto& w : r.checked.warnings)
      if (w.rfind(t.name + ": the time step moves", 0) == 0 && w.find("--steps-per-cycle 128") != std::string::npos)
        ++warned;
  }
  EXPECT_EQ(warned, 2);
}

// Without a dashpot (the control's hyperfoam and Prony series) the sweep is second order in the step: the change from
// 64 to 32 steps is about three times the 64-step error (measured 0.18 against 0.06-0.07 noise units), so the check
// bounds that error from above, and stays below the warning.
TEST(StepCheck, BoundsTheErrorOfASecondOrderSweepFromAbove) {
  const StepChecked r = step_checked("control");
  for (std::size_t i = 0; i < r.checked.tests.size(); ++i) {
    const cc::TestCompare& t = r.checked.tests[i];
    if (t.kind != "dynamic") continue;
    const double error_at_64 = model_change(t, r.fine.tests[i]);
    std::cout << t.name << ": step error estimate " << t.step_error << ", change 64 -> 512 steps " << error_at_64
              << "\n";
    EXPECT_GT(t.step_error, 2.0 * error_at_64) << t.name;
    EXPECT_LT(t.step_error, 0.5) << t.name;
  }
  for (const auto& w : r.checked.warnings) EXPECT_EQ(w.find("the time step moves"), std::string::npos) << w;
}

// diagnose checks the step of its named model only: the winner's sweeps carry a step_error, the baseline's not.
TEST(StepCheck, DiagnoseChecksTheNamedModel) {
  const auto base = cushion::material::read_material_file(hidden() / "base_material.json");
  const cc::Campaign campaign = cc::read_campaign(hidden() / "campaign_pneumatic" / "campaign.json");
  cc::DiagnoseOptions o;
  o.candidates = {"pneumatic"};
  o.max_iterations = 4;
  std::ostringstream log;
  const cc::Diagnosis d = cc::diagnose(base.spec, campaign, o, log);
  ASSERT_TRUE(d.winner.has_value()) << d.verdict;
  int checked = 0;
  for (const cc::TestCompare& t : d.candidates[*d.winner].compare.tests)
    if (t.kind == "dynamic") checked += t.step_error >= 0.0;
  EXPECT_EQ(checked, 2);
  for (const cc::TestCompare& t : d.baseline.tests) EXPECT_LT(t.step_error, 0.0) << t.name;
}
