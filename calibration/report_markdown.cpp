#include <cmath>
#include <iomanip>
#include <sstream>

#include "calibration/report_fit.hpp"

namespace cushion::calibration {

namespace {

std::string pct(double x) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << 100.0 * x << " %";
  return o.str();
}

std::string num(double x, int digits = 4) {
  std::ostringstream o;
  o << std::setprecision(digits) << x;
  return o.str();
}

void hyperfoam_table(std::ostringstream& o, const std::vector<material::HyperfoamTerm>& terms) {
  o << "| i | mu_i [kPa] | alpha_i | nu_i |\n|---|---|---|---|\n";
  for (std::size_t i = 0; i < terms.size(); ++i)
    o << "| " << i + 1 << " | " << num(terms[i].mu * 1e3, 6) << " | " << num(terms[i].alpha, 6) << " | "
      << num(terms[i].nu) << " |\n";
}

void prony_table(std::ostringstream& o, const PronyConversion& c, const ViscoHyperfoam* refit) {
  o << "| tau_i [s] | E_i [kPa] | g_i paper (a) | g_i tangent (b) |" << (refit ? " g_i refit |" : "") << "\n";
  o << "|---|---|---|---|" << (refit ? "---|" : "") << "\n";
  for (std::size_t i = 0; i < c.tau.size(); ++i) {
    o << "| " << num(c.tau[i]) << " | " << num(c.E[i] * 1e3) << " | " << num(c.paper[i].g) << " | " << num(c.tangent[i].g)
      << " |";
    if (refit) o << " " << num(refit->prony[i].g) << " |";
    o << "\n";
  }
}

/// Title, campaign and the calibration tests.
void header_section(std::ostringstream& o, const FitResult& R, const Campaign& campaign) {
  o << "# cushion fit report\n\n";
  o << "Campaign: `" << campaign.manifest.string() << "`";
  if (!campaign.description.empty()) o << " - " << campaign.description;
  o << "\n\nCalibration tests: quasi-static `" << R.quasi_static_name << "`, dynamic `" << R.dynamic_name
    << "`. Units: strains and stresses nominal, compression positive; stresses in kPa.\n\n";
}

/// Steps 1-2: segments of the quasi-static record and the loading/unloading pairs.
void segments_section(std::ostringstream& o, const FitResult& R) {
  o << "## 1-2. Segments and difference stress\n\n";
  o << "Peak strain " << pct(R.segments.peak_strain) << ", peak stress " << num(R.segments.peak_stress * 1e3) << " kPa, hold "
    << num(R.segments.hold_duration) << " s, " << R.pairs.t1.size() << " loading/unloading pairs every " << num(R.pair_interval) << " s"
    << (R.pair_interval < 1.0 ? " (the paper's 1 s interval halved until the short unloading branch gave enough pairs)" : "")
    << (R.segments.lift_off ? ", unloading truncated at lift-off (strain " + num(R.segments.lift_off_strain) + ")" : "")
    << ".\n";
  for (const auto& w : R.segments.warnings) o << "\n- warning: " << w << "\n";
}

/// Step 3: hereditary modes, difference-stress RMSE, Table 2 on the paper's protocol.
void hereditary_section(std::ostringstream& o, const FitResult& R) {
  o << "\n## 3. Hereditary integral (paper eq. 6, two complex modes)\n\n";
  o << "| mode | Re alpha [kPa] | Im alpha [kPa] | Re beta [1/s] | Im beta [1/s] |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < R.hereditary.modes.size(); ++i) {
    const auto& m = R.hereditary.modes[i];
    o << "| " << i + 1 << " | " << num(m.alpha.real() * 1e3) << " | " << num(m.alpha.imag() * 1e3) << " | "
      << num(m.beta.real()) << " | " << num(m.beta.imag()) << " |\n";
  }
  o << "\nDifference-stress RMSE (eq. 11): " << num(R.hereditary.rmse * 1e3) << " kPa = " << pct(R.hereditary.rmse_relative)
    << " of the peak stress (" << R.hereditary.starts << " starts).\n\n";
  double t2_sv = 0.0, t2_ds = 0.0;
  for (double s : R.table2_curve.sigma_v) t2_sv = std::max(t2_sv, std::abs(s));
  for (double s : R.table2_curve.delta_sigma) t2_ds = std::max(t2_ds, std::abs(s));
  o << "The paper's Table 2 parameters on the paper's protocol (80 mm, 120 mm/min to 75 %, 2 s hold) give a viscous "
       "stress of at most "
    << num(t2_sv * 1e3) << " kPa and a difference stress of at most " << num(t2_ds * 1e3) << " kPa.\n";
}

