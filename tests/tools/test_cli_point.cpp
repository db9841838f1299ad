// `cushion point` as a user runs it: bad arguments and bad files give a non-zero exit, a one-line
// message and no output file; a good run writes the documented CSV header.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/csv.hpp"

namespace fs = std::filesystem;

#include "cli_runner.hpp"

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

fs::path scratch_dir() { return cli_test::scratch_dir("cushion_test_cli_point_"); }

const std::string material = '"' + std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json\"";


std::size_t lines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n + (!text.empty() && text.back() != '\n');
}

}  // namespace

TEST(CliPoint, BadArgumentsFailWithOneLineAndNoOutput) {
  const fs::path dir = scratch_dir();
  const std::string out = quoted(dir / "out.csv");
  const fs::path bad_material = dir / "bad.json";
  std::ofstream(bad_material) << R"({"hyperfoam": {"terms": [{"mu_kPa": 1, "alpha": 0, "nu": 0}]}})";
  const fs::path bad_protocol = dir / "protocol.json";
  std::ofstream(bad_protocol) << R"({"segments": [{"ramp": {"target": -0.5, "duraton_s": 3}}]})";

  struct Case {
    std::string arguments, expected;  // expected: a fragment of the one-line message
  };
  const std::vector<Case> cases = {
      {"point -m " + material + " --ramp=-0.5,abc -o " + out, "'abc' is not a finite number"},
      {"point -m " + material + " --ramp=-0.5 -o " + out, "expected TARGET,DURATION_S[,STEPS]"},
      {"point -m " + material + " --ramp=-1.2,3 -o " + out, "nominal strain must stay > -1"},
      {"point -m " + material + " --ramp=-0.5,0 -o " + out, "duration must be > 0"},
      {"point -m " + material + " --sine 0.1,0,3 -o " + out, "frequency must be > 0"},
      {"point -m " + material + " --hold 2,1.5 -o " + out, "STEPS must be a whole number"},
      {"point -m " + material + " --hold 2 --mode shear -o " + out, "mode 'shear'"},
      {"point -m " + material + " --hold 2 --mode simple_shear --platen -o " + out, "platen control needs"},
      {"point -m " + material + " -o " + out, "either as --ramp/--hold/--sine segments or as --protocol"},
      {"point -m " + material + " --hold 2 --protocol " + quoted(bad_protocol) + " -o " + out, "one of the two"},
      {"point -m " + material + " --protocol " + quoted(bad_protocol) + " -o " + out, "segments[0].ramp.duraton_s"},
      {"point -m " + material + " --hold 2", "--output"},
      {"point --hold 2 -o " + out, "--material"},
      {"point -m " + quoted(dir / "missing.json") + " --hold 2 -o " + out, "missing.json: no such file"},
      {"point -m " + quoted(bad_material) + " --hold 2 -o " + out, "hyperfoam.terms[0].alpha: must be non-zero"},
  };
  for (const Case& c : cases) {
    const CommandRun run = run_cushion(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.output;
    EXPECT_EQ(lines(run.output), 1u) << c.arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.arguments << "\n" << run.output;
    EXPECT_FALSE(fs::exists(dir / "out.csv")) << c.arguments;
  }
  // Parse errors caught by CLI11 itself (unknown option): non-zero exit, no output.
  const CommandRun unknown = run_cushion("point -m " + material + " --hold 2 --bogus -o " + out);
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("--bogus"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

TEST(CliPoint, GoodRunWritesTheDocumentedCsv) {
  const fs::path dir = scratch_dir();
  const fs::path out = dir / "nested" / "cube.csv";
  const CommandRun run = run_cushion("point -m " + material + " --mode uniaxial_free --ramp=-0.5,5,50 --hold 1,10 --ramp 0,5,50 "
                              "--sine 0.01,2,1,16 -o " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(out.string()), std::string::npos) << "the summary names the output file";
  const cushion::CsvTable t = cushion::read_csv(out);
  const std::vector<std::string> header = {"time_s", "control", "stretch_1", "stretch_2", "stretch_3", "F12", "J", "P11_kPa",
                                           "P22_kPa", "P33_kPa", "P12_kPa", "sigma11_kPa", "sigma22_kPa", "sigma33_kPa",
                                           "sigma12_kPa", "in_contact"};
  EXPECT_EQ(t.columns, header);
  ASSERT_EQ(t.rows(), 1u + 50u + 10u + 50u + 16u);  // segments in the order typed
  EXPECT_NEAR(t.col("time_s").back(), 11.5, 1e-12);
  EXPECT_NEAR(t.col("control")[50], -0.5, 1e-15);
  EXPECT_NEAR(t.col("stretch_1")[50], 0.5, 1e-15);
  EXPECT_LT(t.col("P11_kPa")[50], -1.0);  // compression is negative, in kPa
  EXPECT_NEAR(t.col("J")[50], 0.5, 1e-12);  // nu = 0: no lateral strain
  for (double c : t.col("in_contact")) EXPECT_EQ(c, 1.0);

  // The same history from a protocol file gives the same table.
  const fs::path protocol = dir / "protocol.json";
  std::ofstream(protocol) << R"({"segments": [{"ramp": {"target": -0.5, "duration_s": 5, "steps": 50}},
    {"hold": {"duration_s": 1, "steps": 10}}, {"ramp": {"target": 0, "duration_s": 5, "steps": 50}},
    {"sine": {"amplitude": 0.01, "frequency_Hz": 2, "cycles": 1, "steps_per_cycle": 16}}]})";
  const fs::path out2 = dir / "cube2.csv";
  ASSERT_EQ(run_cushion("point -m " + material + " --protocol " + quoted(protocol) + " -o " + quoted(out2)).exit_code, 0);
  const cushion::CsvTable t2 = cushion::read_csv(out2);
  EXPECT_EQ(t2.data, t.data);
}
