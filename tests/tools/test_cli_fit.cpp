// `cushion fit` as a user runs it: a good campaign gives every documented output; bad campaigns give a
// non-zero exit, one message naming the file and the line/column (or key), and no output folder.
#include <gtest/gtest.h>
#include <unistd.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "material/io/material_file.hpp"

namespace fs = std::filesystem;

#include "cli_runner.hpp"

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// A small SYNTHETIC campaign made once by `cushion lab` (few samples, 4 frequencies).
class CliFit : public ::testing::Test {
 protected:
  // One folder per process: ctest runs the tests of this suite as parallel processes.
  static fs::path root() { return fs::temp_directory_path() / ("cushion_test_cli_fit_" + std::to_string(::getpid())); }
  static fs::path campaign() { return root() / "campaign"; }
  static void SetUpTestSuite() {
    fs::remove_all(root());
    fs::create_directories(root());
    write(root() / "truth.json",
          "{\"material\": \"" + std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json\",\n"
          " \"specimen\": {\"length_mm\": 80, \"width_mm\": 80, \"thickness_mm\": 80, \"density_kg_m3\": 65},\n"
          " \"quasi_static\": [{\"name\": \"qs\", \"rate_mm_min\": 120, \"sample_hz\": 2, \"preload_cycle\": false}],\n"
          " \"dynamic\": [{\"name\": \"dyn\", \"preload_strain\": 0.25, \"acceleration_amplitude_m_s2\": 0.25,\n"
          "   \"frequencies_Hz\": [1, 5, 10, 20], \"cycles\": 4, \"fit_cycles\": 2, \"steps_per_cycle\": 32}]}\n");
    const CommandRun lab = run_cushion("lab " + quoted(root() / "truth.json") + " -o " + quoted(campaign()));
    ASSERT_EQ(lab.exit_code, 0) << lab.output;
  }
  /// A copy of the campaign with one file replaced; returns its manifest.
  fs::path variant(const std::string& name, const std::string& file, const std::string& text) {
    const fs::path dir = root() / name;
    fs::remove_all(dir);
    fs::copy(campaign(), dir);
    write(dir / file, text);
    return dir / "campaign.json";
  }
  /// Runs fit on a bad campaign: exit 2, one line naming `where`, no output and no partial output.
  void expect_rejected(const fs::path& manifest, const std::string& where, const std::string& what = "") {
    const fs::path out = manifest.parent_path() / "out";
    const CommandRun r = run_cushion("fit " + quoted(manifest) + " -o " + quoted(out));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("input error"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
    if (!what.empty()) {
      EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  }
  std::string qs_csv() { return read(campaign() / "qs.csv"); }
};

/// Replaces the first occurrence of `from` in `text`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The CSV with data row `row` (0-based, after the header) replaced by `line`; returns the file line number too.
std::pair<std::string, int> with_row(const std::string& csv, std::size_t row, const std::string& line) {
  std::istringstream in(csv);
  std::ostringstream out;
  std::string text;
  int number = 0, hit = 0;
  std::size_t data = 0;
  bool header = false;
  while (std::getline(in, text)) {
    ++number;
    if (text.empty() || text[0] == '#' || !header) {
      header = header || (!text.empty() && text[0] != '#');
      out << text << "\n";
      continue;
    }
    if (data++ == row) {
      out << line << "\n";
      hit = number;
    } else {
      out << text << "\n";
    }
  }
  return {out.str(), hit};
}

}  // namespace

TEST_F(CliFit, WritesEveryOutputAndAReadableMaterial) {
  const fs::path out = root() / "fit_out";
  fs::remove_all(out);
  const CommandRun r = run_cushion("fit " + quoted(campaign() / "campaign.json") + " -o " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("outputs in"), std::string::npos);
  for (const char* f : {"material.json", "abaqus_paper.inp",
                        "abaqus_refit.inp", "report.json", "report.md", "fig8_decomposition.csv", "fig8_decomposition.gp",
                        "fig7_difference_stress.csv", "fig4_dynamic.csv", "table2_protocol.csv"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  // The default material is one of the two written, and the solver reads it.
  const auto def = cushion::material::read_material_file(out / "material.json");
  const auto json = nlohmann::json::parse(read(out / "report.json"));
  // A material file is written unless the reader would reject it (then the report says why).
  for (const std::string which : {"paper", "refit"})
    EXPECT_EQ(fs::exists(out / ("material_" + which + ".json")), json["material_problems"][which].get<std::string>().empty())
        << which;
  const std::string chosen = json["default"]["material"];
  const auto same = cushion::material::read_material_file(out / ("material_" + chosen + ".json"));
  ASSERT_EQ(def.spec.hyperfoam.size(), same.spec.hyperfoam.size());
  EXPECT_EQ(def.spec.hyperfoam[0].mu, same.spec.hyperfoam[0].mu);
  EXPECT_EQ(json["tests"].size(), 2u);
  EXPECT_NE(read(out / "abaqus_refit.inp").find("*HYPERFOAM, N=3, MODULI=LONG TERM"), std::string::npos);
  // Console and report.md give the same pairing interval.
  const auto interval = [](const std::string& text) {
    const std::size_t at = text.find("pairs every ");
    return at == std::string::npos ? std::string("none") : text.substr(at, text.find(" s", at + 12) - at);
  };
  EXPECT_NE(interval(r.output), "none") << r.output;
  EXPECT_EQ(interval(r.output), interval(read(out / "report.md")));
  // Plots: each script resets gnuplot's state (one process draws them all); a right axis only where a series uses it.
  for (const char* plot : {"fig8_decomposition", "fig7_difference_stress", "fig4_dynamic", "table2_protocol",
                           "model_vs_test_quasi_static", "model_vs_test_dynamic"}) {
    const std::string gp = read(out / (std::string(plot) + ".gp"));
    EXPECT_NE(gp.find("\nreset\n"), std::string::npos) << plot;
    const bool right_axis = std::string(plot) == "fig4_dynamic";
    EXPECT_EQ(gp.find("y2") != std::string::npos, right_axis) << plot << "\n" << gp;
    EXPECT_TRUE(fs::exists(out / (std::string(plot) + ".csv"))) << plot;
  }
  const std::string dynamic = read(out / "model_vs_test_dynamic.gp");
  EXPECT_NE(dynamic.find("set multiplot layout 2,1"), std::string::npos) << dynamic;
  EXPECT_NE(dynamic.find("set ylabel 'phase [deg]'"), std::string::npos) << dynamic;
  EXPECT_NE(dynamic.find("dyn: test phase"), std::string::npos) << dynamic;
  const std::string qs = read(out / "model_vs_test_quasi_static.gp");
  EXPECT_NE(qs.find("dashtype 2"), std::string::npos) << qs;  // the paper's material dashed, the refit solid
  EXPECT_NE(qs.find("key outside"), std::string::npos) << qs;
  // A second run replaces an earlier fit output with --overwrite only; without it, the folder is refused
  // before the fit runs and stays as it was.
  const auto before = cli_test::listing(out);
  cli_test::expect_input_error(run_cushion("fit " + quoted(campaign() / "campaign.json") + " -o " + quoted(out)),
                               {out.string() + ": --output: the folder exists and is not empty", "--overwrite"});
  EXPECT_EQ(cli_test::listing(out), before);
  write(out / "stale.txt", "left by hand\n");
  EXPECT_EQ(run_cushion("fit " + quoted(campaign() / "campaign.json") + " -o " + quoted(out) + " --overwrite").exit_code, 0);
  EXPECT_TRUE(fs::exists(out / "material.json"));
  EXPECT_FALSE(fs::exists(out / "stale.txt"));
}

TEST_F(CliFit, MissingOrMisspeltColumnsAndOtherUnits) {
  expect_rejected(variant("misspelt", "qs.csv", replaced(qs_csv(), "force_N", "forse_N")), "qs.csv", "force_N");
  expect_rejected(variant("units", "qs.csv", replaced(qs_csv(), "force_N", "force_kN")), "qs.csv", "force_N");
  expect_rejected(variant("missing", "dyn.csv", "frequency_Hz,dynamic_modulus_kPa\n1,10\n2,11\n3,12\n"), "dyn.csv",
                  "phase_deg");
}

TEST_F(CliFit, EmptyAndNaNFiles) {
  expect_rejected(variant("empty", "qs.csv", ""), "qs.csv");
  const auto [text, line] = with_row(qs_csv(), 10, "5,10,nan");
  expect_rejected(variant("nan", "qs.csv", text), "qs.csv:" + std::to_string(line));
}

TEST_F(CliFit, NotALoadUnloadTest) {
  // Loading only: the record stops at the peak.
  std::istringstream in(qs_csv());
  std::ostringstream loading;
  std::string text;
  double last = -1.0;
  while (std::getline(in, text)) {
    if (!text.empty() && text[0] != '#' && std::isdigit(static_cast<unsigned char>(text[0]))) {
      const double d = std::stod(text.substr(text.find(',') + 1));
      if (d < last) break;
      last = d;
    }
    loading << text << "\n";
  }
  expect_rejected(variant("no_unloading", "qs.csv", loading.str()), "qs.csv", "unloading");
  // Non-monotonic loading: a sample in the middle of the loading ramp pulled back by 10 mm.
  const auto [text2, line] = with_row(qs_csv(), 20, "10,5,20");
  expect_rejected(variant("non_monotonic", "qs.csv", text2), "qs.csv");
}

TEST_F(CliFit, FewerThanThreeFrequencies) {
  expect_rejected(variant("two_freq", "dyn.csv", "frequency_Hz,dynamic_modulus_kPa,phase_deg\n1,20,10\n2,21,11\n"),
                  "dyn.csv", "3");
}

TEST_F(CliFit, BadOptions) {
  const fs::path out = root() / "bad_option_out";
  const CommandRun r = run_cushion("fit " + quoted(campaign() / "campaign.json") + " -o " + quoted(out) + " --nu 0.7");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--nu"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

// A user who sends the console to a log file or a pipe (`cushion fit ... | tee fit.log`) sees each progress line when
// it is written, not all of them at exit: the first line must reach the pipe while the fit still runs, i.e. before
// its outputs exist (they appear at the end, all at once). With stdout fully buffered (the C library's default off a
// terminal) the first line arrived only at exit, after the outputs.
TEST_F(CliFit, ProgressLinesReachAPipeWhileItRuns) {
  const fs::path out = root() / "piped_out";
  fs::remove_all(out);
  const std::string reader = "{ IFS= read -r first; if [ -e " + quoted(out) +
                             " ]; then echo 'FIRST LINE AFTER THE OUTPUTS'; else echo 'FIRST LINE WHILE RUNNING'; fi; "
                             "echo \"first: $first\"; cat; }";
  const CommandRun r = cli_test::run_command(quoted(CUSHION_BINARY) + " fit " + quoted(campaign() / "campaign.json") +
                                             " -o " + quoted(out) + " | " + reader);
  EXPECT_NE(r.output.find("FIRST LINE WHILE RUNNING"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("first: fit: "), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "material.json")) << r.output;
}
