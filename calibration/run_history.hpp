#pragma once
/// History of `cushion compare` runs: DIR/history.csv gains one row per test per run
///   run,label,test,kind,use,nrmse,error_over_noise
/// (run: 1, 2, ... in order of appending; label: the model version name; nrmse [-] and error/noise [-]
/// as in the compare report), and DIR/history.{csv of the plot,gp,png} plots error/noise per test
/// across the runs (one line per test; the noise level is 1).
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/compare.hpp"

namespace cushion::calibration {

struct HistoryRow {
  int run = 0;
  std::string label, test, kind, use;
  double nrmse = 0.0, error_over_noise = 0.0;
};

/// Rows of DIR/history.csv (empty when absent). Throws InputError naming the file and line on a malformed row.
std::vector<HistoryRow> read_history(const std::filesystem::path& dir);

/// Appends `result` as the next run with `label`, rewrites the history plot (drawn with `gnuplot` when
/// not empty). Returns the run number.
int append_history(const std::filesystem::path& dir, const std::string& label, const CompareResult& result,
                   const std::string& gnuplot);

}  // namespace cushion::calibration
