#include "calibration/fit_pipeline.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>

#include "calibration/compare.hpp"
#include "calibration/hyperfoam_fit.hpp"
#include "calibration/prony_fit.hpp"
#include "material/hyperfoam.hpp"
#include "io/input_error.hpp"
#include "io/text_support.hpp"

namespace cushion::calibration {

namespace {

class Stopwatch {
 public:
  explicit Stopwatch(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void lap(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.emplace_back(stage, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

std::string percent(double x) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << 100.0 * x << " %";
  return o.str();
}

/// Records a run warning in the result and the log.
void warn(FitResult& R, std::string message, std::ostream& log) {
  R.warnings.push_back(std::move(message));
  log << "fit: warning: " << R.warnings.back() << "\n";
}

/// The campaign's calibration tests (one of each kind) and the dynamic test's timing, shared by the steps.
struct CalibrationTests {
  const Campaign& campaign;
  const FitOptions& options;
  const QuasiStaticTest& qs;
  const DynamicTest& dyn;
  std::optional<DynamicSchedule> schedule;  ///< paper 2.3 timing; empty: about a relaxed preload
  const DynamicSchedule* sched() const { return schedule ? &*schedule : nullptr; }
};

/// The calibration tests of the campaign; throws InputError when a kind has none.
CalibrationTests calibration_tests(const Campaign& campaign, const FitOptions& options) {
  const QuasiStaticTest* qs = campaign.quasi_static_calibration();
  const DynamicTest* dyn = campaign.dynamic_calibration();
  if (!qs) throw InputError(campaign.manifest.string() + ": tests: no quasi-static calibration test");
  if (!dyn) throw InputError(campaign.manifest.string() + ": tests: no dynamic calibration test");
  std::optional<DynamicSchedule> schedule;
  if (!options.relaxed_preload) {
    schedule = options.dynamic_schedule;
    schedule->thickness = campaign.specimen.thickness;
    if (dyn->preload_rate_mm_min > 0.0) schedule->preload_rate_mm_min = dyn->preload_rate_mm_min;  // campaign key
  }
  return {campaign, options, *qs, *dyn, schedule};
}

/// Steps 1-2: segments of the quasi-static record and the loading/unloading pairs at equal strain whose
/// difference stress the hereditary fit uses.
void segment_and_pair(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  const QuasiStaticTest& qs = c.qs;
  R.segments = detect_segments(qs.record);
  for (const auto& w : R.segments.warnings) log << "fit: warning: " << qs.name << ": " << w << "\n";
  // The paper pairs at 1 s intervals; a short unloading branch (lift-off) may leave too few pairs for
  // the 4M hereditary parameters: then the interval is halved (down to the sampling interval), with a warning.
  const std::size_t wanted = 3 * 4 * static_cast<std::size_t>(c.options.hereditary.modes);
  const double sample_dt = 1.0 / sampling_rate(qs.record);
  R.pair_interval = 1.0;
  R.pairs = pair_loading_unloading(qs.record, R.segments, R.pair_interval);
  while (R.pairs.t1.size() < wanted && R.pair_interval / 2.0 >= sample_dt * 0.999) {
    R.pair_interval /= 2.0;
    R.pairs = pair_loading_unloading(qs.record, R.segments, R.pair_interval);
  }
  if (R.pair_interval < 1.0)
    warn(R, "only a short unloading branch: difference stress paired every " + io::format_with("%g", R.pair_interval) +
                " s instead of 1 s", log);
  log << "fit: [1-2] " << qs.name << ": loading " << R.segments.load_end - R.segments.load_begin + 1
      << " samples to " << percent(R.segments.peak_strain) << ", hold " << R.segments.hold_duration << " s, "
      << R.pairs.t1.size() << " loading/unloading pairs every " << R.pair_interval << " s\n";
  if (R.pairs.t1.size() < 4 * static_cast<std::size_t>(c.options.hereditary.modes) + 1)
    throw InputError(qs.record.source + ": only " + std::to_string(R.pairs.t1.size()) +
                     " loading/unloading pairs at equal strain (the unloading branch is too short)");
}

/// Step 3: hereditary modes from the difference stress; fitted and Table 2 modes on the paper's protocol.
void hereditary_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  R.hereditary = fit_hereditary(c.qs.record, R.segments, R.pairs, c.options.hereditary);
  R.table2_curve = protocol_curve(paper_table2_modes());
  R.fitted_curve = protocol_curve(R.hereditary.modes);
  log << "fit: [3] hereditary fit (" << R.hereditary.starts << " starts): RMSE "
      << R.hereditary.rmse * 1e3 << " kPa = " << percent(R.hereditary.rmse_relative) << " of peak stress\n";
}

/// Step 4: the quasi-static stress split into its elastic and hereditary parts.
void decomposition_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  R.decomposition = decompose(c.qs.record, R.segments, R.hereditary.modes);
  log << "fit: [4] decomposition: loading/unloading elastic stress mismatch " << percent(R.decomposition.branch_mismatch)
      << " of peak\n";
}

/// Step 5: hyperfoam terms (and nu unless fixed) fitted to the elastic stress.
void hyperfoam_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  HyperfoamFitOptions ho;
  ho.terms = c.options.terms;
  ho.lateral = c.qs.lateral;
  ho.fit_nu = !c.options.nu.has_value();
  ho.nu = c.options.nu.value_or(0.0);
  try {
    R.hyperfoam = fit_hyperfoam(R.decomposition.elastic, ho);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("hyperfoam fit: ") + e.what());
  }
  for (const auto& w : R.hyperfoam.warnings) log << "fit: warning: hyperfoam: " << w << "\n";
  log << "fit: [5] hyperfoam N=" << R.hyperfoam.terms.size() << ", nu " << R.hyperfoam.nu << ": RMS error "
      << percent(R.hyperfoam.rms_error) << " of peak, " << (R.hyperfoam.stable ? "stable" : "UNSTABLE") << "\n";
}

/// Step 6: Prony series E_inf + sum E_i at the given tau_i fitted to the dynamic moduli: E_inf free as in the
/// paper (always reported), and by default E_inf = the hyperfoam's long-term tangent at the preload (1-20 Hz
/// data cannot separate E_inf from the 100 s term; the free fit may return E_inf = 0).
void prony_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  DynamicModuli moduli;  // the frequencies with a positive loss modulus (noise can make a nearly elastic one <= 0)
  const DynamicModuli& all = c.dyn.moduli;
  for (std::size_t i = 0; i < all.frequency.size(); ++i)
    if (all.loss[i] > 0.0) {
      moduli.frequency.push_back(all.frequency[i]);
      moduli.storage.push_back(all.storage[i]);
      moduli.loss.push_back(all.loss[i]);
    }
  if (moduli.frequency.size() < all.frequency.size())
    warn(R, c.dyn.name + ": " + std::to_string(all.frequency.size() - moduli.frequency.size()) +
                " frequency(ies) with a phase <= 0 (noise) left out of the paper's Prony fit (step 6)", log);
  try {
    R.prony_free = fit_prony(moduli, c.options.tau);
    R.prony = R.prony_free;
    if (c.options.prony_long_term_from_hyperfoam)
      R.prony = fit_prony(moduli, c.options.tau,
                          preload_tangent(material::Hyperfoam(R.hyperfoam.terms), c.dyn.preload_strain).K_hf);
  } catch (const std::invalid_argument& e) {
    throw InputError(c.dyn.file.string() + ": " + e.what());
  }
  log << "fit: [6] Prony fit at " << moduli.frequency.size() << " frequencies: chi2 " << R.prony.chi2
      << ", E_inf " << R.prony.E_inf * 1e3 << " kPa"
      << (R.prony.E_inf_fixed ? " (the hyperfoam's long-term tangent at the preload; E_inf fitted freely as in the "
                                "paper: " + std::to_string(R.prony_free.E_inf * 1e3) + " kPa, chi2 " +
                                    std::to_string(R.prony_free.chi2) + ")"
                              : std::string())
      << "\n";
}

