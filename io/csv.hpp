#pragma once
/// CSV tables whose header names carry the units (e.g. "time_s,displacement_mm,force_N").
/// Reading validates: header present, required columns present (misspelt ones reported with the
/// closest known name), every cell a finite number; errors are InputError naming file, line, column.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cushion {

struct CsvTable {
  std::string source;                           ///< file name, for messages
  std::vector<std::string> columns;             ///< header order
  std::vector<std::vector<double>> data;        ///< data[column][row]
  std::size_t rows() const { return data.empty() ? 0 : data.front().size(); }
  bool has(const std::string& column) const;
  const std::vector<double>& col(const std::string& column) const;  ///< throws InputError if absent
};

/// Reads a CSV file. Lines starting with '#' are comments. Throws InputError on any problem,
/// including an empty file or a table with no data rows.
CsvTable read_csv(const std::filesystem::path& file);

/// Requires that the table has exactly one of the given column sets; returns its index. Throws an
/// InputError listing the accepted sets and naming unknown columns otherwise.
std::size_t require_columns(const CsvTable& table, const std::vector<std::vector<std::string>>& accepted);

/// Writes columns (all of equal length) atomically: to a temporary then renamed. `comment` lines
/// (without '#') are written first as "# ..." lines.
void write_csv(const std::filesystem::path& file, const std::vector<std::string>& columns,
               const std::vector<std::vector<double>>& data, const std::vector<std::string>& comment = {});

}  // namespace cushion
