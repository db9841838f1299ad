#include "calibration/plot.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io/csv.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

/// gnuplot string literal (single quotes; a quote is doubled).
std::string literal(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool executable(const fs::path& p) { return !p.empty() && fs::is_regular_file(p) && ::access(p.c_str(), X_OK) == 0; }

}  // namespace

std::string find_gnuplot(const std::string& preferred) {
  if (executable(preferred)) return preferred;
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::istringstream dirs(path);
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && executable(fs::path(d) / "gnuplot")) return (fs::path(d) / "gnuplot").string();
  return "";
}

PlotFiles write_plot(const Plot& plot, const fs::path& dir) {
  PlotFiles files{dir / (plot.name + ".csv"), dir / (plot.name + ".gp"), dir / (plot.name + ".png")};
  std::vector<double> series, x, y;
  for (std::size_t s = 0; s < plot.series.size(); ++s)
    for (std::size_t i = 0; i < plot.series[s].x.size(); ++i) {
      series.push_back(static_cast<double>(s));
      x.push_back(plot.series[s].x[i]);
      y.push_back(plot.series[s].y[i]);
    }
  write_csv(files.csv, {"series", plot.x_column, plot.y_column}, {series, x, y});

  std::ostringstream g;
  g << "# " << plot.title << ": data in " << files.csv.filename().string() << " (series,x,y; series numbered below)\n";
  g << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size 900,600 enhanced font 'sans,11'\n"
    << "} else {\n  set terminal png size 900,600\n}\n";
  g << "set output " << literal(files.png.filename().string()) << "\n";
  g << "set datafile separator comma\nset key outside bottom center horizontal\nset grid\n";
  g << "set title " << literal(plot.title) << " noenhanced\n";
  g << "set xlabel " << literal(plot.xlabel) << " noenhanced\nset ylabel " << literal(plot.ylabel) << " noenhanced\n";
  bool any_y2 = false;
  for (const auto& s : plot.series) any_y2 = any_y2 || s.y2;
  if (any_y2) g << "set y2label " << literal(plot.y2label) << " noenhanced\nset ytics nomirror\nset y2tics\n";
  g << "plot \\\n";
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const auto& ser = plot.series[s];
    g << "  " << literal(files.csv.filename().string()) << " skip 1 using 2:($1==" << s << " ? $3 : 1/0)"
      << (ser.y2 ? " axes x1y2" : "") << (ser.points ? " with points pt 7 ps 0.6" : " with lines lw 2")
      << " title " << literal(ser.title) << " noenhanced" << (s + 1 < plot.series.size() ? ", \\\n" : "\n");
  }
  {
    std::ofstream out(files.script);
    out << g.str();
    if (!out) throw std::runtime_error(files.script.string() + ": cannot write");
  }
  return files;
}

void draw_plots(std::vector<PlotFiles>& plots, const fs::path& dir, const std::string& gnuplot) {
  if (plots.empty()) return;
  if (gnuplot.empty()) {
    for (auto& p : plots) p.drawn = false, p.message = "gnuplot not found: run `gnuplot " + p.script.filename().string() + "` in " + dir.string();
    return;
  }
  std::string cmd = "cd " + shell_quoted(dir.string()) + " && " + shell_quoted(gnuplot);
  for (const auto& p : plots) cmd += " " + shell_quoted(p.script.filename().string());
  cmd += " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  for (auto& p : plots) {
    p.drawn = rc == 0 && fs::exists(p.png) && fs::file_size(p.png) > 0;
    if (!p.drawn) p.message = "gnuplot failed (exit " + std::to_string(rc) + ") on " + p.script.filename().string();
  }
}

}  // namespace cushion::calibration