/// Step 7, one normalisation: the solver's model with these relative moduli on both calibration tests. A
/// material the solver cannot build gets NaN errors and a warning; if it was the requested one, the run
/// falls back to the tangent normalisation.
void judge_normalisation(const CalibrationTests& c, PronyNormalisation n, const material::Hyperfoam& paper_base,
                         double qs_hz, FitResult& R, std::ostream& log) {
  const ViscoHyperfoam m{R.hyperfoam.terms, relative_moduli(R.conversion, n)};
  auto& d = n == PronyNormalisation::paper ? R.dynamic_normalisation_paper : R.dynamic_normalisation_tangent;
  auto& q = n == PronyNormalisation::paper ? R.quasi_static_normalisation_paper : R.quasi_static_normalisation_tangent;
  try {
    const auto model = build_model(m);
    d = predict_dynamic(*model, paper_base, c.dyn, c.sched());
    q = predict_quasi_static(*model, c.campaign.specimen, c.qs, R.segments, qs_hz);
  } catch (const std::exception& e) {  // e.g. E_inf = 0: the paper's g_i sum to 1
    d.magnitude_rms = d.phase_rms = q.rms_error = q.max_error = std::nan("");
    warn(R, "Prony normalisation " + to_string(n) + " gives no usable material (its errors: n/a): " + e.what(), log);
    (n == PronyNormalisation::paper ? R.normalisation_failure_paper : R.normalisation_failure_tangent) = e.what();
    if (n == c.options.normalisation) R.run_normalisation = PronyNormalisation::tangent;
    return;
  }
  if (n == c.options.normalisation) R.paper_material = m;
}

