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

std::string fixed_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

/// Error/noise per test (lines with markers) against the run, tics labelled with each run's label; the
/// noise level (1) and the "at noise level" limit of compare/diagnose as dashed lines over a shaded band.
Plot history_plot(const std::vector<HistoryRow>& rows) {
  Plot plot;
  plot.name = "history_plot";
  plot.title = "Model error per test across model versions (error/noise; lower is better, 1 = measurement noise)";
  plot.xlabel = "model version (run number: label, as in history.csv)";
  plot.ylabel = "RMS error / measurement noise [-]";
  plot.x_column = "run";
  plot.y_column = "error_over_noise";
  std::map<std::string, std::size_t> index;
  std::map<int, std::string> labels;
  for (const auto& r : rows) {
    if (!index.count(r.test)) {
      index[r.test] = plot.series.size();
      plot.series.push_back({r.test, {}, {}});
      plot.series.back().markers = true;
    }
    plot.series[index[r.test]].x.push_back(r.run);
    plot.series[index[r.test]].y.push_back(r.error_over_noise);
    labels[r.run] = r.label;
  }
  for (const auto& [run, label] : labels) plot.xtics.push_back({run, std::to_string(run) + ": " + label});
  const double at_noise = CompareOptions().noise_level_ratio;
  plot.bands.push_back({0.0, at_noise, "#e3f2e3", "at the noise level (error/noise <= " + fixed_text(at_noise) + ")"});
  plot.levels.push_back({1.0, "error = noise"});
  plot.levels.push_back({at_noise, "error = " + fixed_text(at_noise) + " x noise"});
  return plot;
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
  std::vector<PlotFiles> files{write_plot(history_plot(rows), dir)};
  draw_plots(files, dir, gnuplot);
  return run;
}

}  // namespace cushion::calibration
