#pragma once
/// Report plots through gnuplot (Debian gnuplot-nox): every plot is a CSV of its data (long format
/// "series,x,y", series numbered in the order of Plot::series), a gnuplot script (.gp) that reads it,
/// and, when gnuplot is available, the PNG it draws (pngcairo terminal if gnuplot has it, else png).
/// No drawing code here: the script is the plot. Each script starts with `reset`, so several scripts run
/// by one gnuplot process do not inherit each other's axes, ranges or labels.
#include <filesystem>
#include <string>
#include <vector>

namespace cushion::calibration {

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  bool points = false;  ///< points (measured data) instead of lines (models)
  bool y2 = false;      ///< against the right axis, or in the lower panel of a two-panel plot
  int colour = -1;      ///< index into the palette (series sharing a colour belong together); -1: own colour
  int dash = 1;         ///< gnuplot dash type of a line (1 solid, 2 dashed, 3 dotted, ...)
  bool markers = false; ///< lines with a marker at every point
};

/// A horizontal reference line across the plot (e.g. the noise level), dashed, labelled at the right.
struct PlotLevel {
  double y = 0.0;
  std::string label;
};

/// A shaded horizontal band [y0, y1] behind the data, labelled inside at the left.
struct PlotBand {
  double y0 = 0.0, y1 = 0.0;
  std::string colour = "#e8f5e9", label;
};

struct Plot {
  std::string name;  ///< file stem: name.csv, name.gp, name.png
  std::string title, xlabel, ylabel, y2label;
  std::string x_column = "x", y_column = "y";  ///< CSV column names with units, e.g. "strain", "stress_kPa"
  std::vector<PlotSeries> series;
  bool two_panels = false;  ///< y2 series in a lower panel (y axis y2label) instead of on a right axis
  bool log_x = false;       ///< logarithmic x axis; the range is that of the data either way
  std::vector<std::pair<double, std::string>> xtics;  ///< labelled x tics (only these); empty: automatic
  std::vector<PlotLevel> levels;
  std::vector<PlotBand> bands;
  std::string note;  ///< text under the plot (what the figure does and does not compare)
};

struct PlotFiles {
  std::filesystem::path csv, script, png;
  bool drawn = false;   ///< gnuplot ran and the PNG exists
  std::string message;  ///< why not drawn
};

/// Writes dir/name.csv and dir/name.gp (nothing drawn yet).
PlotFiles write_plot(const Plot& plot, const std::filesystem::path& dir);

/// The gnuplot script of `plot` reading `csv` and writing `png` (file names in the script's folder).
std::string plot_script(const Plot& plot, const std::string& csv, const std::string& png);

/// Runs `gnuplot` (an executable path; empty: nothing drawn, message says how to draw) once on all the
/// scripts, in `dir`, and sets drawn/message of each.
void draw_plots(std::vector<PlotFiles>& plots, const std::filesystem::path& dir, const std::string& gnuplot);

/// The gnuplot executable: `preferred` if it names an executable file, else "gnuplot" found on PATH,
/// else empty.
std::string find_gnuplot(const std::string& preferred = "");

/// gnuplot string literal (single quotes; a quote is doubled).
std::string gnuplot_literal(const std::string& s);

/// "set xrange [a:b]" covering [lo, hi] with a margin (2 % of the span, or a factor on a log axis).
std::string gnuplot_xrange(double lo, double hi, bool log_x);

}  // namespace cushion::calibration
