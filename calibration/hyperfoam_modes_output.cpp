#include "calibration/hyperfoam_modes_output.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "calibration/abaqus_cards.hpp"
#include "calibration/fit_model.hpp"
#include "calibration/fit_output.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/output_folder.hpp"
#include "io/text_support.hpp"
#include "material/io/material_file.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::string num(double x, int digits) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream o;
  o << std::setprecision(digits) << x;
  return o.str();
}

std::string percent(double fraction) { return fraction < 0.0 ? "-" : num(100.0 * fraction, 3) + " %"; }

/// Test x axis label: stretch, or gamma for simple shear.
std::string control_name(const HyperfoamTest& t) {
  return t.mode == HyperfoamMode::simple_shear ? "gamma" : "stretch";
}

/// The model on 80 controls spanning the test's range (and the undeformed state).
HyperfoamTest dense_controls(const HyperfoamTest& t) {
  HyperfoamTest d = t;
  const double rest = t.mode == HyperfoamMode::simple_shear ? 0.0 : 1.0;
  double lo = rest, hi = rest;
  for (double x : t.control) lo = std::min(lo, x), hi = std::max(hi, x);
  d.control.clear();
  for (int k = 0; k <= 80; ++k) d.control.push_back(lo + (hi - lo) * k / 80.0);
  if (t.mode != HyperfoamMode::simple_shear)
    for (double& x : d.control) x = std::max(x, 1e-3);
  d.stress.assign(d.control.size(), 0.0);
  d.lateral.clear();
  return d;
}

std::string provenance(const HyperfoamCampaign& c, const HyperfoamModesFit& fit) {
  std::string tests;
  for (const auto& t : c.tests) tests += (tests.empty() ? "" : ", ") + t.name + " (" + to_string(t.mode) + ")";
  return "cushion fit of " + c.manifest.filename().string() + " (hyperfoam-only campaign: " + tests + "), N = " +
         std::to_string(fit.terms.size()) + (c.settings.per_term_nu ? ", nu per term" : ", one common nu");
}

nlohmann::json report_json(const HyperfoamModesFit& fit, const HyperfoamCampaign& c) {
  nlohmann::json j;
  j["kind"] = "hyperfoam_only";
  j["campaign"] = c.manifest.string();
  j["terms"] = nlohmann::json::array();
  for (const auto& t : fit.terms) j["terms"].push_back({{"mu_kPa", t.mu * 1e3}, {"alpha", t.alpha}, {"nu", t.nu}});
  j["settings"] = {{"terms", c.settings.terms},
                   {"poisson", c.settings.per_term_nu ? "per_term" : "common"},
                   {"lateral_weight", c.settings.lateral_weight}};
  j["objective"] = fit.cost;
  const char* modes[4] = {"uniaxial", "equibiaxial", "planar", "volumetric"};
  for (std::size_t m = 0; m < 4; ++m) j["stable_stretch"][modes[m]] = {fit.stable_stretch[m].first, fit.stable_stretch[m].second};
  j["stability"] = fit.stability;
  j["search"] = {{"screened_starts", fit.starts}, {"polishes", fit.polishes}, {"rejected_unstable", fit.rejected_unstable},
                 {"common_nu_screen", fit.nu_screen}};
  j["tests"] = nlohmann::json::array();
  for (std::size_t i = 0; i < c.tests.size(); ++i) {
    const HyperfoamTestFigures& f = fit.tests[i];
    nlohmann::json t = {{"name", c.tests[i].name}, {"mode", to_string(c.tests[i].mode)}, {"points", c.tests[i].control.size()},
                        {"stress_r2", f.r2}, {"stress_rms_over_peak", f.rms}, {"stress_max_over_peak", f.max}};
    if (f.lateral_max >= 0.0) {
      t["lateral_stretch_max_relative_error"] = f.lateral_max;
      t["lateral_stretch_rms_relative_error"] = f.lateral_rms;
    }
    j["tests"].push_back(t);
  }
  j["warnings"] = fit.warnings;
  return j;
}

std::string report_markdown(const HyperfoamModesFit& fit, const HyperfoamCampaign& c, const std::vector<PlotFiles>& plots) {
  std::ostringstream o;
  o << "# Hyperfoam fit: " << (c.description.empty() ? c.manifest.filename().string() : c.description) << "\n\n";
  o << provenance(c, fit) << ". Stress is nominal, tension positive; the lateral stretch is that of the stress-free "
       "direction. Objective: stress residuals / peak stress of each test, plus " << c.settings.lateral_weight
    << " x lateral-stretch residuals / the test's lateral range (docs/physics.md 2.7).\n\n";
  o << "| i | mu_i [kPa] | alpha_i | nu_i |\n|---|---|---|---|\n";
  for (std::size_t i = 0; i < fit.terms.size(); ++i)
    o << "| " << i + 1 << " | " << num(fit.terms[i].mu * 1e3, 8) << " | " << num(fit.terms[i].alpha, 8) << " | "
      << num(fit.terms[i].nu, 6) << " |\n";
  o << "\n| test | mode | points | stress R^2 | RMS / peak | max / peak | lateral stretch max error | lateral RMS |\n"
       "|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < c.tests.size(); ++i) {
    const HyperfoamTestFigures& f = fit.tests[i];
    o << "| " << c.tests[i].name << " | " << to_string(c.tests[i].mode) << " | " << c.tests[i].control.size() << " | "
      << num(f.r2, 7) << " | " << percent(f.rms) << " | " << percent(f.max) << " | " << percent(f.lateral_max) << " | "
      << percent(f.lateral_rms) << " |\n";
  }
  o << "\nDrucker stability required over stretch " << describe(fit.stable_stretch) << "; the check over their union:\n\n```\n"
    << fit.stability
    << "\n```\n\nSearch: " << fit.starts << " screened starts (exponent subsets x common nu), " << fit.polishes
    << " Ceres polishes, " << fit.rejected_unstable << " better candidate(s) rejected as unstable.\n\n";
  for (const auto& w : fit.warnings) o << "- warning: " << w << "\n";
  for (const auto& p : plots)
    o << (p.drawn ? "![" + p.png.filename().string() + "](" + p.png.filename().string() + ")\n\n"
                  : "- " + p.script.filename().string() + ": " + p.message + "\n");
  return o.str();
}

