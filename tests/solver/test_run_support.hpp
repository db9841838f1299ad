#pragma once
/// Helpers for the analysis-driver tests: scratch folders, material and case files written on the
/// fly, running a case through load_case + run_analysis, and reading the history back.
#include <unistd.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/csv.hpp"
#include "solver/analysis/analysis.hpp"

namespace cushion::solver::test {

namespace fs = std::filesystem;

/// An empty folder named after the running test.
inline fs::path scratch_dir(const std::string& tag = "") {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("cushion_h7_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name() + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline fs::path write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

/// The hyperfoam of cases/materials/paper_table3.json with Poisson ratio `nu` on every term;
/// with_prony adds the paper's Table 3 Prony series.
inline std::string foam_json(double nu, bool with_prony) {
  const std::string n = std::to_string(nu);
  std::string text = R"({"name": "foam", "density_kg_m3": 65, "hyperfoam": {"terms": [
      {"mu_kPa": 10.0, "alpha": 10.0, "nu": )" + n + R"(}, {"mu_kPa": 0.1, "alpha": -2.0, "nu": )" + n +
                     R"(}, {"mu_kPa": 0.5, "alpha": 3.0, "nu": )" + n + "}]}";
  if (with_prony)
    text += R"(, "viscoelastic": {"moduli": "long_term", "absolute": {"E_inf_kPa": 3.05, "terms": [
      {"E_kPa": 23.9, "tau_s": 0.01}, {"E_kPa": 19.7, "tau_s": 0.1}, {"E_kPa": 8.99, "tau_s": 1},
      {"E_kPa": 12.4, "tau_s": 10}, {"E_kPa": 8.14, "tau_s": 100}]}})";
  return text + "}";
}

/// Runs a case file silently into `out`.
inline RunSummary run_case(const fs::path& case_file, const fs::path& out) {
  RunOptions options;
  options.output_dir = out;
  options.threads = 2;
  return run_analysis(load_case(case_file), options);
}

inline CsvTable read_history(const fs::path& out) { return read_csv(out / "history.csv"); }

/// y at x = at, linear between the points of (x, y) with x increasing; a test failure if `at` is outside.
inline double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  for (std::size_t i = 1; i < x.size() && i < y.size(); ++i)
    if (x[i - 1] <= at && at <= x[i] && x[i] > x[i - 1])
      return y[i - 1] + (y[i] - y[i - 1]) * (at - x[i - 1]) / (x[i] - x[i - 1]);
  ADD_FAILURE() << at << " outside the table";
  return 0.0;
}

}  // namespace cushion::solver::test
