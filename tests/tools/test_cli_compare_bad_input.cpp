// `cushion compare` on the bad input of issue 7: a one-test campaign of another foam. The command says
// what the campaign cannot tell apart and that the specimens differ, and still reports the comparison.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

TEST(CliCompareBadInput, SingleTestOfAnotherFoamWarnsAndStillReports) {
  const fs::path hidden = fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects";
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_cli_compare_bad_input_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(hidden / "campaign_control" / "qs_120.csv", dir / "qs_120.csv", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "campaign.json")
      << R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 30},
            "tests": [{"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120}]})";
  const cli_test::CommandRun r = cli_test::run_cushion("compare " + cli_test::quoted(hidden / "base_material.json") + " " +
                                                       cli_test::quoted(dir / "campaign.json") + " -o " +
                                                       cli_test::quoted(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("specimen mismatch"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("only one material-level test"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| qs_120 | quasi_static |"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "report.json"));
  fs::remove_all(dir);
}
