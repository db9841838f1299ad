#pragma once
/// History output: a CSV table "time_s,<column>,..." (units in the column names, e.g. "top.U3_mm",
/// "top.RF3_N"), one row per converged increment, flushed after every row so that an interrupted run
/// leaves every completed row on disk. Readable by cushion::read_csv (io/csv.hpp).
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace cushion::solver {

class HistoryWriter {
 public:
  /// Creates (truncates) `file` and writes the `comment` lines as "# ..." then the header.
  /// std::runtime_error if the file cannot be opened.
  HistoryWriter(const std::filesystem::path& file, std::vector<std::string> columns,
                const std::vector<std::string>& comment = {});
  /// A writer that checks its rows and writes nothing (the processes of a distributed run that do not
  /// write files).
  explicit HistoryWriter(std::vector<std::string> columns);

  /// Appends one row: time [s] then `values` (same order and count as the columns), exact
  /// shortest round-trip decimal text; flushed. std::invalid_argument on a count mismatch.
  void write_row(double time, std::span<const double> values);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::ofstream out_;
};

}  // namespace cushion::solver
