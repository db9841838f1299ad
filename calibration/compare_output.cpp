#include "calibration/compare_output.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "calibration/plot.hpp"
#include "io/csv.hpp"

#include "io/text_support.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

/// The region with the largest error in noise units (or largest NRMSE when the noise is unknown).
const RegionError* worst_region(const TestCompare& t) {
  const RegionError* worst = nullptr;
  for (const auto& r : t.regions) {
    if (r.region.rfind("all", 0) == 0 || r.region == "hysteresis_area") continue;
    const double v = r.noise > 0.0 ? r.ratio() : r.nrmse;
    if (!worst || v > (worst->noise > 0.0 ? worst->ratio() : worst->nrmse)) worst = &r;
  }
  return worst;
}

/// How a test kind is shown: the scale from internal units to the reported unit, axis labels, CSV columns.
struct Presentation {
  double scale;                      ///< reported = internal x scale
  std::string x_label, y_label;      ///< plot axes (curves: y; spectra: the amplitude)
  std::vector<std::string> columns;  ///< CSV header
};

Presentation presentation(const TestCompare& t) {
  if (t.kind == "quasi_static")
    return {1000.0, "nominal strain [-]", "nominal stress [kPa]",
            {"strain", "measured_kPa", "model_kPa", "residual_kPa", "noise_kPa"}};
  if (t.kind == "indentation")
    return {1.0, "indentation [mm]", "force [N]",
            {"indentation_mm", "measured_force_N", "model_force_N", "residual_force_N", "noise_force_N"}};
  if (t.kind == "dynamic_stiffness")
    return {1.0, "frequency [Hz]", "|K*| [N/mm]",
            {"frequency_Hz", "measured_stiffness_N_per_mm", "model_stiffness_N_per_mm", "residual_stiffness_N_per_mm",
             "measured_phase_deg", "model_phase_deg", "residual_phase_deg", "noise_stiffness_N_per_mm", "noise_phase_deg"}};
  return {1000.0, "frequency [Hz]", "|E*| [kPa]",
          {"frequency_Hz", "measured_modulus_kPa", "model_modulus_kPa", "residual_modulus_kPa", "measured_phase_deg",
           "model_phase_deg", "residual_phase_deg", "noise_modulus_kPa", "noise_phase_deg"}};
}

/// Two-panel gnuplot script: curves on top, residuals with the noise band below; keys right of the panels, the
/// x range that of the data.
std::string two_panel_script(const TestCompare& t, const std::string& csv, const std::string& png) {
  std::ostringstream g;
  const Presentation p = presentation(t);
  const std::string a = p.y_label.substr(0, p.y_label.find(' '));  // "|E*|" or "|K*|"
  g << "# " << t.name << ": model vs measurement (top) and residual model - measured (bottom); data in " << csv << "\n";
  g << "reset\nif (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size 1200,800 enhanced font 'sans,11'\n"
    << "} else {\n  set terminal png size 1200,800\n}\n";
  g << "set output '" << png << "'\nset datafile separator comma\nset grid\n"
    << "set key outside right top vertical Left reverse noenhanced\nset lmargin 12\n";
  const bool log_x = !t.is_curve();
  g << "set rmargin " << (log_x ? 50 : 24) << "\n";  // the key, and on spectra the phase axis
  if (log_x) g << "set logscale x\n";
  if (!t.x.empty()) g << gnuplot_xrange(*std::min_element(t.x.begin(), t.x.end()), *std::max_element(t.x.begin(), t.x.end()), log_x);
  g << "set multiplot layout 2,1 title " << gnuplot_literal(t.name + " (" + t.use + "): model vs measurement, error " +
                                                             fixed(t.noise_ratio(), 2) + " x noise")
    << " noenhanced\n";
  if (t.is_curve()) {
    g << "set xlabel '" << p.x_label << "'\nset ylabel '" << p.y_label << "'\n";
    g << "plot '" << csv << "' skip 1 using 1:2 with points pt 7 ps 0.4 title 'measured', \\\n"
      << "     '' skip 1 using 1:3 with lines lw 2 title 'model'\n";
    g << "set ylabel 'residual " << p.y_label.substr(p.y_label.find('[')) << "'\n";
    g << "plot '" << csv << "' skip 1 using 1:4 with points pt 7 ps 0.4 title 'model - measured', \\\n"
      << "     '' skip 1 using 1:5 with lines dt 2 lc rgb 'gray40' title '+-1 noise', \\\n"
      << "     '' skip 1 using 1:(-$5) with lines dt 2 lc rgb 'gray40' notitle\n";
  } else {
    g << "set xlabel '" << p.x_label << "'\nset ylabel '" << p.y_label << "' noenhanced\nset y2label 'phase [deg]'\n"
      << "set ytics nomirror\nset y2tics\n";
    g << "plot '" << csv << "' skip 1 using 1:2 with points pt 7 title '" << a << " measured' noenhanced, \\\n"
      << "     '' skip 1 using 1:3 with lines lw 2 title '" << a << " model' noenhanced, \\\n"
      << "     '' skip 1 using 1:5 axes x1y2 with points pt 6 title 'phase measured (right axis)', \\\n"
      << "     '' skip 1 using 1:6 axes x1y2 with lines lw 2 dt 3 title 'phase model (right axis)'\n";
    g << "set ylabel 'residual " << p.y_label << "' noenhanced\nset y2label 'residual phase [deg]'\n";
    g << "plot '" << csv << "' skip 1 using 1:4 with linespoints pt 7 title '" << a << " model - measured' noenhanced, \\\n"
      << "     '' skip 1 using 1:8 with lines dt 2 lc rgb 'gray40' title '+-1 noise " << a << "' noenhanced, \\\n"
      << "     '' skip 1 using 1:(-$8) with lines dt 2 lc rgb 'gray40' notitle, \\\n"
      << "     '' skip 1 using 1:7 axes x1y2 with linespoints pt 6 title 'phase model - measured (right axis)', \\\n"
      << "     '' skip 1 using 1:9 axes x1y2 with lines dt 3 lc rgb 'gray70' title '+-1 noise phase (right axis)', \\\n"
      << "     '' skip 1 using 1:(-$9) axes x1y2 with lines dt 3 lc rgb 'gray70' notitle\n";
  }
  g << "unset multiplot\n";
  return g.str();
}

