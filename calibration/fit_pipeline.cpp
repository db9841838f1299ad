#include "calibration/fit_pipeline.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>

#include "calibration/hyperfoam_fit.hpp"
#include "calibration/prony_fit.hpp"
#include "material/hyperfoam.hpp"
#include "io/input_error.hpp"

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

}  // namespace

FitResult fit_pipeline(const Campaign& campaign, const FitOptions& options, std::ostream& log) {
  FitResult R;
  R.options = options;
  R.run_normalisation = options.normalisation;
  Stopwatch clock(R.timings);
  const QuasiStaticTest* qs = campaign.quasi_static_calibration();
  const DynamicTest* dyn = campaign.dynamic_calibration();
  if (!qs) throw InputError(campaign.manifest.string() + ": tests: no quasi-static calibration test");
  if (!dyn) throw InputError(campaign.manifest.string() + ": tests: no dynamic calibration test");
  R.quasi_static_name = qs->name;
  R.dynamic_name = dyn->name;

  // Steps 1-2: segments, difference stress pairs.
  R.segments = detect_segments(qs->record);
  for (const auto& w : R.segments.warnings) log << "fit: warning: " << qs->name << ": " << w << "\n";
  // The paper pairs at 1 s intervals; a short unloading branch (lift-off) may leave too few pairs for
  // the 4M hereditary parameters: then the interval is halved (down to the sampling interval), with a warning.
  const std::size_t wanted = 3 * 4 * static_cast<std::size_t>(options.hereditary.modes);
  const double sample_dt = 1.0 / sampling_rate(qs->record);
  R.pair_interval = 1.0;
  R.pairs = pair_loading_unloading(qs->record, R.segments, R.pair_interval);
  while (R.pairs.t1.size() < wanted && R.pair_interval / 2.0 >= sample_dt * 0.999) {
    R.pair_interval /= 2.0;
    R.pairs = pair_loading_unloading(qs->record, R.segments, R.pair_interval);
  }
  if (R.pair_interval < 1.0) {
    R.warnings.push_back("only a short unloading branch: difference stress paired every " + std::to_string(R.pair_interval) +
                         " s instead of 1 s");
    log << "fit: warning: " << R.warnings.back() << "\n";
  }
  log << "fit: [1-2] " << qs->name << ": loading " << R.segments.load_end - R.segments.load_begin + 1
      << " samples to " << percent(R.segments.peak_strain) << ", hold " << R.segments.hold_duration << " s, "
      << R.pairs.t1.size() << " loading/unloading pairs every " << R.pair_interval << " s\n";
  if (R.pairs.t1.size() < 4 * static_cast<std::size_t>(options.hereditary.modes) + 1)
    throw InputError(qs->record.source + ": only " + std::to_string(R.pairs.t1.size()) +
                     " loading/unloading pairs at equal strain (the unloading branch is too short)");
  clock.lap("segments and pairs");

  // Step 3: hereditary fit; Table 2 on the paper's protocol.
  R.hereditary = fit_hereditary(qs->record, R.segments, R.pairs, options.hereditary);
  R.table2_curve = protocol_curve(paper_table2_modes());
  R.fitted_curve = protocol_curve(R.hereditary.modes);
  log << "fit: [3] hereditary fit (" << R.hereditary.starts << " starts): RMSE "
      << R.hereditary.rmse * 1e3 << " kPa = " << percent(R.hereditary.rmse_relative) << " of peak stress\n";
  clock.lap("hereditary fit");

  // Step 4: decomposition.
  R.decomposition = decompose(qs->record, R.segments, R.hereditary.modes);
  log << "fit: [4] decomposition: loading/unloading elastic stress mismatch " << percent(R.decomposition.branch_mismatch)
      << " of peak\n";
  clock.lap("decomposition");

  // Step 5: hyperfoam.
  HyperfoamFitOptions ho;
  ho.terms = options.terms;
  ho.lateral = qs->lateral;
  ho.fit_nu = !options.nu.has_value();
  ho.nu = options.nu.value_or(0.0);
  try {
    R.hyperfoam = fit_hyperfoam(R.decomposition.elastic, ho);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("hyperfoam fit: ") + e.what());
  }
  for (const auto& w : R.hyperfoam.warnings) log << "fit: warning: hyperfoam: " << w << "\n";
  log << "fit: [5] hyperfoam N=" << R.hyperfoam.terms.size() << ", nu " << R.hyperfoam.nu << ": RMS error "
      << percent(R.hyperfoam.rms_error) << " of peak, " << (R.hyperfoam.stable ? "stable" : "UNSTABLE") << "\n";
  clock.lap("hyperfoam fit");

  // Step 6: Prony (E_inf free as in the paper; by default E_inf = the hyperfoam's long-term tangent at the preload).
  try {
    R.prony_free = fit_prony(dyn->moduli, options.tau);
    R.prony = R.prony_free;
    if (options.prony_long_term_from_hyperfoam)
      R.prony = fit_prony(dyn->moduli, options.tau,
                          preload_tangent(material::Hyperfoam(R.hyperfoam.terms), dyn->preload_strain).K_hf);
  } catch (const std::invalid_argument& e) {
    throw InputError(dyn->file.string() + ": " + e.what());
  }
  log << "fit: [6] Prony fit at " << dyn->moduli.frequency.size() << " frequencies: chi2 " << R.prony.chi2
      << ", E_inf " << R.prony.E_inf * 1e3 << " kPa"
      << (R.prony.E_inf_fixed ? " (the hyperfoam's long-term tangent at the preload; E_inf fitted freely as in the paper: " +
                                    std::to_string(R.prony_free.E_inf * 1e3) + " kPa, chi2 " + std::to_string(R.prony_free.chi2) + ")"
                              : std::string())
      << "\n";
  clock.lap("Prony fit");

  FitOptions run_options = options;
  std::optional<DynamicSchedule> schedule;
  if (!options.relaxed_preload) {
    schedule = options.dynamic_schedule;
    schedule->thickness = campaign.specimen.thickness;
    if (dyn->preload_rate_mm_min > 0.0) schedule->preload_rate_mm_min = dyn->preload_rate_mm_min;  // campaign key
  }
  run_options.refit_options.schedule = schedule;
  const DynamicSchedule* sched = schedule ? &*schedule : nullptr;

  // Step 7: relative moduli, both normalisations, judged by the solver's model on both tests.
  R.conversion = convert_prony(R.prony.E_inf, R.prony.E, R.prony.tau, R.hyperfoam.terms, dyn->preload_strain);
  const material::Hyperfoam paper_base(R.hyperfoam.terms);
  const double qs_hz = std::min(10.0, sampling_rate(qs->record));  // reported predictions: up to 10 Hz
  for (PronyNormalisation n : {PronyNormalisation::paper, PronyNormalisation::tangent}) {
    const ViscoHyperfoam m{R.hyperfoam.terms, relative_moduli(R.conversion, n)};
    auto& d = n == PronyNormalisation::paper ? R.dynamic_normalisation_paper : R.dynamic_normalisation_tangent;
    auto& q = n == PronyNormalisation::paper ? R.quasi_static_normalisation_paper : R.quasi_static_normalisation_tangent;
    try {
      const auto model = build_model(m);
      d = predict_dynamic(*model, paper_base, *dyn, sched);
      q = predict_quasi_static(*model, campaign.specimen, *qs, R.segments, qs_hz);
    } catch (const std::exception& e) {  // e.g. E_inf = 0: the paper's g_i sum to 1
      d.magnitude_rms = d.phase_rms = q.rms_error = q.max_error = std::nan("");
      R.warnings.push_back("Prony normalisation " + to_string(n) + " gives no usable material (its errors: n/a): " + e.what());
      (n == PronyNormalisation::paper ? R.normalisation_failure_paper : R.normalisation_failure_tangent) = e.what();
      log << "fit: warning: " << R.warnings.back() << "\n";
      if (n == options.normalisation) R.run_normalisation = PronyNormalisation::tangent;
      continue;
    }
    if (n == options.normalisation) R.paper_material = m;
  }
  if (R.run_normalisation != options.normalisation)
    R.paper_material = {R.hyperfoam.terms, relative_moduli(R.conversion, R.run_normalisation)};
  log << "fit: [7] E_inf " << R.conversion.E_inf * 1e3 << " kPa, hyperfoam tangent at " << percent(dyn->preload_strain)
      << " K_hf " << R.conversion.preload.K_hf * 1e3 << " kPa (K_v " << R.conversion.preload.K_v * 1e3
      << " kPa); |E*| error paper/tangent normalisation " << percent(R.dynamic_normalisation_paper.magnitude_rms) << " / "
      << percent(R.dynamic_normalisation_tangent.magnitude_rms) << "; quasi-static "
      << percent(R.quasi_static_normalisation_paper.rms_error) << " / "
      << percent(R.quasi_static_normalisation_tangent.rms_error) << "\n";
  clock.lap("Prony conversion");

  // Step 8: consistency refit.
  R.default_material = R.paper_material;
  R.default_choice = DefaultMaterial::paper;
  if (options.refit) {
    std::vector<QuasiStaticTarget> targets{{qs, R.segments}};
    for (const auto& t : campaign.quasi_static)
      if (&t != qs && (options.refit_all_quasi_static || t.use == TestUse::calibration))
        targets.push_back({&t, detect_segments(t.record)});
    R.refit = refit(R.paper_material, campaign.specimen, targets, *dyn, run_options.refit_options);
    const RefitResult& f = *R.refit;
    log << "fit: [8] refit on " << targets.size() << " quasi-static test(s) and " << dyn->name << " (" << f.iterations << " iterations, " << f.evaluations << " model runs, "
        << std::setprecision(3) << f.seconds << " s): quasi-static " << percent(f.quasi_static_rms_start) << " -> "
        << percent(f.quasi_static_rms) << ", dynamic " << percent(f.dynamic_rms_start) << " -> " << percent(f.dynamic_rms)
        << (f.accepted() ? "" : "  (NOT accepted: " + f.rejection + ")") << "\n";
    if (options.default_material == DefaultMaterial::refit) {
      if (f.accepted()) {
        R.default_material = f.material;
        R.default_choice = DefaultMaterial::refit;
        R.default_reason = "the refit converged, is Drucker-stable and lowers the joint error of the solver's model on both "
                           "calibration tests";
      } else {
        R.default_reason = "the refit was not accepted (" + f.rejection + "): the paper's material";
      }
    } else {
      R.default_reason = "requested with --default paper";
    }
  } else {
    R.default_reason = "refit disabled (--no-refit)";
  }
  // Never hand out a material the solver rejects or a Drucker-unstable one.
  R.paper_problem = material_problem(R.paper_material);
  if (R.paper_problem.empty() && !R.hyperfoam.stable) R.paper_problem = "Drucker-unstable hyperfoam";
  if (R.refit) R.refit_problem = material_problem(R.refit->material);
  if (R.refit && R.refit_problem.empty() && !R.refit->stable) R.refit_problem = R.refit->rejection;
  const bool refit_usable = R.refit && R.refit->converged && R.refit_problem.empty();
  if (R.default_choice == DefaultMaterial::paper && !R.paper_problem.empty() && refit_usable) {
    R.default_material = R.refit->material;
    R.default_choice = DefaultMaterial::refit;
    R.default_reason += "; but the paper's material is not usable (" + R.paper_problem + "): the refit";
  }
  // Nor, by default, a paper's material that misses a calibration test by more than 100 % (e.g. E_inf ~ 0 with the
  // paper's normalisation) when the refit is usable and closer.
  const double paper_error = std::max(R.refit ? R.refit->quasi_static_rms_start : 0.0, R.refit ? R.refit->dynamic_rms_start : 0.0);
  if (R.default_choice == DefaultMaterial::paper && options.default_material == DefaultMaterial::refit && refit_usable &&
      !(paper_error <= 1.0) && R.refit->cost < R.refit->cost_start) {
    R.default_material = R.refit->material;
    R.default_choice = DefaultMaterial::refit;
    R.default_reason += "; but the paper's material misses the calibration tests by " + percent(paper_error) + ": the refit";
  }
  if ((R.default_choice == DefaultMaterial::paper ? R.paper_problem : R.refit_problem) != "")
    throw std::runtime_error("fit: no usable material: paper's: " + R.paper_problem +
                             (R.refit ? "; refit: " + R.refit_problem : std::string()));
  clock.lap("refit");

  // Every test of the campaign, paper's material vs refit. A prediction that fails (one material, one test:
  // e.g. the point driver's Newton not converging) is reported "n/a (reason)" and never aborts the fit.
  const ViscoHyperfoam& refit_material = R.refit ? R.refit->material : R.paper_material;
  const material::Hyperfoam refit_base(refit_material.terms);
  std::shared_ptr<const material::Material> paper_model, refit_model;
  std::string paper_model_failure, refit_model_failure;
  try {
    paper_model = build_model(R.paper_material);
  } catch (const std::exception& e) {
    paper_model_failure = std::string("the material gives no model: ") + e.what();
  }
  try {
    refit_model = build_model(refit_material);
  } catch (const std::exception& e) {
    refit_model_failure = std::string("the material gives no model: ") + e.what();
  }
  // Runs `predict` into `error` (NaN and `failure` set when it throws).
  auto attempt = [](const std::string& model_failure, std::string& failure, double& error, auto&& predict) {
    error = std::nan("");
    if (!model_failure.empty()) {
      failure = model_failure;
      return;
    }
    try {
      error = predict();
      if (!std::isfinite(error)) failure = "non-finite error";
    } catch (const std::exception& e) {
      failure = e.what();
      error = std::nan("");
    }
  };
  for (const auto& t : campaign.quasi_static) {
    TestComparison c;
    c.name = t.name;
    c.kind = "quasi_static";
    c.use = t.use == TestUse::calibration ? "calibration" : (options.refit && options.refit_all_quasi_static ? "refit target" : "validation");
    const Segments s = &t == qs ? R.segments : detect_segments(t.record);
    const double hz = std::min(10.0, sampling_rate(t.record));
    attempt(paper_model_failure, c.failure_paper, c.error_paper, [&] {
      c.quasi_static_paper = predict_quasi_static(*paper_model, campaign.specimen, t, s, hz);
      return c.quasi_static_paper->rms_error;
    });
    if (R.refit)
      attempt(refit_model_failure, c.failure_refit, c.error_refit, [&] {
        c.quasi_static_refit = predict_quasi_static(*refit_model, campaign.specimen, t, s, hz);
        return c.quasi_static_refit->rms_error;
      });
    R.comparisons.push_back(std::move(c));
  }
  for (const auto& t : campaign.dynamic) {
    TestComparison c;
    c.name = t.name;
    c.kind = "dynamic";
    c.use = t.use == TestUse::calibration ? "calibration" : "validation";
    attempt(paper_model_failure, c.failure_paper, c.error_paper, [&] {
      c.dynamic_paper = predict_dynamic(*paper_model, paper_base, t, sched);
      return c.dynamic_paper->magnitude_rms;
    });
    if (R.refit)
      attempt(refit_model_failure, c.failure_refit, c.error_refit, [&] {
        c.dynamic_refit = predict_dynamic(*refit_model, refit_base, t, sched);
        return c.dynamic_refit->magnitude_rms;
      });
    R.comparisons.push_back(std::move(c));
  }
  // The solver must run the default material on every calibration test: when its prediction of one failed
  // (e.g. seed 31 of the random foams: the refit, fitted with the fast uniaxial model, makes the point driver's
  // free-stretch Newton fail) and the other usable material ran them all, the other one is the default.
  auto failed_calibration = [&](bool refit_material_) {
    std::string why;
    for (const auto& c : R.comparisons)
      if (c.use == "calibration" && !(refit_material_ ? c.failure_refit : c.failure_paper).empty())
        why += (why.empty() ? "" : "; ") + c.name + ": " + (refit_material_ ? c.failure_refit : c.failure_paper);
    return why;
  };
  if (R.refit) {
    const bool is_refit = R.default_choice == DefaultMaterial::refit;
    const std::string why = failed_calibration(is_refit);
    if (!why.empty()) {
      const bool other_usable = is_refit ? R.paper_problem.empty() : refit_usable;
      if (other_usable && failed_calibration(!is_refit).empty()) {
        R.default_material = is_refit ? R.paper_material : R.refit->material;
        R.default_choice = is_refit ? DefaultMaterial::paper : DefaultMaterial::refit;
        R.default_reason += std::string("; but the solver's model of the ") + (is_refit ? "refit" : "paper's material") +
                            " fails on a calibration test (" + why + "): the " + (is_refit ? "paper's material" : "refit");
      } else {
        R.default_reason += "; note: the solver's model of the default material fails on a calibration test (" + why + ")";
      }
      log << "fit: warning: default material: " << R.default_reason << "\n";
    }
  }
  auto shown = [](double error, const std::string& failure) {
    return failure.empty() ? percent(error) : "n/a (" + failure + ")";
  };
  for (const auto& c : R.comparisons)
    log << "fit: " << c.use << " " << c.name << ": error paper " << shown(c.error_paper, c.failure_paper)
        << (R.refit ? ", refit " + shown(c.error_refit, c.failure_refit) : std::string()) << "\n";
  clock.lap("comparison on every test");
  return R;
}

}  // namespace cushion::calibration
