// `cushion fit` on a hyperfoam-only campaign ("hyperfoam_tests"): the shipped Kossa case gives every documented
// output; bad manifests and files give exit 2, one message naming the file and key or line/column, nothing written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

fs::path case_dir() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "kossa_pe_foam"; }

class CliFitHyperfoam : public ::testing::Test {
 protected:
  fs::path root = fs::temp_directory_path() / ("cushion_test_cli_fit_hyperfoam_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(root);
    fs::create_directories(root);
    for (const char* f : {"campaign.json", "uniaxial_compression.csv", "equibiaxial_compression.csv"})
      fs::copy_file(case_dir() / f, root / f);
  }
  void TearDown() override { fs::remove_all(root); }
  void write(const std::string& file, const std::string& text) { std::ofstream(root / file) << text; }
  /// The case's manifest with `patch` applied (a JSON merge patch).
  void patch_manifest(const nlohmann::json& patch) {
    std::ifstream in(root / "campaign.json");
    nlohmann::json j = nlohmann::json::parse(in);
    j.merge_patch(patch);
    write("campaign.json", j.dump(1));
  }
  void expect_rejected(const std::string& where, const std::string& what) {
    const fs::path out = root / "out";
    const CommandRun r = run_cushion("fit " + quoted(root / "campaign.json") + " -o " + quoted(out));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("input error"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  }
};

}  // namespace

TEST_F(CliFitHyperfoam, KossaCaseWritesEveryOutput) {
  const fs::path out = root / "out";
  const CommandRun r = run_cushion("fit " + quoted(root / "campaign.json") + " -o " + quoted(out) + " --terms 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("uniaxial (uniaxial): stress R^2 = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lateral stretch max error"), std::string::npos) << r.output;
  for (const char* f : {"material.json", "abaqus_hyperfoam.inp", "report.md", "report.json", "fit_uniaxial.csv",
                        "fit_equibiaxial.csv", "hyperfoam_stress.csv", "hyperfoam_stress.gp",
                        "hyperfoam_lateral_stretch.csv", "hyperfoam_lateral_stretch.gp"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  std::ifstream in(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report.at("kind"), "hyperfoam_only");
  EXPECT_EQ(report.at("terms").size(), 2u);
  EXPECT_GT(report.at("tests")[0].at("stress_r2").get<double>(), 0.99);
  EXPECT_LT(report.at("tests")[1].at("lateral_stretch_max_relative_error").get<double>(), 0.01);
}

TEST_F(CliFitHyperfoam, StressColumnWithoutUnit) {
  patch_manifest({{"hyperfoam_tests", {{{"mode", "uniaxial"}, {"file", "uniaxial_compression.csv"},
                                        {"stretch_column", "stretch"}, {"stress_column", "stress"}}}}});
  expect_rejected("hyperfoam_tests[0].stress_column", "_MPa, _kPa or _Pa");
}

TEST_F(CliFitHyperfoam, UnknownModeKeyAndColumn) {
  patch_manifest({{"hyperfoam_tests", {{{"mode", "biaxial"}, {"file", "uniaxial_compression.csv"}}}}});
  expect_rejected("hyperfoam_tests[0].mode", "biaxial");
  patch_manifest({{"hyperfoam_tests", {{{"mode", "uniaxial"}, {"file", "uniaxial_compression.csv"},
                                        {"stretch_column", "stretch"}, {"stress_column", "nominal_stress_MPa"},
                                        {"lateral_column", "transverse_stretch"}}}}});
  expect_rejected("campaign.json", "lateral_column");
  patch_manifest({{"hyperfoam_tests", {{{"mode", "uniaxial"}, {"file", "uniaxial_compression.csv"},
                                        {"stretch_column", "stretch"}, {"stress_column", "nominal_stress_MPa"},
                                        {"lateral_stretch_column", "lateral"}}}}});
  expect_rejected("lateral_stretch_column", "column 'lateral' is not in");
}

TEST_F(CliFitHyperfoam, CompressionPositiveStressIsRejectedWithItsLine) {
  write("uniaxial_compression.csv", "stretch,nominal_stress_MPa,transverse_stretch\n0.9,0.0173,1.01\n0.8,0.0338,1.02\n");
  expect_rejected("uniaxial_compression.csv:2, column nominal_stress_MPa", "tension positive");
}

TEST_F(CliFitHyperfoam, LateralStretchInAModeWithoutAFreeDirection) {
  patch_manifest({{"hyperfoam_tests", {{{"mode", "volumetric"}, {"file", "uniaxial_compression.csv"},
                                        {"stretch_column", "stretch"}, {"stress_column", "nominal_stress_MPa"},
                                        {"lateral_stretch_column", "transverse_stretch"}}}}});
  expect_rejected("hyperfoam_tests[0].lateral_stretch_column", "no stress-free direction");
}