PlotFiles write_test_plot(const TestCompare& t, const fs::path& dir) {
  const std::string stem = "compare_" + t.name;
  PlotFiles f{dir / (stem + ".csv"), dir / (stem + ".gp"), dir / (stem + ".png"), false, ""};
  const Presentation p = presentation(t);
  const std::size_t n = t.x.size();
  std::vector<double> m(n), d(n), r(n);
  for (std::size_t i = 0; i < n; ++i) m[i] = t.measured[i] * p.scale, d[i] = t.model[i] * p.scale, r[i] = d[i] - m[i];
  if (t.is_curve()) {
    std::vector<double> s(n, 0.0);
    for (std::size_t i = 0; i < n && i < t.noise_local.size(); ++i) s[i] = t.noise_local[i] * p.scale;
    write_csv(f.csv, p.columns, {t.x, m, d, r, s},
              {"cushion compare: " + t.name + (t.kind == "quasi_static" ? " (nominal, compression positive)" : " (compression positive)")});
  } else {
    std::vector<double> rp(n), sn(n, t.noise.modulus * p.scale), sp(n, t.noise.phase);
    for (std::size_t i = 0; i < n; ++i) rp[i] = t.model_phase[i] - t.measured_phase[i];
    for (std::size_t i = 0; i < n && i < t.noise.modulus_local.size(); ++i) sn[i] = t.noise.modulus_local[i] * p.scale;
    for (std::size_t i = 0; i < n && i < t.noise.phase_local.size(); ++i) sp[i] = t.noise.phase_local[i];
    write_csv(f.csv, p.columns, {t.x, m, d, r, t.measured_phase, t.model_phase, rp, sn, sp}, {"cushion compare: " + t.name});
  }
  io::write_file_atomically(f.script, two_panel_script(t, f.csv.filename().string(), f.png.filename().string()));
  return f;
}

}  // namespace