/// Steps 4-5: decomposition sigma_e = sigma - sigma_v and the hyperfoam fitted to sigma_e.
void elastic_sections(std::ostringstream& o, const FitResult& R) {
  o << "\n## 4. Decomposition sigma_e = sigma - sigma_v\n\n";
  o << "Loading and unloading elastic stress agree to " << pct(R.decomposition.branch_mismatch)
    << " of the peak stress (RMS over strain " << num(R.decomposition.paired_strain_min) << " .. "
    << num(R.decomposition.paired_strain_max) << ").\n";

  o << "\n## 5. Hyperfoam (N = " << R.hyperfoam.terms.size() << ", long term)\n\n";
  hyperfoam_table(o, R.hyperfoam.terms);
  o << "\nRMS error " << pct(R.hyperfoam.rms_error) << ", max " << pct(R.hyperfoam.max_error) << " of the peak; "
    << (R.hyperfoam.stable ? "Drucker-stable over the tested range" : "NOT stable over the tested range") << ".\n\n```\n"
    << R.hyperfoam.stability << "\n```\n";
}

/// Step 6: Prony series and its fit at every frequency.
void prony_section(std::ostringstream& o, const FitResult& R) {
  const PronyConversion& c = R.conversion;
  o << "\n## 6. Prony series (normalised chi-square " << num(R.prony.chi2) << ")\n\n";
  o << "E_inf = " << num(c.E_inf * 1e3) << " kPa, E_0 = E_inf + sum E_i = " << num(c.E_0 * 1e3) << " kPa.\n\n";
  o << "| f [Hz] | E' [kPa] | E' model | E'' [kPa] | E'' model | phase [deg] | model |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : R.prony.residuals)
    o << "| " << num(r.frequency) << " | " << num(r.storage * 1e3) << " | " << num(r.storage_model * 1e3) << " | "
      << num(r.loss * 1e3) << " | " << num(r.loss_model * 1e3) << " | " << num(r.phase) << " | " << num(r.phase_model) << " |\n";
}

/// Step 7: relative moduli in both normalisations and the solver's error with each.
void conversion_section(std::ostringstream& o, const FitResult& R) {
  const PronyConversion& c = R.conversion;
  o << "\n## 7. Relative moduli for the solver\n\n";
  o << "Hyperfoam at the " << pct(c.preload.preload) << " preload: long-term nominal tangent K_hf = " << num(c.preload.K_hf * 1e3)
    << " kPa (measured E_inf = " << num(c.E_inf * 1e3) << " kPa); the part the Prony series scales is K_v = l^2 C = "
    << num(c.preload.K_v * 1e3) << " kPa (K_hf minus the geometric term S11 = " << num(c.preload.S11 * 1e3) << " kPa).\n\n"
    << "(a) paper: g_i = E_i / E_0 (a_i = E_i / E_inf); (b) tangent: a_i = E_i / K_v, g_i = a_i / (1 + sum a).\n\n";
  prony_table(o, c, R.refit ? &R.refit->material : nullptr);
  o << "\n| normalisation | dynamic |E*| RMS error | phase RMS [deg] | quasi-static RMS error |\n|---|---|---|---|\n";
  o << "| (a) paper | " << pct(R.dynamic_normalisation_paper.magnitude_rms) << " | " << num(R.dynamic_normalisation_paper.phase_rms)
    << " | " << pct(R.quasi_static_normalisation_paper.rms_error) << " |\n";
  o << "| (b) tangent | " << pct(R.dynamic_normalisation_tangent.magnitude_rms) << " | "
    << num(R.dynamic_normalisation_tangent.phase_rms) << " | " << pct(R.quasi_static_normalisation_tangent.rms_error) << " |\n";
  o << "\nThe paper's material uses (" << (R.run_normalisation == PronyNormalisation::paper ? "a" : "b")
    << "): (b) makes the solver's dynamic modulus at the preload equal to the measured one (up to K_hf - E_inf in the "
       "storage modulus), (a) scales the viscous part by K_v / E_inf = "
    << num(c.preload.K_v / c.E_inf) << ".\n";
}

