// CSV tables: round trip, atomic writes and every malformed-input case naming file, line and column.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <fstream>

#include "io/input_error.hpp"
#include "io/csv.hpp"
#include "io/json_reader.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_csv_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                                    "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(dir);
  return dir;
}

fs::path write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

/// The InputError message of reading `text` as a CSV (empty if it reads fine).
std::string read_error(const std::string& text, const std::string& name = "table.csv") {
  const fs::path file = write_text(scratch_dir() / name, text);
  try {
    cushion::read_csv(file);
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return {};
}

void expect_contains(const std::string& message, const std::vector<std::string>& parts) {
  for (const auto& p : parts) EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

}  // namespace

TEST(Csv, RoundTripIsExactAndAtomic) {
  const fs::path file = scratch_dir() / "sub" / "out.csv";  // the writer creates missing folders
  const std::vector<std::string> columns = {"time_s", "displacement_mm", "force_N"};
  const std::vector<std::vector<double>> data = {{0.0, 0.1, 1.0 / 3.0}, {-1e-300, 2.5, 1e22}, {std::numbers::pi, -0.0, 123456789.123456789}};
  cushion::write_csv(file, columns, data, {"a comment line"});
  for (const auto& entry : fs::directory_iterator(file.parent_path()))  // no temporary left behind
    EXPECT_EQ(entry.path().filename(), "out.csv");
  const cushion::CsvTable t = cushion::read_csv(file);
  EXPECT_EQ(t.columns, columns);
  ASSERT_EQ(t.rows(), 3u);
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t r = 0; r < 3; ++r) EXPECT_EQ(t.data[c][r], data[c][r]);  // shortest round-trip text: exact
  EXPECT_EQ(&t.col("force_N"), &t.data[2]);
  EXPECT_TRUE(t.has("time_s"));
  EXPECT_FALSE(t.has("time"));
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# a comment line");
  EXPECT_THROW(cushion::write_csv(file, columns, {{1.0}, {2.0}}), std::invalid_argument);
}

TEST(Csv, CommentsBlankLinesAndSpacesAreAccepted) {
  const fs::path file = write_text(scratch_dir() / "ok.csv", "# test\n time_s , force_N \r\n\n0, 1.5\r\n# mid\n1,2e3\n");
  const cushion::CsvTable t = cushion::read_csv(file);
  EXPECT_EQ(t.columns, (std::vector<std::string>{"time_s", "force_N"}));
  EXPECT_EQ(t.col("force_N"), (std::vector<double>{1.5, 2000.0}));
}

TEST(Csv, MalformedInputNamesFileLineAndColumn) {
  expect_contains(read_error("time_s,force_N\n0,1\n1,abc\n", "bad.csv"), {"bad.csv:3", "column 2", "force_N", "abc"});
  expect_contains(read_error("time_s,force_N\n0,nan\n"), {"table.csv:2", "column 2", "not a finite number"});
  expect_contains(read_error("time_s,force_N\n0,inf\n"), {"table.csv:2", "column 2", "finite"});
  expect_contains(read_error("time_s,force_N\n0,1\n1\n"), {"table.csv:3", "expected 2 cells", "found 1"});
  expect_contains(read_error("time_s,force_N\n0,\n"), {"table.csv:2", "column 2", "empty cell"});
  expect_contains(read_error("time_s,time_s\n0,1\n"), {"table.csv:1", "column 2", "duplicate"});
  expect_contains(read_error("0,1\n2,3\n"), {"table.csv:1", "header"});
  expect_contains(read_error("# only a comment\n"), {"table.csv", "empty file"});
  expect_contains(read_error("time_s,force_N\n"), {"table.csv", "no data rows"});
  expect_contains(read_error("time_s,force_N\n0,1 2\n"), {"table.csv:2", "column 2"});
  try {
    cushion::read_csv(scratch_dir() / "missing.csv");
    FAIL();
  } catch (const cushion::InputError& e) {
    expect_contains(e.what(), {"missing.csv", "no such file"});
  }
  try {  // a folder where a file belongs
    cushion::read_csv(scratch_dir());
    FAIL();
  } catch (const cushion::InputError& e) {
    expect_contains(e.what(), {"is a folder, not a CSV file"});
  }
}

TEST(Csv, RequireColumnsSuggestsTheClosestName) {
  const fs::path file = write_text(scratch_dir() / "cols.csv", "time_s,displacment_mm,force_N\n0,1,2\n");
  const cushion::CsvTable t = cushion::read_csv(file);
  const std::vector<std::vector<std::string>> accepted = {{"time_s", "displacement_mm", "force_N"}, {"time_s", "strain", "stress_kPa"}};
  try {
    cushion::require_columns(t, accepted);
    FAIL();
  } catch (const cushion::InputError& e) {
    expect_contains(e.what(), {"cols.csv", "missing column(s) 'displacement_mm'", "'displacment_mm'",
                               "did you mean 'displacement_mm'", "{time_s, strain, stress_kPa}"});
  }
  try {
    t.col("forces_N");
    FAIL();
  } catch (const cushion::InputError& e) {
    expect_contains(e.what(), {"cols.csv", "forces_N", "did you mean 'force_N'"});
  }
  const fs::path good = write_text(scratch_dir() / "good.csv", "time_s,strain,stress_kPa,extra\n0,1,2,3\n");
  EXPECT_EQ(cushion::require_columns(cushion::read_csv(good), accepted), 1u);
  const fs::path both = write_text(scratch_dir() / "both.csv", "time_s,strain,stress_kPa,displacement_mm,force_N\n0,1,2,3,4\n");
  EXPECT_THROW(cushion::require_columns(cushion::read_csv(both), accepted), cushion::InputError);  // ambiguous
}

// Fuzzing finding (issue 16): a syntax error after a long string overflowed the stack in the error
// location code (recursive std::regex); it must be an InputError naming the file, line and last key.
TEST(JsonReader, SyntaxErrorAfterALongStringIsAnInputError) {
  const std::string text = "{\"description\": \"" + std::string(200000, 'x') + "\", \"mu_kPa\": 1,, }";
  try {
    cushion::io::parse_json(text, "long.json");
    FAIL() << "accepted malformed JSON";
  } catch (const cushion::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("long.json:1:", 0), 0u) << message;
    EXPECT_NE(message.find("mu_kPa"), std::string::npos) << message;
  }
}
