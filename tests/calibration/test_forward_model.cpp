// The forward models of compare and diagnose follow the whole protocol a campaign describes (issue 15):
//  - compare and diagnose run ONE schedule: the same material and campaign give the same error/noise;
//  - on campaigns made by an independent generator (tests/foreign, run as its own program) with the exact
//    truth material, the dynamic error/noise falls once the model runs the campaign's protocol (20 cycles per
//    frequency, the last 10 fitted, the 5 s dwell before the sweep) instead of the former cheap schedule
//    (6 cycles, 3 fitted, 48 steps a cycle, no dwell), and every test is at the noise level (error/noise <= 1.5)
//    once the dynamic noise is estimated per frequency (a constant-acceleration sweep: the force amplitude falls as
//    1/f^2, the load cell's floor dominates at 20 Hz and is 10-100 x smaller at 1 Hz).
#include <gtest/gtest.h>

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
