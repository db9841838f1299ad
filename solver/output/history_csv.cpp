#include "solver/output/history_csv.hpp"

#include <stdexcept>

#include "io/text_support.hpp"

namespace cushion::solver {

HistoryWriter::HistoryWriter(const std::filesystem::path& file, std::vector<std::string> columns,
                             const std::vector<std::string>& comment)
    : file_(file), columns_(std::move(columns)) {
  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path());
  out_.open(file, std::ios::trunc);
  if (!out_) throw std::runtime_error(file.string() + ": cannot open the history file for writing");
  for (const std::string& line : comment) out_ << "# " << line << '\n';
  out_ << "time_s";
  for (const std::string& c : columns_) {
    if (c.find_first_of(",\n\"") != std::string::npos)
      throw std::invalid_argument("HistoryWriter: column name '" + c + "' contains a comma, quote or newline");
    out_ << ',' << c;
  }
  out_ << '\n' << std::flush;
}

HistoryWriter::HistoryWriter(std::vector<std::string> columns) : columns_(std::move(columns)) {}

void HistoryWriter::write_row(double time, std::span<const double> values) {
  if (values.size() != columns_.size())
    throw std::invalid_argument("HistoryWriter::write_row: " + std::to_string(values.size()) + " values for " +
                                std::to_string(columns_.size()) + " columns");
  if (file_.empty()) return;  // a writer of a process that writes nothing
  out_ << io::format_double(time);
  for (double v : values) out_ << ',' << io::format_double(v);
  out_ << '\n' << std::flush;
  if (!out_) throw std::runtime_error(file_.string() + ": write failed");
}

}  // namespace cushion::solver
