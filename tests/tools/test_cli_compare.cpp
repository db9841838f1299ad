// `cushion compare` / `cushion diagnose` as a user runs them on cases/hidden_effects: outputs written, the
// run history grows by one run per compare, and bad input gives a clear message (exit 2) or a warning
// while the rest of the analysis is still reported.
#include <gtest/gtest.h>
#include <unistd.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fs = std::filesystem;

#include "cli_runner.hpp"

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

fs::path hidden() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects"; }
/// One folder per process: ctest runs the tests of this file as parallel processes.
fs::path scratch() { return fs::temp_directory_path() / ("cushion_test_cli_compare_" + std::to_string(::getpid())); }

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count_lines(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string l; std::getline(in, l);) n += !l.empty();
  return n;
}

}  // namespace

TEST(CliCompare, WritesReportAndAppendsHistory) {
  fs::remove_all(scratch());
  const std::string args = quoted(hidden() / "base_material.json") + " " +
                           quoted(hidden() / "campaign_friction" / "campaign.json") + " -o " + quoted(scratch() / "c1") +
                           " --history " + quoted(scratch() / "history");
  const CommandRun a = run_cushion("compare " + args + " --label baseline");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("some tests fail beyond noise"), std::string::npos) << a.output;
  std::ifstream in(scratch() / "c1" / "report.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["tests"].size(), 5u);
  EXPECT_TRUE(fs::exists(scratch() / "c1" / "compare_qs_30.gp"));
  EXPECT_TRUE(fs::exists(scratch() / "c1" / "compare_dyn_40.csv"));
  const CommandRun b = run_cushion("compare " + quoted(hidden() / "truth_material_friction.json") + " " +
                                   quoted(hidden() / "campaign_friction" / "campaign.json") + " -o " +
                                   quoted(scratch() / "c2") + " --history " + quoted(scratch() / "history") +
                                   " --label with_friction");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find("every test is at the noise level"), std::string::npos) << b.output;
  EXPECT_EQ(count_lines(scratch() / "history" / "history.csv"), 1u + 2u * 5u);  // header + 2 runs x 5 tests
  // History plot: integer tics labelled with the run labels, markers, the noise level and the 1.5 x noise limit.
  const std::string history = read_text(scratch() / "history" / "history_plot.gp");
  EXPECT_NE(history.find("set xtics ('1: baseline' 1, '2: with_friction' 2)"), std::string::npos) << history;
  EXPECT_NE(history.find("with linespoints"), std::string::npos) << history;
  EXPECT_NE(history.find("first 1 to graph 1, first 1 nohead"), std::string::npos) << history;
  EXPECT_NE(history.find("first 1.5 to graph 1, first 1.5 nohead"), std::string::npos) << history;
  EXPECT_NE(history.find("set object 1 rect from graph 0, first 0 to graph 1, first 1.5"), std::string::npos) << history;
  // Spectrum plot: x range that of the data (1-20 Hz), not gnuplot's next decade; keys outside the plot area.
  const std::string dyn = read_text(scratch() / "c1" / "compare_dyn_40.gp");
  EXPECT_NE(dyn.find("\nreset\n"), std::string::npos) << dyn;
  EXPECT_NE(dyn.find("set key outside"), std::string::npos) << dyn;
  const std::size_t range = dyn.find("set xrange [");
  ASSERT_NE(range, std::string::npos) << dyn;
  const double upper = std::stod(dyn.substr(dyn.find(':', range) + 1));
  EXPECT_GT(upper, 20.0);
  EXPECT_LT(upper, 25.0) << dyn;
}