/// Step 7: relative moduli g_i from the Prony moduli and the hyperfoam tangent at the preload, in both
/// normalisations, judged by the solver's model; the paper's material uses the run normalisation.
void prony_conversion_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  R.conversion = convert_prony(R.prony.E_inf, R.prony.E, R.prony.tau, R.hyperfoam.terms, c.dyn.preload_strain);
  const material::Hyperfoam paper_base(R.hyperfoam.terms);
  const double qs_hz = std::min(10.0, sampling_rate(c.qs.record));  // reported predictions: up to 10 Hz
  for (PronyNormalisation n : {PronyNormalisation::paper, PronyNormalisation::tangent})
    judge_normalisation(c, n, paper_base, qs_hz, R, log);
  if (R.run_normalisation != c.options.normalisation)
    R.paper_material = {R.hyperfoam.terms, relative_moduli(R.conversion, R.run_normalisation)};
  log << "fit: [7] E_inf " << R.conversion.E_inf * 1e3 << " kPa, hyperfoam tangent at " << percent(c.dyn.preload_strain)
      << " K_hf " << R.conversion.preload.K_hf * 1e3 << " kPa (K_v " << R.conversion.preload.K_v * 1e3
      << " kPa); |E*| error paper/tangent normalisation " << percent(R.dynamic_normalisation_paper.magnitude_rms) << " / "
      << percent(R.dynamic_normalisation_tangent.magnitude_rms) << "; quasi-static "
      << percent(R.quasi_static_normalisation_paper.rms_error) << " / "
      << percent(R.quasi_static_normalisation_tangent.rms_error) << "\n";
}

