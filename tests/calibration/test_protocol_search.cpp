// Unrecorded dynamic protocol keys as nuisance parameters (calibration/protocol_search.hpp, issue 15 part 2). The
// campaigns come from the independent generator (tests/foreign, run as its own program) with
// `--protocol unrecorded`: each campaign runs its own cycles per frequency, preload ramp, dwell and amplitude
// convention and leaves those keys out of the manifest; truth.json says what ran. The model is the exact material of
// the campaign's base foam (foreign_program.hpp), so any misfit beyond noise is the protocol's.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "calibration/compare.hpp"
#include "calibration/protocol_search.hpp"
#include "foreign_program.hpp"

namespace cc = cushion::calibration;
namespace fs = std::filesystem;

namespace {

const cc::ProtocolKeySearch* key(const cc::ProtocolSearch& s, const std::string& name) {
  for (const auto& k : s.keys)
    if (k.key == name) return &k;
  return nullptr;
}

double worst_dynamic_ratio(const cc::CompareResult& r) {
  double w = 0.0;
  for (const auto& t : r.tests)
    if (t.kind == "dynamic") w = std::max(w, t.noise_ratio());
  return w;
}

}  // namespace

TEST(ProtocolSearch, RecordedKeysAreNotSearched) {
  const fs::path dir = cushion::foreign_program::generate("protocol_recorded", 1, 5, 0, 1);
  const cc::Campaign campaign = cc::read_campaign(dir / "c000" / "campaign.json");
  for (const auto& t : campaign.dynamic) EXPECT_TRUE(t.unrecorded.empty()) << t.name;
  const auto def = cushion::foreign_program::exact_material(dir / "c000");
  const cc::ProtocolSearch s = cc::search_protocol(*def.model, campaign, cc::estimate_noise(campaign), {}, 10.0);
  EXPECT_TRUE(s.keys.empty());
  EXPECT_FALSE(s.changed());
  EXPECT_FALSE(s.moved);
  EXPECT_EQ(s.runs, 0);
  fs::remove_all(dir);
}

// Controls with their exact base (seed 31; measured 2026-11-25): where the amplitude convention matters (its two values
// differ in chi2 by more than 10 about the values found) the one found is what the lab ran (6 of 6); the search never
// ends above the defaults' chi2; with the values found every dynamic test is within 1.5x its noise on all but at most
// one campaign (measured: 0.54-0.73x on 5; 2.14 -> 1.78x on the one run with 5 cycles a frequency and 2 fitted, where
// the protocol found is close to what ran: 5 cycles, 100 mm/min for 78, 10 s dwell for 13.6 s, peak).
TEST(ProtocolSearch, FindsTheProtocolAForeignLabRanWithoutRecordingIt) {
  const int count = 6;
  const fs::path dir = cushion::foreign_program::generate("protocol_search", count, 31, 0, count, "--protocol unrecorded");
  int beyond_noise = 0, convention_decided = 0;
  for (int i = 0; i < count; ++i) {
    const std::string name = "c00" + std::to_string(i);
    SCOPED_TRACE(name);
    const cc::Campaign campaign = cc::read_campaign(dir / name / "campaign.json");
    std::ifstream in(dir / name / "truth.json");
    const nlohmann::json truth = nlohmann::json::parse(in).at("protocol");
    const auto def = cushion::foreign_program::exact_material(dir / name);
    const std::vector<cc::TestNoise> noise = cc::estimate_noise(campaign);
    const cc::ProtocolSearch s = cc::search_protocol(*def.model, campaign, noise, {}, 10.0);
    ASSERT_EQ(s.keys.size(), 4u);
    for (const auto& t : campaign.dynamic) EXPECT_EQ(t.unrecorded.size(), 5u);  // the four keys and fit_cycles
    std::cout << name << ": truth " << truth.dump() << "\n  searched (" << s.runs << " runs, " << s.seconds
              << " s): chi2 " << s.chi2_assumed << " -> " << s.chi2_chosen << "\n";
    for (const auto& k : s.keys) {
      std::cout << "  " << k.key << ": chosen " << k.chosen << " (default " << k.assumed << ", range " << k.chi2_range() << "):";
      for (const auto& v : k.tried) std::cout << " " << v.label << " " << v.chi2 << ";";
      std::cout << "\n";
    }
    EXPECT_LE(s.chi2_chosen, s.chi2_assumed);
    EXPECT_EQ(s.moved, s.changed());  // searched from the defaults
    const cc::ProtocolKeySearch* convention = key(s, "amplitude_convention");
    ASSERT_NE(convention, nullptr);
    if (convention->chi2_range() > 10.0) {
      ++convention_decided;
      EXPECT_EQ(convention->chosen, truth.at("amplitude_convention").get<std::string>());
    }
    const double before = worst_dynamic_ratio(cc::compare_campaign(*def.model, campaign, {}, noise));
    const double after = worst_dynamic_ratio(cc::compare_campaign(*def.model, s.campaign, {}, noise));
    std::cout << "  worst dynamic error/noise " << before << " -> " << after << "\n";
    if (after > 1.5) ++beyond_noise;
  }
  EXPECT_GE(convention_decided, 4);
  EXPECT_LE(beyond_noise, 1);
  fs::remove_all(dir);
}