TEST(CliCompare, BadMaterialIsAnInputError) {
  const fs::path dir = scratch() / "bad";
  fs::create_directories(dir);
  std::ofstream(dir / "m.json") << R"({"hyperfoam": {"terms": [{"mu_kPa": 1, "alpha": 0, "nu": 0}]}})";
  const CommandRun r = run_cushion("compare " + quoted(dir / "m.json") + " " +
                                   quoted(hidden() / "campaign_control" / "campaign.json") + " -o " + quoted(dir / "out"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("alpha"), std::string::npos) << r.output;
}

// One test only: diagnose still runs and says what cannot be told apart.
TEST(CliDiagnose, SingleTestCampaignWarnsAndStillReports) {
  const fs::path dir = scratch() / "single";
  fs::create_directories(dir);
  fs::copy_file(hidden() / "campaign_friction" / "qs_120.csv", dir / "qs_120.csv", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "campaign.json")
      << R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
            "tests": [{"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120}]})";
  const CommandRun r = run_cushion("diagnose " + quoted(hidden() / "base_material.json") + " " +
                                   quoted(dir / "campaign.json") + " -o " + quoted(dir / "out") +
                                   " --candidates friction,stiffness_damping");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cannot be told"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "diagnosis.md"));
  EXPECT_TRUE(fs::exists(dir / "out" / "report.json"));
}

// --joint-base: the candidate is fitted together with the base moduli; the verdict points at the extended
// material (effect + refitted base), which is written.
TEST(CliDiagnose, JointBaseNamesTheEffectAndWritesTheRefittedMaterial) {
  const fs::path dir = scratch() / "joint";
  const CommandRun r = run_cushion("diagnose " + quoted(hidden() / "base_material.json") + " " +
                                   quoted(hidden() / "campaign_friction" / "campaign.json") + " -o " +
                                   quoted(dir / "out") + " --candidates friction --joint-base");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Add friction"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("joint"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "material_extended.json"));
  EXPECT_TRUE(fs::exists(dir / "out" / "fragment.json"));
  // diagnosis.md says what each value of the change means (the catalogue's line for friction's yield stress)
  EXPECT_NE(read_text(dir / "out" / "diagnosis.md").find("- `friction.yield_stress_kPa`: s_y: sliding stress"),
            std::string::npos);
}

// From raw test files: no material given, so the base is calibrated first (the fit job into OUT/fit) and the
// candidate is fitted jointly with it; the hidden friction of the campaign is still named.
TEST(CliDiagnose, RawCampaignIsCalibratedFirstAndTheEffectNamed) {
  const fs::path dir = scratch() / "raw";
  const CommandRun r = run_cushion("diagnose " + quoted(hidden() / "campaign_friction" / "campaign.json") + " -o " +
                                   quoted(dir / "out") + " --candidates friction");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("calibrating the base from the campaign"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "fit" / "material.json"));
  EXPECT_TRUE(fs::exists(dir / "out" / "fit" / "report.md"));
  EXPECT_NE(r.output.find("Add friction"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "material_extended.json"));
}

// compare and diagnose run one forward-model schedule (the campaign's cycles, the same time step): the same
// material and campaign give the same error/noise per test and region in both report.json files (to 1e-9).
// --max-iterations and --steps-per-cycle are options of diagnose (the latter of compare too).
TEST(CliDiagnose, BaselineFiguresEqualCompareFigures) {
  const fs::path dir = scratch() / "same";
  const std::string files =
      quoted(hidden() / "base_material.json") + " " + quoted(hidden() / "campaign_friction" / "campaign.json");
  const CommandRun c = run_cushion("compare " + files + " -o " + quoted(dir / "cmp"));
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const CommandRun d =
      run_cushion("diagnose " + files + " -o " + quoted(dir / "diag") + " --candidates friction --max-iterations 1");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  std::ifstream ci(dir / "cmp" / "report.json"), di(dir / "diag" / "report.json");
  const nlohmann::json cj = nlohmann::json::parse(ci), dj = nlohmann::json::parse(di);
  const nlohmann::json& a = cj["tests"];
  const nlohmann::json& b = dj["baseline"]["tests"];
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i]["name"], b[i]["name"]);
    EXPECT_NEAR(a[i]["error_over_noise"].get<double>(), b[i]["error_over_noise"].get<double>(), 1e-9) << a[i]["name"];
    for (std::size_t r = 0; r < a[i]["regions"].size(); ++r)
      EXPECT_NEAR(a[i]["regions"][r]["rms"].get<double>(), b[i]["regions"][r]["rms"].get<double>(), 1e-9);
  }
  const CommandRun bad = run_cushion("diagnose " + files + " -o " + quoted(dir / "bad") + " --max-iterations 0");
  EXPECT_NE(bad.exit_code, 0) << bad.output;
  EXPECT_NE(bad.output.find("--max-iterations"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

// A campaign that does not record how its dynamic tests were run (the virtual lab ran 8 cycles a frequency, the last
// 4 fitted; the manifest leaves out cycles, fit_cycles, the convention, the preload ramp and the dwell): diagnose
// searches them as nuisance parameters with the true material, reports the chi2 of every value tried (of the cycle
// counts searched, 10 with the last 5 fitted, the nearest to what ran, fits best) and says what it assumed, in the
// verdict when it keeps the values found, in a warning when a refitted base explains the data as well under the
// defaults. --assume-protocol models the defaults without a search.
TEST(CliDiagnose, UnrecordedProtocolIsSearchedAndReported) {
  const fs::path dir = scratch() / "protocol";
  fs::create_directories(dir);
  std::ifstream in(hidden() / "campaign_friction" / "campaign.json");
  nlohmann::json campaign = nlohmann::json::parse(in);
  for (auto& t : campaign["tests"]) {
    fs::copy_file(hidden() / "campaign_friction" / t["file"].get<std::string>(), dir / t["file"].get<std::string>(),
                  fs::copy_options::overwrite_existing);
    if (t["kind"] == "dynamic")
      for (const char* k : {"amplitude_convention", "preload_rate_mm_min", "dwell_before_sweep_s", "cycles", "fit_cycles"})
        t.erase(k);
  }
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  const std::string files = quoted(hidden() / "truth_material_friction.json") + " " + quoted(dir / "campaign.json");
  const std::string options = " --candidates friction --max-iterations 2";
  const CommandRun r = run_cushion("diagnose " + files + " -o " + quoted(dir / "searched") + options);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream ri(dir / "searched" / "report.json");
  const nlohmann::json j = nlohmann::json::parse(ri);
  ASSERT_TRUE(j.contains("protocol")) << r.output;
  const nlohmann::json& keys = j["protocol"]["keys"];
  ASSERT_EQ(keys.size(), 4u);
  for (const auto& k : keys) {
    EXPECT_EQ(k["tests"].size(), 2u);
    for (const auto& v : k["tried"]) EXPECT_TRUE(v["chi2"].is_number()) << k["key"] << " " << v["value"];
    if (k["key"] != "cycles") continue;
    std::string best;
    double lowest = 1e300;
    for (const auto& v : k["tried"])
      if (v["chi2"].get<double>() < lowest) lowest = v["chi2"].get<double>(), best = v["value"].get<std::string>();
    EXPECT_EQ(best, "10 (last 5 fitted)") << k.dump();
  }
  const std::string verdict = j["verdict"].get<std::string>(), warnings = j["warnings"].dump();
  EXPECT_TRUE(verdict.find("Protocol: the campaign does not record") != std::string::npos ||
              warnings.find("the defaults are kept") != std::string::npos) << verdict << "\n" << warnings;
  EXPECT_NE(read_text(dir / "searched" / "diagnosis.md").find("## Protocol assumptions"), std::string::npos);

  const CommandRun a = run_cushion("diagnose " + files + " -o " + quoted(dir / "assumed") + " --assume-protocol" + options);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  std::ifstream ai(dir / "assumed" / "report.json");
  EXPECT_FALSE(nlohmann::json::parse(ai).contains("protocol"));
}
