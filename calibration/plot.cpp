#include "calibration/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <unistd.h>

#include "io/csv.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// gnuplot double-quoted string: "\n" starts a new line of a label.
std::string multiline_literal(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '\n' ? std::string("\\n") : c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

bool executable(const fs::path& p) { return !p.empty() && fs::is_regular_file(p) && ::access(p.c_str(), X_OK) == 0; }

/// Colour-blind-safe palette (Okabe-Ito, then greys); series sharing an index share the colour.
const char* colour(int index) {
  static const char* palette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#999999"};
  return palette[static_cast<std::size_t>(index) % (sizeof(palette) / sizeof(palette[0]))];
}

std::string number(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v, bool log) {
    if (std::isfinite(v) && (!log || v > 0.0)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

/// "set yrange" over the data of the first axis and the levels and bands, so that the reference lines show.
std::string yrange_with_levels(const Plot& plot) {
  if (plot.levels.empty() && plot.bands.empty()) return "";
  Range r;
  r.add(0.0, false);
  for (const auto& s : plot.series)
    if (!s.y2)
      for (double v : s.y) r.add(v, false);
  for (const auto& l : plot.levels) r.add(l.y, false);
  for (const auto& b : plot.bands) r.add(b.y1, false);
  return r.empty() ? "" : "set yrange [0:" + number(r.hi * 1.1) + "]\n";
}

std::string xaxis(const Plot& plot) {
  std::ostringstream g;
  if (plot.log_x) g << "set logscale x\n";
  Range r;
  if (!plot.xtics.empty()) {
    for (const auto& t : plot.xtics) r.add(t.first, false);
    g << "set xtics (";
    for (std::size_t i = 0; i < plot.xtics.size(); ++i)
      g << (i ? ", " : "") << gnuplot_literal(plot.xtics[i].second) << " " << number(plot.xtics[i].first);
    g << ") noenhanced\nset xrange [" << number(r.lo - 0.5) << ":" << number(r.hi + 0.5) << "]\n";
    return g.str();
  }
  for (const auto& s : plot.series)
    for (double v : s.x) r.add(v, plot.log_x);
  if (!r.empty()) g << gnuplot_xrange(r.lo, r.hi, plot.log_x);
  return g.str();
}

std::string decorations(const Plot& plot) {
  std::ostringstream g;
  int object = 1;
  for (const auto& b : plot.bands) {
    g << "set object " << object++ << " rect from graph 0, first " << number(b.y0) << " to graph 1, first " << number(b.y1)
      << " fillcolor rgb " << gnuplot_literal(b.colour) << " fillstyle solid 1.0 noborder behind\n";
    if (!b.label.empty())
      g << "set label " << gnuplot_literal(b.label) << " at graph 0.01, first " << number(0.5 * (b.y0 + b.y1))
        << " left front font ',9' noenhanced\n";
  }
  for (const auto& l : plot.levels) {
    g << "set arrow from graph 0, first " << number(l.y) << " to graph 1, first " << number(l.y)
      << " nohead dashtype 2 linewidth 1.5 linecolor rgb '#444444' front\n";
    if (!l.label.empty())
      g << "set label " << gnuplot_literal(l.label) << " at graph 0.99, first " << number(l.y)
        << " right offset 0,0.6 front font ',9' noenhanced\n";
  }
  if (!plot.note.empty())
    g << "set label " << multiline_literal(plot.note) << " at screen 0.01, screen 0.02 left font ',9' noenhanced\n";
  return g.str();
}

/// Measured points are thinned to about 80 per series on the plot (the CSV keeps every point).
std::string thinning(const PlotSeries& s) {
  const std::size_t stride = s.points ? std::max<std::size_t>(1, s.x.size() / 80) : 1;
  return stride > 1 ? " every " + std::to_string(stride) : "";
}

/// Right margin [characters] that holds the key (sample and longest title) and, with a right axis, its tics and label.
int key_margin(const Plot& plot, bool right_axis) {
  std::size_t longest = 0;
  for (const auto& s : plot.series) longest = std::max(longest, s.title.size());
  return static_cast<int>(longest) + 10 + (right_axis ? 10 : 0);
}

/// A long title in two lines, broken after its first ": " (what is plotted, then what it is compared with).
std::string title_text(const std::string& title) {
  const std::size_t colon = title.find(": ");
  if (title.size() <= 80 || colon == std::string::npos) return multiline_literal(title);
  return multiline_literal(title.substr(0, colon + 1) + "\n" + title.substr(colon + 2));
}

std::string style(const PlotSeries& s, std::size_t index) {
  const std::string lc = std::string(" linecolor rgb '") + colour(s.colour >= 0 ? s.colour : static_cast<int>(index)) + "'";
  if (s.points) return " with points pointtype 6 pointsize 0.9" + lc;  // open circles: a model line under them shows
  if (s.markers) return " with linespoints linewidth 2 pointtype 7 pointsize 1 dashtype " + std::to_string(s.dash) + lc;
  return " with lines linewidth 2 dashtype " + std::to_string(s.dash) + lc;
}

/// plot command over the series for which `take` holds (one panel or one axis).
template <class Take>
std::string plot_command(const Plot& plot, const std::string& csv, bool right_axis, Take take) {
  std::ostringstream g;
  std::string sep = "plot \\\n";
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const auto& ser = plot.series[s];
    if (!take(ser)) continue;
    g << sep << "  " << gnuplot_literal(csv) << " skip 1" << thinning(ser) << " using 2:($1==" << s << " ? $3 : 1/0)"
      << (right_axis && ser.y2 ? " axes x1y2" : "") << style(ser, s) << " title " << gnuplot_literal(ser.title)
      << " noenhanced";
    sep = ", \\\n";
  }
  return g.str() + "\n";
}

}  // namespace

std::string gnuplot_literal(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string gnuplot_xrange(double lo, double hi, bool log_x) {
  if (log_x)  // 1-2-5 tics: the log axis labels only the decades otherwise
    return "set xrange [" + number(lo / 1.08) + ":" + number(hi * 1.08) + "]\nset xtics add (0.2, 0.5, 2, 5, 20, 50, 200, 500)\n";
  const double pad = hi > lo ? 0.02 * (hi - lo) : std::max(0.5, 0.05 * std::abs(lo));
  return "set xrange [" + number(lo - pad) + ":" + number(hi + pad) + "]\n";
}

std::string find_gnuplot(const std::string& preferred) {
  if (executable(preferred)) return preferred;
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::istringstream dirs(path);
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && executable(fs::path(d) / "gnuplot")) return (fs::path(d) / "gnuplot").string();
  return "";
}

std::string plot_script(const Plot& plot, const std::string& csv, const std::string& png) {
  bool any_y2 = false;
  for (const auto& s : plot.series) any_y2 = any_y2 || s.y2;
  const bool panels = plot.two_panels && any_y2;
  const int height = (panels ? 860 : 620) + (plot.note.empty() ? 0 : 90);
  std::ostringstream g;
  g << "# " << plot.title << ": data in " << csv << " (series,x,y; series numbered below)\nreset\n";
  g << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size 1100," << height
    << " enhanced font 'sans,11'\n} else {\n  set terminal png size 1100," << height << "\n}\n";
  g << "set output " << gnuplot_literal(png) << "\n";
  g << "set datafile separator comma\nset key outside right top vertical Left reverse noenhanced\nset grid\n";
  g << "set lmargin 12\nset rmargin " << key_margin(plot, any_y2 && !panels) << "\n";
  if (!plot.note.empty()) g << "set bmargin " << 4 + 1 + std::count(plot.note.begin(), plot.note.end(), '\n') << "\n";
  g << xaxis(plot) << decorations(plot) << yrange_with_levels(plot);
  g << "set xlabel " << gnuplot_literal(plot.xlabel) << " noenhanced\nset ylabel " << gnuplot_literal(plot.ylabel) << " noenhanced\n";
  if (panels) {
    g << "set multiplot layout 2,1 title " << title_text(plot.title) << " noenhanced\n";
    g << plot_command(plot, csv, false, [](const PlotSeries& s) { return !s.y2; });
    g << "set ylabel " << gnuplot_literal(plot.y2label) << " noenhanced\nunset label\n";
    g << plot_command(plot, csv, false, [](const PlotSeries& s) { return s.y2; });
    g << "unset multiplot\n";
    return g.str();
  }
  g << "set title " << title_text(plot.title) << " noenhanced\n";
  if (any_y2) g << "set y2label " << gnuplot_literal(plot.y2label) << " noenhanced\nset ytics nomirror\nset y2tics\n";
  g << plot_command(plot, csv, true, [](const PlotSeries&) { return true; });
  return g.str();
}

PlotFiles write_plot(const Plot& plot, const fs::path& dir) {
  PlotFiles files{dir / (plot.name + ".csv"), dir / (plot.name + ".gp"), dir / (plot.name + ".png"), false, ""};
  std::vector<double> series, x, y;
  for (std::size_t s = 0; s < plot.series.size(); ++s)
    for (std::size_t i = 0; i < plot.series[s].x.size(); ++i) {
      series.push_back(static_cast<double>(s));
      x.push_back(plot.series[s].x[i]);
      y.push_back(plot.series[s].y[i]);
    }
  write_csv(files.csv, {"series", plot.x_column, plot.y_column}, {series, x, y});
  std::ofstream out(files.script);
  out << plot_script(plot, files.csv.filename().string(), files.png.filename().string());
  if (!out) throw std::runtime_error(files.script.string() + ": cannot write");
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
