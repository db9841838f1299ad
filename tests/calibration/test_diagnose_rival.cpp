// Two families that explain a campaign equally (diagnose step 7, separating_test.hpp), on data of the independent
// generator (tests/foreign, its own program): campaign c021 of seed 2025 (the benchmark's; stiffness-proportional
// damping s = beta E_t(e) e' on a soft-plateau foam). From raw data (fit, then diagnose with the two candidates
// concerned, no pairs):
//  - the verdict names stiffness_damping and says that pneumatic explains the tests about as well (dBIC within 10,
//    measured 65.35 vs 57.66), and names as the separating test a quasi-static test at 3000 mm/min (five times the
//    fastest rate), which would add chi2 > 10 between the two fitted models;
//  - the same campaign generated with that test added (--extra-rate 3000: same truth, same other records) tells them
//    apart: stiffness_damping named, pneumatic more than 10 below it, no rival (measured 63.1 vs 21.3).
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "calibration/diagnose.hpp"
#include "calibration/fit_pipeline.hpp"
#include "foreign_program.hpp"

namespace cc = cushion::calibration;
namespace fs = std::filesystem;

namespace {

cc::Diagnosis diagnose_raw(const fs::path& campaign_dir) {
  const cc::Campaign campaign = cc::read_campaign(campaign_dir / "campaign.json");
  std::ostringstream log;
  const cc::FitResult R = cc::fit_pipeline(campaign, cc::diagnose_base_fit_options(), log);
  const auto spec = cc::to_spec(R.default_material, "foam", "fitted", campaign.specimen.density);
  cc::DiagnoseOptions o;
  o.candidates = {"stiffness_damping", "pneumatic"};
  o.pairs_from = 0;
  cc::Diagnosis d = cc::diagnose(spec, campaign, o, log);
  std::cout << campaign_dir.filename().string() << ": " << d.verdict << "\n";
  for (const auto& c : d.candidates) std::cout << "  " << c.name() << ": dBIC " << c.delta_bic << "\n";
  return d;
}

}  // namespace

TEST(DiagnoseRival, TheNamedSeparatingTestTellsTheFamiliesApart) {
  const fs::path plain = cushion::foreign_program::generate("rival_plain", 60, 2025, 10, 10);
  const fs::path extra = cushion::foreign_program::generate("rival_extra", 60, 2025, 10, 10, "--extra-rate 3000");
  std::ifstream in(plain / "c021" / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  ASSERT_EQ(truth.at("forms").at(0).get<std::string>(), "stiffness_proportional") << "the generator's mix changed";

  const cc::Diagnosis d = diagnose_raw(plain / "c021");
  ASSERT_TRUE(d.winner.has_value()) << d.verdict;
  EXPECT_EQ(d.candidates[*d.winner].name(), "stiffness_damping");
  ASSERT_TRUE(d.rival.has_value()) << d.verdict;
  EXPECT_EQ(d.rival->name, "pneumatic");
  ASSERT_FALSE(d.rival->tests.empty());
  const cc::SeparatingTest& best = d.rival->tests.front();
  EXPECT_EQ(best.name.rfind("quasi-static at 3000 mm/min", 0), 0u) << best.name;
  EXPECT_GT(best.delta_chi2(), 10.0);
  EXPECT_NE(d.verdict.find("cannot tell stiffness_damping from pneumatic"), std::string::npos) << d.verdict;
  EXPECT_NE(d.verdict.find("The test that would separate them: quasi-static at 3000 mm/min"), std::string::npos);

  const cc::Diagnosis e = diagnose_raw(extra / "c021");
  ASSERT_TRUE(e.winner.has_value()) << e.verdict;
  EXPECT_EQ(e.candidates[*e.winner].name(), "stiffness_damping");
  EXPECT_FALSE(e.rival.has_value()) << e.verdict;
  for (const auto& c : e.candidates)
    if (c.name() == "pneumatic") EXPECT_GT(e.candidates[*e.winner].delta_bic - c.delta_bic, 10.0);
  fs::remove_all(plain);
  fs::remove_all(extra);
}
