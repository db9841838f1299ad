#pragma once
/// Report plots through gnuplot (Debian gnuplot-nox): every plot is a CSV of its data (long format
/// "series,x,y", series numbered in the order of Plot::series), a gnuplot script (.gp) that reads it,
/// and, when gnuplot is available, the PNG it draws (pngcairo terminal if gnuplot has it, else png).
/// No drawing code here: the script is the plot.
#include <filesystem>
#include <string>
#include <vector>

namespace cushion::calibration {

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  bool points = false;  ///< points (measured data) instead of lines (models)
  bool y2 = false;      ///< plotted against the right axis
};

struct Plot {
  std::string name;  ///< file stem: name.csv, name.gp, name.png
  std::string title, xlabel, ylabel, y2label;
  std::string x_column = "x", y_column = "y";  ///< CSV column names with units, e.g. "strain", "stress_kPa"
  std::vector<PlotSeries> series;
};

struct PlotFiles {
  std::filesystem::path csv, script, png;
  bool drawn = false;   ///< gnuplot ran and the PNG exists
  std::string message;  ///< why not drawn
};

/// Writes dir/name.csv and dir/name.gp (nothing drawn yet).
PlotFiles write_plot(const Plot& plot, const std::filesystem::path& dir);

/// Runs `gnuplot` (an executable path; empty: nothing drawn, message says how to draw) once on all the
/// scripts, in `dir`, and sets drawn/message of each.
void draw_plots(std::vector<PlotFiles>& plots, const std::filesystem::path& dir, const std::string& gnuplot);

/// The gnuplot executable: `preferred` if it names an executable file, else "gnuplot" found on PATH,
/// else empty.
std::string find_gnuplot(const std::string& preferred = "");

}  // namespace cushion::calibration
