#include "calibration/fit_output.hpp"

#include <cmath>
#include <fstream>
#include <numbers>

#include "calibration/abaqus_cards.hpp"
#include "calibration/report_fit.hpp"
#include "io/input_error.hpp"

#include "io/text_support.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::vector<double> kpa(const std::vector<double>& mpa) {
  std::vector<double> out;
  for (double x : mpa) out.push_back(x * 1e3);
  return out;
}

/// Long-term hyperfoam curve of a material on the lateral condition of the test, 0 .. peak strain.
PlotSeries hyperfoam_series(const std::string& title, const std::vector<material::HyperfoamTerm>& terms, Lateral lateral,
                            double peak) {
  PlotSeries s{title, {}, {}};
  for (int i = 0; i <= 60; ++i) s.x.push_back(peak * i / 60.0);
  s.y = kpa(hyperfoam_uniaxial_stress(terms, terms.front().nu, lateral, s.x));
  return s;
}

std::vector<double> magnitude(const DynamicModuli& d) {
  std::vector<double> m;
  for (std::size_t i = 0; i < d.frequency.size(); ++i) m.push_back(std::hypot(d.storage[i], d.loss[i]) * 1e3);
  return m;
}

std::vector<double> phase(const DynamicModuli& d) {
  std::vector<double> p;
  for (std::size_t i = 0; i < d.frequency.size(); ++i) p.push_back(std::atan2(d.loss[i], d.storage[i]) * 180.0 / std::numbers::pi);
  return p;
}

/// One colour per test: test points, the paper's material dashed, the refit solid.
Plot quasi_static_overview(const FitResult& R) {
  Plot p{"model_vs_test_quasi_static",
         "Quasi-static tests (points) vs the solver's model: paper's material (dashed), refit (solid)",
         "nominal strain [-]", "nominal stress [kPa]", "", "strain", "stress_kPa", {}};
  int colour = 0;
  for (const auto& c : R.comparisons) {
    // Either prediction may have failed (reported n/a): the test from whichever ran.
    const auto& any = c.quasi_static_paper ? c.quasi_static_paper : c.quasi_static_refit;
    if (!any) continue;
    p.series.push_back({c.name + ": test", any->strain, kpa(any->measured), true, false, colour});
    if (c.quasi_static_paper)
      p.series.push_back({c.name + ": paper's material", c.quasi_static_paper->strain, kpa(c.quasi_static_paper->model),
                          false, false, colour, 2});
    if (c.quasi_static_refit)
      p.series.push_back({c.name + ": refit", c.quasi_static_refit->strain, kpa(c.quasi_static_refit->model), false,
                          false, colour, 1});
    ++colour;
  }
  return p;
}

/// |E*| (upper panel) and phase (lower panel) of every dynamic test against the model, one colour per test.
Plot dynamic_overview(const FitResult& R) {
  Plot p{"model_vs_test_dynamic",
         "Dynamic tests (points) vs the solver's model at each preload: paper's material (dashed), refit (solid)",
         "frequency [Hz]", "dynamic modulus |E*| [kPa]", "phase [deg]", "frequency_Hz", "modulus_kPa_or_phase_deg", {}};
  p.two_panels = true;
  int colour = 0;
  for (const auto& c : R.comparisons) {
    const auto& any = c.dynamic_paper ? c.dynamic_paper : c.dynamic_refit;
    if (!any) continue;
    const auto add = [&](const std::string& what, const DynamicModuli& d, bool points, int dash) {
      p.series.push_back({c.name + ": " + what + " |E*|", d.frequency, magnitude(d), points, false, colour, dash});
      p.series.push_back({c.name + ": " + what + " phase", d.frequency, phase(d), points, true, colour, dash});
    };
    add("test", any->measured, true, 1);
    if (c.dynamic_paper) add("paper's material", c.dynamic_paper->model, false, 2);
    if (c.dynamic_refit) add("refit", c.dynamic_refit->model, false, 1);
    ++colour;
  }
  return p;
}

}  // namespace

