#include "io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "io/input_error.hpp"
#include "io/text_support.hpp"

namespace cushion {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();  // trailing empty cell
  return cells;
}

bool is_blank_or_comment(const std::string& line) {
  const std::string t = trim(line);
  return t.empty() || t.front() == '#';
}

std::string where(const std::string& source, std::size_t line) {
  return source + ":" + std::to_string(line);
}

}  // namespace

bool CsvTable::has(const std::string& column) const {
  return std::find(columns.begin(), columns.end(), column) != columns.end();
}

const std::vector<double>& CsvTable::col(const std::string& column) const {
  const auto it = std::find(columns.begin(), columns.end(), column);
  if (it == columns.end())
    throw InputError(source + ": no column '" + column + "'" + io::did_you_mean(column, columns));
  return data[static_cast<std::size_t>(it - columns.begin())];
}

CsvTable read_csv(const std::filesystem::path& file) {
  CsvTable table;
  table.source = file.string();
  io::require_readable_file(file, "CSV file");
  std::ifstream in(file);
  if (!in) throw InputError(table.source + ": cannot open file");

  std::string line;
  std::size_t line_number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (is_blank_or_comment(line)) continue;
    const std::vector<std::string> cells = split_cells(line);
    if (!have_header) {
      std::set<std::string> seen;
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::string at = where(table.source, line_number) + ", column " + std::to_string(c + 1);
        if (cells[c].empty()) throw InputError(at + ": empty column name in the header");
        if (!seen.insert(cells[c]).second) throw InputError(at + ": duplicate column '" + cells[c] + "'");
      }
      for (const auto& name : cells) {
        double ignored = 0.0;
        const auto [ptr, ec] = std::from_chars(name.data(), name.data() + name.size(), ignored);
        if (ec == std::errc{} && ptr == name.data() + name.size())
          throw InputError(where(table.source, line_number) + ": the first line must be a header of column names, found the number '" + name + "'");
      }
      table.columns = cells;
      table.data.assign(cells.size(), {});
      have_header = true;
      continue;
    }
    if (cells.size() != table.columns.size())
      throw InputError(where(table.source, line_number) + ": expected " + std::to_string(table.columns.size()) +
                       " cells (as in the header), found " + std::to_string(cells.size()));
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string& text = cells[c];
      double value = 0.0;
      const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      const std::string at = where(table.source, line_number) + ", column " + std::to_string(c + 1) + " (" + table.columns[c] + ")";
      if (text.empty()) throw InputError(at + ": empty cell");
      if (ec != std::errc{} || ptr != text.data() + text.size())
        throw InputError(at + ": '" + text + "' is not a number");
      if (!std::isfinite(value)) throw InputError(at + ": '" + text + "' is not a finite number");
      table.data[c].push_back(value);
    }
  }
  if (!have_header) throw InputError(table.source + ": empty file (no header line)");
  if (table.rows() == 0) throw InputError(table.source + ": no data rows after the header");
  return table;
}

std::size_t require_columns(const CsvTable& table, const std::vector<std::vector<std::string>>& accepted) {
  std::vector<std::size_t> matching;
  for (std::size_t s = 0; s < accepted.size(); ++s)
    if (std::all_of(accepted[s].begin(), accepted[s].end(), [&](const std::string& c) { return table.has(c); }))
      matching.push_back(s);
  if (matching.size() == 1) return matching.front();

  auto describe_set = [](const std::vector<std::string>& set) {
    std::string text = "{";
    text += io::join(set, ", ");
    return text += "}";
  };
  std::vector<std::string> set_texts;
  for (const auto& set : accepted) set_texts.push_back(describe_set(set));
  const std::string sets = io::join(set_texts, " or ");
  if (matching.size() > 1)
    throw InputError(table.source + ": ambiguous columns: they match both " + describe_set(accepted[matching[0]]) +
                     " and " + describe_set(accepted[matching[1]]));

  std::vector<std::string> known;
  for (const auto& set : accepted) known.insert(known.end(), set.begin(), set.end());
  std::vector<std::string> unknown;
  for (const auto& column : table.columns)
    if (std::find(known.begin(), known.end(), column) == known.end())
      unknown.push_back("'" + column + "'" + io::did_you_mean(column, known));
  // Name what is missing from the accepted set the table comes closest to.
  std::size_t nearest = 0, most_present = 0;
  for (std::size_t s = 0; s < accepted.size(); ++s) {
    const auto present = static_cast<std::size_t>(
        std::count_if(accepted[s].begin(), accepted[s].end(), [&](const std::string& c) { return table.has(c); }));
    if (present > most_present) nearest = s, most_present = present;
  }
  std::vector<std::string> missing;
  if (!accepted.empty())
    for (const auto& c : accepted[nearest])
      if (!table.has(c)) missing.push_back("'" + c + "'");
  throw InputError(table.source + ": missing column(s) " + io::join(missing, ", ") + " (expected the columns " + sets +
                   ")" + (unknown.empty() ? std::string{} : "; unknown column(s) " + io::join(unknown, ", ")));
}

void write_csv(const std::filesystem::path& file, const std::vector<std::string>& columns,
               const std::vector<std::vector<double>>& data, const std::vector<std::string>& comment) {
  if (columns.size() != data.size())
    throw std::invalid_argument("write_csv: " + std::to_string(columns.size()) + " column names for " +
                                std::to_string(data.size()) + " columns");
  const std::size_t rows = data.empty() ? 0 : data.front().size();
  for (const auto& column : data)
    if (column.size() != rows) throw std::invalid_argument("write_csv: columns of different lengths");

  std::string text;
  for (const auto& line : comment) text += "# " + line + "\n";
  text += io::join(columns, ",") + "\n";
  std::vector<std::string> cells(columns.size());
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) cells[c] = io::format_double(data[c][r]);
    text += io::join(cells, ",") + "\n";
  }
  io::write_file_atomically(file, text);
}

}  // namespace cushion
