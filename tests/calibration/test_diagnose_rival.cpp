// Two families that explain a campaign equally (diagnose step 7, separating_test.hpp), on data of the independent
// generator (tests/foreign, its own program): campaign c021 of seed 2025 (the benchmark's; stiffness-proportional
// damping s = beta E_t(e) e' on a soft-plateau foam). From raw data, as a user runs it (`cushion diagnose CAMPAIGN
// --candidates stiffness_damping pneumatic --max-iterations 25`, fit included):
//  - the verdict names stiffness_damping and says that pneumatic explains the tests about as well (dBIC within 10,
//    measured 63.4 vs 57.7), and names as the separating test a quasi-static test at 3000 mm/min (five times the
//    fastest rate), which would add chi2 > 10 between the two fitted models;
//  - the same campaign generated with that test added (--extra-rate 3000: same truth, same other records) tells them
//    apart: stiffness_damping named (62.1), pneumatic more than 10 below it, no rival.
// 25 iterations: the pneumatic fit converges slowly (26 iterations here); the default 12 stops it at dBIC 43.8, where
// it is no rival (measured 2026-11-25), and the test is about two converged explanations.
//
// A preference that rests on the noise estimates (rival_gap.hpp, docs/physics.md 9.31): campaign c040 of the seed-2026
// scale set (secant-stiffness-proportional damping on a soft-plateau foam), `--candidates stiffness_damping,pneumatic`:
// stiffness_damping wins by more than 10 as the noise estimates stand, but with each quasi-static test's noise
// estimate off by up to x1.15 and each sweep's by up to x1.6 (their measured accuracy) the gap falls within 10, so
// pneumatic is named as a rival; with `--noise-uncertainty 1,1` (the plain dBIC rule) it is not.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "foreign_program.hpp"

namespace fs = std::filesystem;

namespace {

/// `cushion diagnose DIR/campaign.json --candidates stiffness_damping pneumatic --max-iterations 25`'s report.
nlohmann::json diagnose_raw(const fs::path& campaign_dir) {
  return cushion::foreign_program::diagnose_raw(campaign_dir,
                                                "--candidates stiffness_damping pneumatic --max-iterations 25");
}

double delta_bic_of(const nlohmann::json& r, const std::string& name) {
  for (const auto& c : r.at("candidates"))
    if (c.at("name") == name) return c.at("delta_bic").get<double>();
  ADD_FAILURE() << "no candidate " << name;
  return 0.0;
}

}  // namespace

TEST(DiagnoseRival, TheNamedSeparatingTestTellsTheFamiliesApart) {
  const fs::path plain = cushion::foreign_program::generate("rival_plain", 60, 2025, 10, 10, "--only c021");
  const fs::path extra =
      cushion::foreign_program::generate("rival_extra", 60, 2025, 10, 10, "--extra-rate 3000 --only c021");
  std::ifstream in(plain / "c021" / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  ASSERT_EQ(truth.at("forms").at(0).get<std::string>(), "stiffness_proportional") << "the generator's mix changed";

  const nlohmann::json d = diagnose_raw(plain / "c021");
  const std::string verdict = d.at("verdict");
  EXPECT_EQ(d.at("winner"), "stiffness_damping") << verdict;
  ASSERT_TRUE(d.at("rival").is_object()) << verdict;
  EXPECT_EQ(d.at("rival").at("name"), "pneumatic");
  const nlohmann::json& best = d.at("rival").at("separating_tests").at(0);
  EXPECT_EQ(best.at("test").get<std::string>().rfind("quasi-static at 3000 mm/min", 0), 0u) << best.dump();
  EXPECT_GT(best.at("delta_chi2").get<double>(), 10.0);
  EXPECT_NE(verdict.find("cannot tell stiffness_damping from pneumatic"), std::string::npos) << verdict;
  EXPECT_NE(verdict.find("The test that would separate them: quasi-static at 3000 mm/min"), std::string::npos);

  const nlohmann::json e = diagnose_raw(extra / "c021");
  EXPECT_EQ(e.at("winner"), "stiffness_damping") << e.at("verdict");
  EXPECT_TRUE(e.at("rival").is_null()) << e.at("verdict");
  EXPECT_GT(delta_bic_of(e, "stiffness_damping") - delta_bic_of(e, "pneumatic"), 10.0);
  fs::remove_all(plain);
  fs::remove_all(extra);
}

// Friction beats air flow by more than 10 in dBIC, but not once each test's noise estimate may be off by its
// uncertainty: the air flow is named as a rival, and with --noise-uncertainty 1,1 (the estimates taken as exact) it is
// not. Seed-2027 c043 (Bouc-Wen friction + fractional damping, diagnosed with friction and air flow only): friction
// dBIC 915.6 against 842.6, least gap -21.9 (2026-12-07). Until 2026-12-06 this test ran on seed-2026 c040 (stiffness
// damping against air flow), whose stiffness damping on the nominal tangent (docs/physics.md 9.40) now wins clearly.
TEST(DiagnoseRival, APreferenceThatRestsOnTheNoiseEstimatesNamesARival) {
  const fs::path dir =
      cushion::foreign_program::generate("rival_reweighted", 60, 2027, 10, 10, "--base-refit scale --only c043");
  std::ifstream in(dir / "c043" / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  ASSERT_EQ(truth.at("forms").at(0).get<std::string>(), "bouc_wen") << "the generator's mix changed";

  const std::string candidates = "--candidates friction,pneumatic";
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(dir / "c043", candidates);
  const std::string verdict = d.at("verdict");
  EXPECT_EQ(d.at("winner"), "friction") << verdict;
  ASSERT_TRUE(d.at("rival").is_object()) << verdict;
  EXPECT_EQ(d.at("rival").at("name"), "pneumatic");
  EXPECT_GT(delta_bic_of(d, "friction") - delta_bic_of(d, "pneumatic"), 10.0);
  EXPECT_LE(d.at("rival").at("least_gap").get<double>(), 10.0);
  EXPECT_NE(verdict.find("so the preference rests on the noise estimates"), std::string::npos) << verdict;

  const nlohmann::json e =
      cushion::foreign_program::diagnose_raw(dir / "c043", candidates + " --noise-uncertainty 1,1", "diag_plain");
  EXPECT_EQ(e.at("winner"), "friction") << e.at("verdict");
  EXPECT_TRUE(e.at("rival").is_null()) << e.at("verdict");
  fs::remove_all(dir);
}
