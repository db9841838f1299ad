#include "calibration/report_fit.hpp"

namespace cushion::calibration {

namespace {

using nlohmann::json;

json kpa(const std::vector<double>& mpa) {
  json a = json::array();
  for (double x : mpa) a.push_back(x * 1e3);
  return a;
}

json hyperfoam_json(const std::vector<material::HyperfoamTerm>& terms) {
  json a = json::array();
  for (const auto& t : terms) a.push_back({{"mu_kPa", t.mu * 1e3}, {"alpha", t.alpha}, {"nu", t.nu}});
  return a;
}

json material_json(const ViscoHyperfoam& m) {
  json p = json::array();
  const auto a = long_term_ratios(m.prony);
  for (std::size_t i = 0; i < m.prony.size(); ++i)
    p.push_back({{"g", m.prony[i].g}, {"a_long_term", a[i]}, {"tau_s", m.prony[i].tau}});
  return {{"hyperfoam", hyperfoam_json(m.terms)}, {"prony", p}};
}

json dynamic_json(const DynamicPrediction& d) {
  return {{"frequency_Hz", d.measured.frequency},
          {"storage_measured_kPa", kpa(d.measured.storage)}, {"loss_measured_kPa", kpa(d.measured.loss)},
          {"storage_model_kPa", kpa(d.model.storage)}, {"loss_model_kPa", kpa(d.model.loss)},
          {"magnitude_rms_relative", d.magnitude_rms}, {"phase_rms_deg", d.phase_rms},
          {"storage_rms_relative", d.storage_rms}, {"loss_rms_relative", d.loss_rms}};
}

json quasi_static_json(const QuasiStaticPrediction& q) {
  return {{"rms_error_relative", q.rms_error}, {"max_error_relative", q.max_error}};
}

json modes_json(const std::vector<HereditaryMode>& modes) {
  json a = json::array();
  for (const auto& m : modes)
    a.push_back({{"alpha_re_kPa", m.alpha.real() * 1e3}, {"alpha_im_kPa", m.alpha.imag() * 1e3},
                 {"beta_re_per_s", m.beta.real()}, {"beta_im_per_s", m.beta.imag()}});
  return a;
}

json curve_json(const ProtocolCurve& c) {
  double peak_sv = 0.0, peak_ds = 0.0;
  for (double s : c.sigma_v) peak_sv = std::max(peak_sv, std::abs(s));
  for (double s : c.delta_sigma) peak_ds = std::max(peak_ds, std::abs(s));
  return {{"max_abs_sigma_v_kPa", peak_sv * 1e3}, {"max_abs_delta_sigma_kPa", peak_ds * 1e3},
          {"pair_strain", c.pairs.strain}, {"delta_sigma_kPa", kpa(c.delta_sigma)}};
}

/// Step 6: the Prony series and its fit at every frequency.
json prony_fit_json(const PronyFit& prony) {
  json res = json::array();
  for (const auto& r : prony.residuals)
    res.push_back({{"frequency_Hz", r.frequency}, {"storage_kPa", r.storage * 1e3}, {"storage_model_kPa", r.storage_model * 1e3},
                   {"loss_kPa", r.loss * 1e3}, {"loss_model_kPa", r.loss_model * 1e3},
                   {"magnitude_kPa", r.magnitude * 1e3}, {"magnitude_model_kPa", r.magnitude_model * 1e3},
                   {"phase_deg", r.phase}, {"phase_model_deg", r.phase_model}});
  return {{"E_inf_kPa", prony.E_inf * 1e3}, {"E_kPa", kpa(prony.E)}, {"tau_s", prony.tau},
          {"chi2", prony.chi2}, {"bounds_active", prony.bounds_active}, {"residuals", res}};
}

/// A figure that could not be computed: "n/a (reason)" (never NaN in the report).
json not_available(const std::string& reason) { return json("n/a (" + reason + ")"); }

/// Step 7: relative moduli in both normalisations and the solver's error with each.
json conversion_json(const FitResult& R) {
  const PronyConversion& c = R.conversion;
  // One normalisation: relative moduli, long-term factor and the solver's error (or why there is none).
  auto normalisation = [](json g, const auto& a, const std::string& failure, const auto& dynamic, const auto& quasi_static) {
    json n{{"g", std::move(g)}, {"a_long_term", a}};
    n["dynamic"] = failure.empty() ? dynamic_json(dynamic) : not_available(failure);
    n["quasi_static"] = failure.empty() ? quasi_static_json(quasi_static) : not_available(failure);
    return n;
  };
  auto gs = [](const std::vector<material::PronyTerm>& p) {
    json a = json::array();
    for (const auto& t : p) a.push_back(t.g);
    return a;
  };
  return {
      {"E_inf_kPa", c.E_inf * 1e3}, {"E_0_kPa", c.E_0 * 1e3}, {"preload_strain", c.preload.preload},
      {"K_hf_kPa", c.preload.K_hf * 1e3}, {"K_v_kPa", c.preload.K_v * 1e3}, {"S11_kPa", c.preload.S11 * 1e3},
      {"preload_stress_kPa", c.preload.stress * 1e3},
      {"paper", normalisation(gs(c.paper), c.a_paper, R.normalisation_failure_paper, R.dynamic_normalisation_paper,
                              R.quasi_static_normalisation_paper)},
      {"tangent", normalisation(gs(c.tangent), c.a_tangent, R.normalisation_failure_tangent,
                                R.dynamic_normalisation_tangent, R.quasi_static_normalisation_tangent)},
      {"chosen", to_string(R.run_normalisation)}};
}

/// Step 8: the consistency refit.
json refit_json(const RefitResult& f) {
  return {{"material", material_json(f.material)}, {"converged", f.converged}, {"stable", f.stable},
          {"improved", f.improved}, {"accepted", f.accepted()}, {"iterations", f.iterations},
          {"starts", f.starts}, {"model_evaluations", f.evaluations}, {"seconds", f.seconds},
          {"quasi_static_rms_start", f.quasi_static_rms_start}, {"quasi_static_rms", f.quasi_static_rms},
          {"dynamic_rms_start", f.dynamic_rms_start}, {"dynamic_rms", f.dynamic_rms},
          {"cost_start", f.cost_start}, {"cost", f.cost}, {"stability", f.stability}, {"ceres", f.report}};
}

/// Every test of the campaign, paper's material vs refit.
json tests_json(const FitResult& R) {
  json tests = json::array();
  for (const auto& t : R.comparisons) {
    // A failed prediction: "n/a (reason)" instead of a number.
    auto error = [](double x, const std::string& failure) { return failure.empty() ? json(x) : not_available(failure); };
    json e{{"name", t.name}, {"kind", t.kind}, {"use", t.use}, {"error_paper", error(t.error_paper, t.failure_paper)}};
    if (R.refit) e["error_refit"] = error(t.error_refit, t.failure_refit);
    e["error_measure"] = t.kind == "quasi_static" ? "RMS(model - measured)/peak stress" : "RMS of |E*| relative error";
    if (t.quasi_static_paper) e["paper"] = quasi_static_json(*t.quasi_static_paper);
    if (t.quasi_static_refit) e["refit"] = quasi_static_json(*t.quasi_static_refit);
    if (t.dynamic_paper) e["paper"] = dynamic_json(*t.dynamic_paper);
    if (t.dynamic_refit) e["refit"] = dynamic_json(*t.dynamic_refit);
    tests.push_back(e);
  }
  return tests;
}

}  // namespace

nlohmann::json report_json(const FitResult& R, const Campaign& campaign) {
  json j;
  j["campaign"] = {{"manifest", campaign.manifest.string()}, {"description", campaign.description},
                   {"quasi_static_calibration", R.quasi_static_name}, {"dynamic_calibration", R.dynamic_name}};
  j["options"] = {{"terms", R.options.terms}, {"nu", R.options.nu ? json(*R.options.nu) : json("fit")},
                  {"tau_s", R.options.tau}, {"refit", R.options.refit},
                  {"default", R.options.default_material == DefaultMaterial::paper ? "paper" : "refit"},
                  {"normalisation", to_string(R.run_normalisation)}};
  const Segments& s = R.segments;
  j["segments"] = {{"peak_strain", s.peak_strain}, {"peak_stress_kPa", s.peak_stress * 1e3},
                   {"hold_s", s.hold_duration}, {"lift_off", s.lift_off}, {"lift_off_strain", s.lift_off_strain},
                   {"strain_noise", s.strain_noise}, {"stress_noise_kPa", s.stress_noise * 1e3},
                   {"loading_samples", s.load_end - s.load_begin + 1},
                   {"unloading_samples", s.unload_end - s.unload_begin + 1}, {"warnings", s.warnings}};
  j["difference_stress"] = {{"pairs", R.pairs.t1.size()}, {"t1_s", R.pairs.t1}, {"t2_s", R.pairs.t2},
                            {"strain", R.pairs.strain}, {"measured_kPa", kpa(R.hereditary.measured)},
                            {"model_kPa", kpa(R.hereditary.model)}};
  j["hereditary"] = {{"modes", modes_json(R.hereditary.modes)}, {"rmse_kPa", R.hereditary.rmse * 1e3},
                     {"rmse_relative_to_peak", R.hereditary.rmse_relative}, {"starts", R.hereditary.starts},
                     {"ceres", R.hereditary.report}};
  j["table2_protocol"] = {{"modes", modes_json(paper_table2_modes())},
                          {"protocol", "80 mm block, 120 mm/min to 75 %, 2 s hold, unloading at 120 mm/min"},
                          {"table2", curve_json(R.table2_curve)}, {"fitted", curve_json(R.fitted_curve)}};
  j["decomposition"] = {{"branch_mismatch_relative", R.decomposition.branch_mismatch},
                        {"paired_strain_range", {R.decomposition.paired_strain_min, R.decomposition.paired_strain_max}},
                        {"elastic_strain", R.decomposition.elastic.strain},
                        {"elastic_stress_kPa", kpa(R.decomposition.elastic.stress)}};
  j["hyperfoam"] = {{"terms", hyperfoam_json(R.hyperfoam.terms)}, {"nu", R.hyperfoam.nu},
                    {"rms_error_relative", R.hyperfoam.rms_error}, {"max_error_relative", R.hyperfoam.max_error},
                    {"stable", R.hyperfoam.stable}, {"stability", R.hyperfoam.stability},
                    {"starts", R.hyperfoam.starts}, {"rejected_unstable", R.hyperfoam.rejected_unstable},
                    {"warnings", R.hyperfoam.warnings}};
  j["prony"] = prony_fit_json(R.prony);
  j["prony"]["E_inf_from_hyperfoam"] = R.prony.E_inf_fixed;
  j["prony"]["paper_free_E_inf"] = {
      {"E_inf_kPa", R.prony_free.E_inf * 1e3}, {"E_kPa", kpa(R.prony_free.E)}, {"chi2", R.prony_free.chi2}};
  j["conversion"] = conversion_json(R);
  j["material_paper"] = material_json(R.paper_material);
  if (R.refit) j["refit"] = refit_json(*R.refit);
  j["warnings"] = R.warnings;
  j["material_problems"] = {{"paper", R.paper_problem}, {"refit", R.refit_problem}};
  j["default"] = {{"material", R.default_choice == DefaultMaterial::paper ? "paper" : "refit"}, {"reason", R.default_reason}};
  j["tests"] = tests_json(R);
  json tm = json::object();
  for (const auto& [stage, sec] : R.timings) tm[stage] = sec;
  j["timings_s"] = tm;
  return j;
}

}  // namespace cushion::calibration