std::vector<Plot> fit_plots(const FitResult& R, const Campaign& campaign) {
  std::vector<Plot> plots;
  const QuasiStaticTest& qs = *campaign.quasi_static_calibration();
  const DynamicTest& dyn = *campaign.dynamic_calibration();
  {  // Fig. 8
    Plot p{"fig8_decomposition",
           "Decomposition of " + qs.name + ": test = viscous + elastic part; hyperfoam fitted to the elastic part (paper Fig. 8)",
           "nominal strain [-]", "nominal stress [kPa]", "", "strain", "stress_kPa", {}};
    const Decomposition& d = R.decomposition;
    p.series.push_back({"test sigma", d.strain, kpa(d.sigma), true});
    p.series.push_back({"viscous sigma_v (hereditary fit)", d.strain, kpa(d.sigma_v)});
    p.series.push_back({"elastic sigma_e = sigma - sigma_v", d.strain, kpa(d.sigma_e)});
    p.series.push_back(hyperfoam_series("hyperfoam fit (paper method)", R.hyperfoam.terms, qs.lateral, R.segments.peak_strain));
    if (R.refit)
      p.series.push_back(hyperfoam_series("hyperfoam after refit (long term)", R.refit->material.terms, qs.lateral,
                                          R.segments.peak_strain));
    plots.push_back(p);
  }
  {  // Fig. 7
    Plot p{"fig7_difference_stress",
           "Difference stress sigma(t1) - sigma(t2) of " + qs.name + ": test vs hereditary model (paper Fig. 7)",
           "loading time t1 [s]", "difference stress [kPa]", "", "t1_s", "delta_sigma_kPa", {}};
    p.series.push_back({"test", R.pairs.t1, kpa(R.hereditary.measured), true});
    p.series.push_back({"hereditary model (fit)", R.pairs.t1, kpa(R.hereditary.model)});
    plots.push_back(p);
  }
  {  // Fig. 4
    Plot p{"fig4_dynamic", "|E*| (left axis) and phase (right axis) of " + dyn.name + ": test vs Prony fit (paper Fig. 4)",
           "frequency [Hz]", "dynamic modulus |E*| [kPa]", "phase [deg]", "frequency_Hz", "value_kPa_or_deg", {}};
    const DynamicModuli fit = prony_moduli(R.prony.E_inf, R.prony.E, R.prony.tau, dyn.moduli.frequency);
    p.series.push_back({"|E*| test", dyn.moduli.frequency, magnitude(dyn.moduli), true, false, 0});
    p.series.push_back({"|E*| Prony fit", fit.frequency, magnitude(fit), false, false, 0});
    p.series.push_back({"phase test", dyn.moduli.frequency, phase(dyn.moduli), true, true, 1});
    p.series.push_back({"phase Prony fit", fit.frequency, phase(fit), false, true, 1, 2});
    plots.push_back(p);
  }
  {  // Table 2 on the paper's protocol
    Plot p{"table2_protocol",
           "Viscous stress on the paper's protocol (120 mm/min to 75 %, 2 s hold): paper Table 2 modes vs this fit's modes",
           "time [s]", "viscous stress sigma_v [kPa]", "", "time_s", "sigma_v_kPa", {}};
    p.series.push_back({"paper Table 2", R.table2_curve.history.time, kpa(R.table2_curve.sigma_v)});
    p.series.push_back({"this fit", R.fitted_curve.history.time, kpa(R.fitted_curve.sigma_v), false, false, -1, 2});
    plots.push_back(p);
  }
  plots.push_back(quasi_static_overview(R));
  plots.push_back(dynamic_overview(R));
  return plots;
}

io::OutputFolder fit_output_folder(const fs::path& dir, bool overwrite, const fs::path& manifest) {
  io::OutputFolder f;
  f.dir = dir;
  f.overwrite = overwrite;
  f.command = "cushion fit";
  f.markers = {"report.md"};
  f.inputs = {manifest};
  f.staged_next_to_it = true;
  return f;
}

std::vector<PlotFiles> finish_staged_fit_output(const std::vector<Plot>& plots, const fs::path& staging, const fs::path& dir,
                                                const std::string& gnuplot, std::ostream& log, const nlohmann::json& report,
                                                const std::function<std::string(const std::vector<PlotFiles>&)>& markdown) {
  std::vector<PlotFiles> files;
  for (const Plot& p : plots) files.push_back(write_plot(p, staging));
  draw_plots(files, staging, gnuplot);
  for (const auto& f : files)
    if (!f.drawn) log << "fit: note: " << f.message << "\n";
  io::write_file_atomically(staging / "report.json", report.dump(1) + "\n");
  io::write_file_atomically(staging / "report.md", markdown(files));
  io::replace_folder(staging, dir);
  for (auto& f : files) {
    f.csv = dir / f.csv.filename();
    f.script = dir / f.script.filename();
    f.png = dir / f.png.filename();
  }
  return files;
}

std::vector<PlotFiles> write_fit_outputs(const FitResult& R, const Campaign& campaign, const fs::path& dir,
                                         const std::string& gnuplot, std::ostream& log) {
  io::check_output_folder(fit_output_folder(dir, true, campaign.manifest));
  const fs::path tmp = dir.string() + ".partial";
  fs::remove_all(tmp);
  io::create_folder(tmp);
  try {
    const double density = campaign.specimen.density;
    std::string calibration_tests;
    for (const QuasiStaticTest* t : campaign.quasi_static_calibration_tests()) calibration_tests += t->name + ", ";
    if (calibration_tests.empty()) calibration_tests = R.quasi_static_name + ", ";
    const std::string provenance = "cushion fit of " + campaign.manifest.filename().string() + " (calibration tests " +
                                   calibration_tests + R.dynamic_name + ")";
    const ViscoHyperfoam& refit_material = R.refit ? R.refit->material : R.paper_material;
    if (R.paper_problem.empty())
      material::write_material_file(
          to_spec(R.paper_material, "foam_paper", provenance + ": the paper's method, Prony normalisation " +
                                                      to_string(R.run_normalisation), density),
          tmp / "material_paper.json");
    else
      log << "fit: note: material_paper.json not written: " << R.paper_problem << "\n";
    if (R.refit_problem.empty())
      material::write_material_file(
          to_spec(refit_material, "foam_refit",
                  provenance + (R.refit ? ": consistency refit of the solver's model to both tests" : ": refit not run (paper's)"),
                  density),
          tmp / "material_refit.json");
    else
      log << "fit: note: material_refit.json not written: " << R.refit_problem << "\n";
    const bool refit_default = R.default_choice == DefaultMaterial::refit;
    material::write_material_file(
        to_spec(R.default_material, "foam", provenance + ": default = " + (refit_default ? "refit" : "paper") + " (" +
                                                R.default_reason + ")", density),
        tmp / "material.json");
    io::write_file_atomically(tmp / "abaqus_paper.inp", abaqus_cards(R.paper_material, "FOAM_PAPER", density, provenance + ", paper's method"));
    io::write_file_atomically(tmp / "abaqus_refit.inp", abaqus_cards(refit_material, "FOAM_REFIT", density, provenance + ", refit"));

    return finish_staged_fit_output(fit_plots(R, campaign), tmp, dir, gnuplot, log, report_json(R, campaign),
                                    [&](const std::vector<PlotFiles>& files) { return report_markdown(R, campaign, files); });
  } catch (...) {
    fs::remove_all(tmp);
    throw;
  }
}

}  // namespace cushion::calibration