/// Step 8: consistency refit of the paper's material with the solver's model on the quasi-static
/// calibration test (and the other quasi-static targets) and the dynamic calibration test.
void refit_step(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  const Campaign& campaign = c.campaign;
  auto target = [&](const auto& t) { return c.options.refit_on_all_tests || t.use == TestUse::calibration; };
  std::vector<QuasiStaticTarget> targets{{&c.qs, R.segments, {}}};
  std::vector<DynamicTarget> dynamic{{&c.dyn, {}, {}}};
  std::string dynamic_names = c.dyn.name;
  for (const auto& t : campaign.quasi_static)
    if (&t != &c.qs && target(t)) targets.push_back({&t, detect_segments(t.record), {}});
  for (const auto& t : campaign.dynamic)
    if (&t != &c.dyn && target(t)) dynamic.push_back({&t, {}, {}}), dynamic_names += ", " + t.name;
  RefitOptions refit_options = c.options.refit_options;
  refit_options.schedule = c.schedule;
  if (c.options.noise_weighted_refit) {  // each residual over its noise estimate (compare.hpp), as diagnose weighs it
    const std::vector<TestNoise> noise = estimate_noise(campaign);
    const std::size_t nq = campaign.quasi_static.size();
    bool known = true;
    for (auto& t : targets) {
      const TestNoise& n = noise[std::size_t(t.test - campaign.quasi_static.data())];
      known = known && n.known;
      for (double local : n.stress_local) t.stress_sigma.push_back(n.stress_weighting(local));
    }
    for (auto& t : dynamic) {
      const TestNoise& n = noise[nq + std::size_t(t.test - campaign.dynamic.data())];
      known = known && n.known;
      t.modulus_sigma = n.modulus_local;
      t.phase_sigma = n.phase_local;
    }
    refit_options.noise_weighted = known;
    if (!known) warn(R, "refit: a target test has no noise estimate: residuals relative to the peak, not to the noise", log);
  }
  R.refit = refit(R.paper_material, c.campaign.specimen, targets, dynamic, refit_options);
  auto report = [&](const RefitResult& f) {
    log << "fit: [8] refit with " << f.material.terms.size() << " hyperfoam terms on " << targets.size()
        << " quasi-static test(s) and " << dynamic_names << " (" << f.iterations << " iterations, " << f.evaluations
        << " model runs, " << std::setprecision(3) << f.seconds << " s): quasi-static " << percent(f.quasi_static_rms_start)
        << " -> " << percent(f.quasi_static_rms) << ", dynamic " << percent(f.dynamic_rms_start) << " -> "
        << percent(f.dynamic_rms) << ", joint cost " << std::setprecision(4) << f.cost
        << (f.accepted() ? "" : "  (NOT accepted: " + f.rejection + ")") << "\n";
  };
  report(*R.refit);
  for (int extra = 1; extra <= c.options.extra_refit_terms; ++extra) {  // N + 1 terms, kept when they pay
    ViscoHyperfoam start = R.paper_material;
    for (int k = 0; k < extra; ++k) start.terms.push_back({0.0, 2.0 + k, start.terms.front().nu});
    RefitResult more = refit(start, c.campaign.specimen, targets, dynamic, refit_options);
    report(more);
    const bool kept = more.accepted() && (!R.refit->accepted() || more.cost < c.options.extra_term_gain * R.refit->cost);
    log << "fit: [8] " << more.material.terms.size() << " terms " << (kept ? "kept" : "not kept") << ": joint cost "
        << std::setprecision(4) << more.cost << " vs " << R.refit->cost << " with " << R.refit->material.terms.size()
        << " (kept when accepted and below " << c.options.extra_term_gain << " x)\n";
    if (!kept) break;
    more.iterations += R.refit->iterations, more.evaluations += R.refit->evaluations, more.seconds += R.refit->seconds;
    R.refit = std::move(more);
  }
}

/// The default material as requested: the refit when requested and accepted, else the paper's; with the reason.
void choose_requested_default(const FitOptions& options, FitResult& R) {
  R.default_material = R.paper_material;
  R.default_choice = DefaultMaterial::paper;
  if (!options.refit) {
    R.default_reason = "refit disabled (--no-refit)";
  } else if (options.default_material != DefaultMaterial::refit) {
    R.default_reason = "requested with --default paper";
  } else if (const RefitResult& f = *R.refit; f.accepted()) {
    R.default_material = f.material;
    R.default_choice = DefaultMaterial::refit;
    R.default_reason = "the refit converged, is Drucker-stable and lowers the joint error of the solver's model on both "
                       "calibration tests";
  } else {
    R.default_reason = "the refit was not accepted (" + f.rejection + "): the paper's material";
  }
}

/// The refit is converged and has no material problem (so it can replace the paper's material).
bool refit_usable(const FitResult& R) { return R.refit && R.refit->converged && R.refit_problem.empty(); }

/// Choose the default material: as requested, but never one the solver rejects or a Drucker-unstable one,
/// nor (by default) a paper's material that misses a calibration test by more than 100 % when the refit is
/// usable and closer; throws when neither material is usable.
void choose_default(const FitOptions& options, FitResult& R) {
  choose_requested_default(options, R);
  R.paper_problem = material_problem(R.paper_material);
  if (R.paper_problem.empty() && !R.hyperfoam.stable) R.paper_problem = "Drucker-unstable hyperfoam";
  if (R.refit) R.refit_problem = material_problem(R.refit->material);
  if (R.refit && R.refit_problem.empty() && !R.refit->stable) R.refit_problem = R.refit->rejection;
  if (R.default_choice == DefaultMaterial::paper && !R.paper_problem.empty() && refit_usable(R)) {
    R.default_material = R.refit->material;
    R.default_choice = DefaultMaterial::refit;
    R.default_reason += "; but the paper's material is not usable (" + R.paper_problem + "): the refit";
  }
  const double paper_error = R.refit ? std::max(R.refit->quasi_static_rms_start, R.refit->dynamic_rms_start) : 0.0;
  if (R.default_choice == DefaultMaterial::paper && options.default_material == DefaultMaterial::refit &&
      refit_usable(R) && !(paper_error <= 1.0) && R.refit->cost < R.refit->cost_start) {
    R.default_material = R.refit->material;
    R.default_choice = DefaultMaterial::refit;
    R.default_reason += "; but the paper's material misses the calibration tests by " + percent(paper_error) + ": the refit";
  }
  if ((R.default_choice == DefaultMaterial::paper ? R.paper_problem : R.refit_problem) != "")
    throw std::runtime_error("fit: no usable material: paper's: " + R.paper_problem +
                             (R.refit ? "; refit: " + R.refit_problem : std::string()));
}