nlohmann::json compare_json(const CompareResult& result, const std::string& label) {
  nlohmann::json j;
  j["label"] = label;
  j["seconds"] = result.seconds;
  j["warnings"] = result.warnings;
  j["tests"] = nlohmann::json::array();
  for (const auto& t : result.tests) {
    nlohmann::json jt{{"name", t.name}, {"kind", t.kind}, {"use", t.use}, {"error_over_noise", t.noise_ratio()}};
    if (t.kind == "quasi_static") {
      jt["rate_mm_min"] = t.rate_mm_min;
      jt["noise_kPa"] = t.noise.stress * 1000.0;
      jt["hysteresis_measured_kPa"] = t.hysteresis_measured * 1000.0;
      jt["hysteresis_model_kPa"] = t.hysteresis_model * 1000.0;
    } else if (t.kind == "indentation") {
      jt["noise_N"] = t.noise.stress;
      jt["hysteresis_measured_N_mm"] = t.hysteresis_measured;
      jt["hysteresis_model_N_mm"] = t.hysteresis_model;
    } else if (t.kind == "dynamic_stiffness") {
      jt["noise_stiffness_N_per_mm"] = t.noise.modulus;
      jt["noise_phase_deg"] = t.noise.phase;
    } else {
      jt["preload_strain"] = t.preload;
      jt["noise_modulus_kPa"] = t.noise.modulus * 1000.0;
      jt["noise_phase_deg"] = t.noise.phase;
      jt["steps_per_cycle"] = t.steps_per_cycle;
      if (t.step_error >= 0.0) jt["step_error_over_noise"] = t.step_error;
    }
    jt["noise_known"] = t.noise.known;
    if (!t.failure.empty()) jt["failure"] = t.failure;
    jt["regions"] = nlohmann::json::array();
    for (const auto& r : t.regions)
      jt["regions"].push_back({{"region", r.region}, {"unit", r.unit}, {"rms", r.rms}, {"bias", r.bias},
                               {"nrmse", r.nrmse}, {"noise", r.noise}, {"error_over_noise", r.ratio()}, {"points", r.points}});
    j["tests"].push_back(jt);
  }
  return j;
}

std::string compare_table(const CompareResult& result) {
  std::ostringstream o;
  o << "| test | kind | use | NRMSE | RMS error | noise | error/noise | worst region |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& t : result.tests) {
    o << "| " << t.name << " | " << t.kind << " | " << t.use << " | ";
    if (!t.failure.empty()) {
      o << "model run failed: " << t.failure << " | | | | |\n";
      continue;
    }
    const RegionError& a = t.regions.front();
    if (t.is_curve()) {
      o << fixed(100.0 * a.nrmse, 2) << "% | " << fixed(a.rms, 3) << " " << a.unit << " | " << fixed(a.noise, 3) << " "
        << a.unit << " | ";
    } else {
      const RegionError& p = t.regions[1];
      o << fixed(100.0 * a.nrmse, 2) << "% | " << fixed(a.rms, 3) << " " << a.unit << ", " << fixed(p.rms, 2) << " deg | "
        << fixed(a.noise, 3) << " " << a.unit << ", " << fixed(p.noise, 2) << " deg | ";
    }
    o << (t.noise.known ? fixed(t.noise_ratio(), 2) : std::string("noise unknown")) << " | ";
    if (const RegionError* w = worst_region(t))
      o << w->region << " (" << fixed(w->rms, 3) << " " << w->unit << (w->noise > 0 ? ", " + fixed(w->ratio(), 1) + "x noise" : "")
        << ")";
    o << " |\n";
  }
  std::string checked;
  for (const auto& t : result.tests)
    if (t.step_error >= 0.0)
      checked += (checked.empty() ? "" : ", ") + t.name + " " + fixed(t.step_error, 2) + "x noise (" +
                 std::to_string(t.steps_per_cycle) + " vs " + std::to_string(t.steps_per_cycle / 2) + " steps a cycle)";
  if (!checked.empty())
    o << "\nTime step of the sweeps: the model's |E*| and phase move by " << checked
      << " when the steps per cycle are halved; for a scheme first order in the step (the dashpot effects) that is "
         "about the error of the sweep at its own step (docs/physics.md 9.39).\n";
  return o.str();
}

std::vector<fs::path> write_compare_outputs(const CompareResult& result, const std::string& label, const fs::path& dir,
                                            const std::string& gnuplot) {
  fs::create_directories(dir);
  io::write_file_atomically(dir / "report.json", compare_json(result, label).dump(2) + "\n");
  std::string summary = "# cushion compare: " + label + "\n\n" + compare_table(result);
  for (const auto& w : result.warnings) summary += "\nwarning: " + w;
  io::write_file_atomically(dir / "summary.md", summary + "\n");
  std::vector<PlotFiles> plots;
  for (const auto& t : result.tests)
    if (t.failure.empty()) plots.push_back(write_test_plot(t, dir));
  draw_plots(plots, dir, gnuplot);
  std::vector<fs::path> drawn;
  for (const auto& p : plots)
    if (p.drawn) drawn.push_back(p.png);
  return drawn;
}

}  // namespace cushion::calibration
