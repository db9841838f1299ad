// compare.hpp bad input of issue 7: what a campaign cannot tell apart (coverage_warnings) and a material
// calibrated on another foam (specimen_warnings): messages, while the comparison itself still runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "calibration/compare.hpp"

namespace cc = cushion::calibration;
namespace fs = std::filesystem;

namespace {

fs::path hidden() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects"; }

/// A campaign folder with the given tests (copies of campaign_friction's files), specimen density `density`.
fs::path campaign_with(const std::string& name, const std::string& tests, double density) {
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_compare_coverage_" + std::to_string(::getpid())) / name;
  fs::create_directories(dir);
  for (const char* f : {"qs_30.csv", "qs_120.csv", "dyn_25.csv"})
    fs::copy_file(hidden() / "campaign_friction" / f, dir / f, fs::copy_options::overwrite_existing);
  std::ofstream(dir / "campaign.json") << R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": )"
                                       << density << R"(}, "tests": [)" << tests << "]}";
  return dir / "campaign.json";
}

bool contains(const std::vector<std::string>& v, const std::string& what) {
  for (const auto& s : v)
    if (s.find(what) != std::string::npos) return true;
  return false;
}

const char* qs120 = R"({"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120})";
const char* qs30 = R"({"kind": "quasi_static", "file": "qs_30.csv", "rate_mm_min": 30})";
const char* dyn25 = R"({"kind": "dynamic", "file": "dyn_25.csv", "preload_strain": 0.25, "acceleration_amplitude_m_s2": 0.25})";

}  // namespace

TEST(CompareCoverage, SingleTestSaysWhatCannotBeToldApart) {
  const auto w = cc::coverage_warnings(cc::read_campaign(campaign_with("single", qs120, 65)));
  EXPECT_TRUE(contains(w, "only one material-level test"));
  EXPECT_TRUE(contains(w, "rate-dependent hysteresis (viscous, pneumatic) cannot be told"));
  EXPECT_FALSE(contains(w, "preload"));  // no dynamic test: nothing said about preloads
}

TEST(CompareCoverage, TwoRatesAndOnePreloadWarnOnlyAboutThePreload) {
  const auto w = cc::coverage_warnings(
      cc::read_campaign(campaign_with("two", std::string(qs120) + "," + qs30 + "," + dyn25, 65)));
  EXPECT_FALSE(contains(w, "only one"));
  EXPECT_FALSE(contains(w, "rate"));
  EXPECT_TRUE(contains(w, "one dynamic preload"));
}

TEST(CompareCoverage, TheShippedCampaignsNeedNoWarning) {
  EXPECT_TRUE(cc::coverage_warnings(cc::read_campaign(hidden() / "campaign_friction" / "campaign.json")).empty());
}

// Density 65 (material) vs 30 kg/m^3 (campaign): one warning naming both; within 5%: none.
TEST(CompareCoverage, MismatchedSpecimenIsNamed) {
  const cc::Campaign c = cc::read_campaign(campaign_with("foam30", qs120, 30));
  const auto w = cc::specimen_warnings(65e-12, c);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("65"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("30"), std::string::npos) << w[0];
  EXPECT_TRUE(cc::specimen_warnings(31e-12, c).empty());
  EXPECT_TRUE(cc::specimen_warnings(0.0, c).empty());  // the material gives no density: nothing to check
}