/// fit_<name>.csv: data and model at every point of the test.
void write_points(const HyperfoamTest& t, const HyperfoamTestFigures& f, const fs::path& file) {
  std::vector<std::string> columns{control_name(t), "stress_data_MPa", "stress_model_MPa", "lateral_stretch_model"};
  std::vector<std::vector<double>> data{t.control, t.stress, f.stress, f.lateral};
  if (!t.lateral.empty()) {
    columns.push_back("lateral_stretch_data");
    data.push_back(t.lateral);
  }
  write_csv(file, columns, data, {"test " + t.name + " (" + to_string(t.mode) + "): nominal stress tension positive [MPa]"});
}

}  // namespace

std::vector<Plot> hyperfoam_plots(const HyperfoamModesFit& fit, const HyperfoamCampaign& c) {
  Plot stress{"hyperfoam_stress", "Nominal stress: measured vs fitted hyperfoam", "stretch (simple shear: gamma) [-]",
              "nominal stress [MPa] (tension positive)", "", "stretch", "nominal_stress_MPa", {}};
  Plot lateral{"hyperfoam_lateral_stretch", "Stretch of the stress-free direction: measured vs fitted",
               "loaded stretch [-]", "lateral stretch [-]", "", "stretch", "lateral_stretch", {}};
  for (std::size_t i = 0; i < c.tests.size(); ++i) {
    const HyperfoamTest& t = c.tests[i];
    const HyperfoamTest dense = dense_controls(t);
    const HyperfoamTestFigures model = evaluate_hyperfoam_test(fit.terms, dense);
    stress.series.push_back({t.name + " measured", t.control, t.stress, true});
    stress.series.push_back({t.name + " fitted", dense.control, model.stress});
    if (t.lateral.empty()) continue;
    lateral.series.push_back({t.name + " measured", t.control, t.lateral, true});
    lateral.series.push_back({t.name + " fitted", dense.control, model.lateral});
  }
  std::vector<Plot> plots{stress};
  if (!lateral.series.empty()) plots.push_back(lateral);
  return plots;
}

void log_hyperfoam_fit(const HyperfoamModesFit& fit, const HyperfoamCampaign& c, std::ostream& log) {
  std::ostringstream o;
  for (std::size_t i = 0; i < fit.terms.size(); ++i)
    o << "fit: term " << i + 1 << ": mu = " << num(fit.terms[i].mu * 1e3, 6) << " kPa, alpha = " << num(fit.terms[i].alpha, 6)
      << ", nu = " << num(fit.terms[i].nu, 6) << "\n";
  for (std::size_t t = 0; t < c.tests.size(); ++t) {
    const HyperfoamTestFigures& f = fit.tests[t];
    o << "fit: " << c.tests[t].name << " (" << to_string(c.tests[t].mode) << "): stress R^2 = " << num(f.r2, 7)
      << ", max error " << percent(f.max) << " of peak";
    if (f.lateral_max >= 0.0) o << ", lateral stretch max error " << percent(f.lateral_max);
    o << "\n";
  }
  o << "fit: Drucker-stable over stretch " << describe(fit.stable_stretch) << "; " << fit.starts << " screened starts, " << fit.polishes << " polishes, " << fit.rejected_unstable
    << " better fit(s) rejected as unstable\n";
  log << o.str();
}

std::vector<PlotFiles> write_hyperfoam_outputs(const HyperfoamModesFit& fit, const HyperfoamCampaign& c, const fs::path& dir,
                                               const std::string& gnuplot, std::ostream& log) {
  io::check_output_folder(fit_output_folder(dir, true, c.manifest));  // the command refused it without --overwrite
  const fs::path tmp = dir.string() + ".partial";
  fs::remove_all(tmp);
  io::create_folder(tmp);
  try {
    const std::string source = provenance(c, fit);
    material::write_material_file(to_spec({fit.terms, {}}, "foam", source, c.density), tmp / "material.json");
    io::write_file_atomically(tmp / "abaqus_hyperfoam.inp", abaqus_cards({fit.terms, {}}, "FOAM", c.density, source));
    for (std::size_t i = 0; i < c.tests.size(); ++i) write_points(c.tests[i], fit.tests[i], tmp / ("fit_" + c.tests[i].name + ".csv"));
    return finish_staged_fit_output(hyperfoam_plots(fit, c), tmp, dir, gnuplot, log, report_json(fit, c),
                                    [&](const std::vector<PlotFiles>& files) { return report_markdown(fit, c, files); });
  } catch (...) {
    fs::remove_all(tmp);
    throw;
  }
}

}  // namespace cushion::calibration