/// A material as the solver's model, or why it gives none.
struct ComparedModel {
  std::shared_ptr<const material::Material> model;
  material::Hyperfoam base;
  std::string failure;  ///< non-empty: no model (every prediction "n/a (failure)")
};

ComparedModel compared_model(const ViscoHyperfoam& m) {
  ComparedModel out{nullptr, material::Hyperfoam(m.terms), ""};
  try {
    out.model = build_model(m);
  } catch (const std::exception& e) {
    out.failure = std::string("the material gives no model: ") + e.what();
  }
  return out;
}

/// Runs `predict` (returning the test's error) into `error`; a throw or a non-finite error leaves the error NaN
/// and the reason in `failure`: one failing prediction never aborts the fit.
template <class Predict>
void attempt(const ComparedModel& m, std::string& failure, double& error, Predict&& predict) {
  error = std::nan("");
  if (!m.failure.empty()) {
    failure = m.failure;
    return;
  }
  try {
    error = predict();
    if (!std::isfinite(error)) failure = "non-finite error";
  } catch (const std::exception& e) {
    failure = e.what();
    error = std::nan("");
  }
}

/// The paper's material and the refit (the paper's when no refit ran) as the solver's models.
struct ComparedModels {
  ComparedModel paper, refit;
};

/// One quasi-static test of the campaign: error of the paper's material and of the refit.
TestComparison compare_quasi_static(const CalibrationTests& c, const QuasiStaticTest& t, const ComparedModels& m,
                                    const FitResult& R) {
  TestComparison cmp;
  cmp.name = t.name;
  cmp.kind = "quasi_static";
  cmp.use = t.use == TestUse::calibration
                ? "calibration"
                : (c.options.refit && c.options.refit_on_all_tests ? "refit target" : "validation");
  const Segments s = &t == &c.qs ? R.segments : detect_segments(t.record);
  const double hz = std::min(10.0, sampling_rate(t.record));
  attempt(m.paper, cmp.failure_paper, cmp.error_paper, [&] {
    cmp.quasi_static_paper = predict_quasi_static(*m.paper.model, c.campaign.specimen, t, s, hz);
    return cmp.quasi_static_paper->rms_error;
  });
  if (R.refit)
    attempt(m.refit, cmp.failure_refit, cmp.error_refit, [&] {
      cmp.quasi_static_refit = predict_quasi_static(*m.refit.model, c.campaign.specimen, t, s, hz);
      return cmp.quasi_static_refit->rms_error;
    });
  return cmp;
}

/// One dynamic test of the campaign: |E*| error of the paper's material and of the refit.
TestComparison compare_dynamic(const CalibrationTests& c, const DynamicTest& t, const ComparedModels& m,
                               const FitResult& R) {
  TestComparison cmp;
  cmp.name = t.name;
  cmp.kind = "dynamic";
  cmp.use = t.use == TestUse::calibration
                ? "calibration"
                : (c.options.refit && c.options.refit_on_all_tests ? "refit target" : "validation");
  attempt(m.paper, cmp.failure_paper, cmp.error_paper, [&] {
    cmp.dynamic_paper = predict_dynamic(*m.paper.model, m.paper.base, t, c.sched());
    return cmp.dynamic_paper->magnitude_rms;
  });
  if (R.refit)
    attempt(m.refit, cmp.failure_refit, cmp.error_refit, [&] {
      cmp.dynamic_refit = predict_dynamic(*m.refit.model, m.refit.base, t, c.sched());
      return cmp.dynamic_refit->magnitude_rms;
    });
  return cmp;
}