/// Step 8: the consistency refit.
void refit_section(std::ostringstream& o, const FitResult& R) {
  o << "\n## 8. Consistency refit\n\n";
  if (R.refit) {
    const RefitResult& f = *R.refit;
    hyperfoam_table(o, f.material.terms);
    o << "\nJoint error of the solver's model (exact fast uniaxial model, finite-amplitude dynamic model) on the "
      << "quasi-static calibration tests and " << R.dynamic_name << ": quasi-static " << pct(f.quasi_static_rms_start) << " -> "
      << pct(f.quasi_static_rms) << ", dynamic (E', E'') " << pct(f.dynamic_rms_start) << " -> " << pct(f.dynamic_rms) << "; "
      << f.starts << " exponent starts, " << f.iterations << " polish iterations, " << f.evaluations << " model evaluations, "
      << num(f.seconds, 3) << " s; "
      << (f.accepted() ? "accepted" : "NOT accepted") << ".\n";
  } else {
    o << "Not run (--no-refit).\n";
  }
}

/// Every test of the campaign, paper's material vs refit, and the default material.
void comparison_section(std::ostringstream& o, const FitResult& R) {
  o << "\n## Every test: paper's method vs refit\n\n";
  o << "| test | use | error measure | paper | refit |\n|---|---|---|---|---|\n";
  for (const auto& t : R.comparisons)
    o << "| " << t.name << " | " << t.use << " | "
      << (t.kind == "quasi_static" ? "RMS(model - test) / peak" : "RMS of |E*| relative error") << " | "
      << (t.failure_paper.empty() ? pct(t.error_paper) : "n/a (" + t.failure_paper + ")") << " | "
      << (R.refit ? (t.failure_refit.empty() ? pct(t.error_refit) : "n/a (" + t.failure_refit + ")") : std::string("-")) << " |\n";
  o << "\nDefault material (`material.json`): **" << (R.default_choice == DefaultMaterial::paper ? "paper" : "refit")
    << "** - " << R.default_reason << ".\n";
}

/// Plots (embedded when drawn, else the script and why) and the stage timings.
void plots_and_timings(std::ostringstream& o, const FitResult& R, const std::vector<PlotFiles>& plots) {
  o << "\n## Plots\n\n";
  for (const auto& p : plots) {
    if (p.drawn) o << "![" << p.png.stem().string() << "](" << p.png.filename().string() << ")\n\n";
    else o << "- " << p.script.filename().string() << " (data " << p.csv.filename().string() << "): " << p.message << "\n";
  }
  o << "\n## Timings\n\n| stage | s |\n|---|---|\n";
  for (const auto& [stage, sec] : R.timings) o << "| " << stage << " | " << num(sec, 3) << " |\n";
}

}  // namespace

std::string report_markdown(const FitResult& R, const Campaign& campaign, const std::vector<PlotFiles>& plots) {
  std::ostringstream o;
  header_section(o, R, campaign);
  segments_section(o, R);
  hereditary_section(o, R);
  elastic_sections(o, R);
  prony_section(o, R);
  conversion_section(o, R);
  refit_section(o, R);
  comparison_section(o, R);
  plots_and_timings(o, R, plots);
  return o.str();
}

}  // namespace cushion::calibration
