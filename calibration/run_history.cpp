#include "calibration/run_history.hpp"

#include <fstream>
#include <map>
#include <sstream>

#include "calibration/plot.hpp"
#include "io/input_error.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {
const char* kHeader = "run,label,test,kind,use,nrmse,error_over_noise";

/// Labels and names are written without commas or newlines.
std::string clean(std::string s) {
  for (char& c : s)
    if (c == ',' || c == '\n' || c == '\r') c = ' ';
  return s;
}
}  // namespace

std::vector<HistoryRow> read_history(const fs::path& dir) {
  const fs::path file = dir / "history.csv";
  std::vector<HistoryRow> rows;
  std::ifstream in(file);
  if (!in) return rows;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1) {
      if (line != kHeader) throw InputError(file.string() + ":1: expected header '" + std::string(kHeader) + "'");
      continue;
    }
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (cells.size() != 7) throw InputError(file.string() + ":" + std::to_string(number) + ": expected 7 columns");
    try {
      HistoryRow r{std::stoi(cells[0]), cells[1], cells[2], cells[3], cells[4], std::stod(cells[5]), std::stod(cells[6])};
      rows.push_back(r);
    } catch (const std::exception&) {
      throw InputError(file.string() + ":" + std::to_string(number) + ": run, nrmse and error_over_noise must be numbers");
    }
  }
  return rows;
}

int append_history(const fs::path& dir, const std::string& label, const CompareResult& result, const std::string& gnuplot) {
  fs::create_directories(dir);
  std::vector<HistoryRow> rows = read_history(dir);
  int run = 1;
  for (const auto& r : rows) run = std::max(run, r.run + 1);
  const bool fresh = !fs::exists(dir / "history.csv");
  {
    std::ofstream out(dir / "history.csv", std::ios::app);
    if (fresh) out << kHeader << "\n";
    out.precision(8);
    for (const auto& t : result.tests) {
      const double nrmse = t.regions.empty() ? 0.0 : t.regions.front().nrmse;
      HistoryRow r{run, clean(label), clean(t.name), t.kind, t.use, nrmse, t.noise_ratio()};
      out << r.run << "," << r.label << "," << r.test << "," << r.kind << "," << r.use << "," << r.nrmse << ","
          << r.error_over_noise << "\n";
      rows.push_back(r);
    }
    if (!out) throw std::runtime_error((dir / "history.csv").string() + ": cannot write");
  }
  Plot plot;
  plot.name = "history_plot";
  plot.title = "error per test across model versions (runs: see history.csv labels)";
  plot.xlabel = "run";
  plot.ylabel = "RMS error / measurement noise [-] (1 = noise level)";
  plot.x_column = "run";
  plot.y_column = "error_over_noise";
  std::map<std::string, std::size_t> index;
  for (const auto& r : rows) {
    if (!index.count(r.test)) {
      index[r.test] = plot.series.size();
      plot.series.push_back({r.test, {}, {}, false, false});
    }
    plot.series[index[r.test]].x.push_back(r.run);
    plot.series[index[r.test]].y.push_back(r.error_over_noise);
  }
  std::vector<PlotFiles> files{write_plot(plot, dir)};
  draw_plots(files, dir, gnuplot);
  return run;
}

}  // namespace cushion::calibration