/// The calibration tests on which the refit's (or the paper's) prediction failed, with the reasons; "" if none.
std::string failed_calibration(const FitResult& R, bool refit) {
  std::string why;
  for (const auto& c : R.comparisons)
    if (c.use == "calibration" && !(refit ? c.failure_refit : c.failure_paper).empty())
      why += (why.empty() ? "" : "; ") + c.name + ": " + (refit ? c.failure_refit : c.failure_paper);
  return why;
}

/// The solver must run the default material on every calibration test: when its prediction of one failed
/// (e.g. a refit fitted with the fast uniaxial model on which the point driver's free-stretch Newton fails) and
/// the other usable material ran them all, the other one becomes the default.
void check_default_runs(FitResult& R, std::ostream& log) {
  if (!R.refit) return;
  const bool is_refit = R.default_choice == DefaultMaterial::refit;
  const std::string why = failed_calibration(R, is_refit);
  if (why.empty()) return;
  const bool other_usable = is_refit ? R.paper_problem.empty() : refit_usable(R);
  if (other_usable && failed_calibration(R, !is_refit).empty()) {
    R.default_material = is_refit ? R.paper_material : R.refit->material;
    R.default_choice = is_refit ? DefaultMaterial::paper : DefaultMaterial::refit;
    R.default_reason += std::string("; but the solver's model of the ") + (is_refit ? "refit" : "paper's material") +
                        " fails on a calibration test (" + why + "): the " + (is_refit ? "paper's material" : "refit");
  } else {
    R.default_reason += "; note: the solver's model of the default material fails on a calibration test (" + why + ")";
  }
  log << "fit: warning: default material: " << R.default_reason << "\n";
}

/// Report: every test of the campaign (calibration and validation), paper's material vs refit; a prediction
/// that fails is reported "n/a (reason)".
void compare_every_test(const CalibrationTests& c, FitResult& R, std::ostream& log) {
  const ComparedModels m{compared_model(R.paper_material),
                         compared_model(R.refit ? R.refit->material : R.paper_material)};
  for (const auto& t : c.campaign.quasi_static) R.comparisons.push_back(compare_quasi_static(c, t, m, R));
  for (const auto& t : c.campaign.dynamic) R.comparisons.push_back(compare_dynamic(c, t, m, R));
  check_default_runs(R, log);
  auto shown = [](double error, const std::string& failure) {
    return failure.empty() ? percent(error) : "n/a (" + failure + ")";
  };
  for (const auto& cmp : R.comparisons)
    log << "fit: " << cmp.use << " " << cmp.name << ": error paper " << shown(cmp.error_paper, cmp.failure_paper)
        << (R.refit ? ", refit " + shown(cmp.error_refit, cmp.failure_refit) : std::string()) << "\n";
}

}  // namespace

FitResult fit_pipeline(const Campaign& campaign, const FitOptions& options, std::ostream& log) {
  FitResult R;
  R.options = options;
  R.run_normalisation = options.normalisation;
  Stopwatch clock(R.timings);
  const CalibrationTests c = calibration_tests(campaign, options);
  R.quasi_static_name = c.qs.name;
  R.dynamic_name = c.dyn.name;
  segment_and_pair(c, R, log);
  clock.lap("segments and pairs");
  hereditary_step(c, R, log);
  clock.lap("hereditary fit");
  decomposition_step(c, R, log);
  clock.lap("decomposition");
  hyperfoam_step(c, R, log);
  clock.lap("hyperfoam fit");
  prony_step(c, R, log);
  clock.lap("Prony fit");
  prony_conversion_step(c, R, log);
  clock.lap("Prony conversion");
  if (options.refit) refit_step(c, R, log);
  choose_default(options, R);
  clock.lap("refit");
  compare_every_test(c, R, log);
  clock.lap("comparison on every test");
  return R;
}

FitOptions diagnose_base_fit_options() {
  FitOptions o;
  o.refit_on_all_tests = true;
  o.noise_weighted_refit = true;
  o.refit_options.times_range = free_times_range;
  o.extra_refit_terms = 0;  // diagnose's budget: the all-test refit with free times takes 7 s with N, about 3x that with N + 1
  return o;
}

}  // namespace cushion::calibration
