#include "calibration/diagnose.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <limits>
#include <mutex>
#include <numeric>
#include <sstream>
#include <variant>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "calibration/ceres_options.hpp"
#include "calibration/damage_start.hpp"
#include "calibration/early_stop.hpp"
#include "calibration/fit_model.hpp"
#include "calibration/parallel_jobs.hpp"
#include "calibration/recent_runs.hpp"
#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "material/effect_catalog.hpp"

namespace cushion::calibration {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string fmt(double v, int digits = 3) {
  std::ostringstream o;
  o << std::setprecision(digits) << v;
  return o.str();
}

/// The base parameters the base refit and joint candidates fit, in words: "hyperfoam mu_i and alpha_i, Prony g_i and
/// tau_i" (the exponents and times as the options free them).
std::string refitted_base_parameters(const DiagnoseOptions& o, bool polished = false) {
  return std::string("hyperfoam mu_i") + (o.base_exponents || polished ? " and alpha_i" : "") + ", Prony g_i" +
         (o.base_times || polished ? " and tau_i" : "");
}

/// chi2: sum of squared noise-normalised residuals of a comparison.
double chi2_of(const CompareResult& r, int points) {
  double s = 0.0;
  for (double x : normalised_residuals(r, points)) s += x * x;
  return s;
}

/// What a base-refit factor scales (none: the parameter is an effect's).
enum class BaseTarget { none, hyperfoam_mu, prony_modulus, prony_time, hyperfoam_exponent };

/// One fitted parameter: where it lives and how it is scaled.
struct FreeParameter {
  std::size_t effect = 0;  ///< index in the candidate's effect list (effect parameters)
  /// A base-refit factor: on hyperfoam term `term`'s mu_i or alpha_i, or on Prony term `term`'s relative modulus
  /// a_i = g_i/(1 - sum g) or time tau_i.
  BaseTarget target = BaseTarget::none;
  std::size_t term = 0;
  bool is_base() const { return target != BaseTarget::none; }
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);  ///< no parameter (scan_partner)
  const material::EffectParameterInfo* info = nullptr;
  double lower = 0.0, upper = 0.0;  ///< bounds of u
  double to_u(double x) const { return info->log_scale ? std::log10(x) : x / scale(); }
  double to_x(double u) const { return info->log_scale ? std::pow(10.0, u) : u * scale(); }
  double scale() const { return info->default_value != 0.0 ? std::abs(info->default_value) : 1.0; }
};

/// Where diagnose's fit of parameter p starts [file unit]: its fit_start, else its default.
double fit_start_of(const material::EffectParameterInfo& p) {
  return p.fit_start > 0.0 ? p.fit_start : p.default_value;
}

/// The value parameter p of effect e takes in this fit's start [file unit]: the value e gives, else fit_start_of(p).
double value_in_fit(const material::EffectParameterInfo& p, const material::EffectSpec& e) {
  const auto given = e.parameters.find(p.name);
  return given != e.parameters.end() ? given->second : fit_start_of(p);
}

/// Whether diagnose fits parameter p of effect e here: not when p is fitted only without a branch that e has on, or
/// only with a branch that e has off (the branch's parameter at a value > 0 in this fit: on).
bool fitted_here(const material::EffectInfo& info, const material::EffectParameterInfo& p,
                 const material::EffectSpec& e) {
  for (const auto& q : info.parameters) {
    if (q.name == p.fitted_only_without && value_in_fit(q, e) != 0.0) return false;
    if (q.name == p.fitted_only_with && value_in_fit(q, e) == 0.0) return false;
  }
  return true;
}

/// `prony` with the long-term ratios a_i (g_i = a_i/(1 + sum a), fit_model.hpp), its times kept.
std::vector<material::PronyTerm> with_long_term_ratios(const std::vector<material::PronyTerm>& prony,
                                                       const std::vector<double>& a) {
  std::vector<double> tau;
  for (const auto& t : prony) tau.push_back(t.tau);
  return prony_from_long_term_ratios(a, tau);
}

/// A Prony term `cushion fit` left at its bound a_i = 0 (a_i = g_i/(1 - sum g)) is out of reach of a factor on a_i:
/// every joint fit would keep it dead. Each term below 1e-3 of the mean a_i is set to a tenth of the mean (the other
/// terms' a_i kept, the g_i renormalised), so that the base factor in [0.1, 10] spans 0.01-1 times the mean. Measured
/// on the Ogden-Roxburgh campaign c002 (docs/physics.md 9.24): its fitted base holds the term at 0.03 s at 0; given with
/// that term's g at 0.01 instead, Mullins reaches chi2/N 0.85 (every test within 1.38x noise) against 2.7.
/// Only the base `cushion fit` or the user placed is revived (the reference's first fit, and the joint candidates when
/// the reference failed): a restart from a fitted point (a polish, a continuation, a pair, a held-out refit) starts
/// exactly where that fit ended, so it can only lower the chi2 (docs/physics.md 9.45).
material::MaterialSpec with_dead_prony_terms_revived(material::MaterialSpec s) {
  if (s.prony.empty()) return s;
  std::vector<double> a = long_term_ratios(s.prony);
  const double mean = std::accumulate(a.begin(), a.end(), 0.0) / static_cast<double>(a.size());
  bool revived = false;
  for (double& x : a)
    if (x < 1e-3 * mean) x = 0.1 * mean, revived = true;
  if (revived) s.prony = with_long_term_ratios(s.prony, a);
  return s;
}

/// The cheaper model Levenberg-Marquardt's Jacobian is differenced from: the dynamic tests' fitted cycles at
/// options.jacobian_steps_per_cycle steps a cycle, the cycles before them at half that (at most the model's own).
CompareOptions jacobian_compare_options(const DiagnoseOptions& options) {
  CompareOptions o = options.compare;
  o.dynamic_steps_per_cycle = options.jacobian_steps_per_cycle;
  o.dynamic_transient_steps_per_cycle =
      std::min(o.dynamic_transient_steps_per_cycle, std::max(1, options.jacobian_steps_per_cycle / 2));
  return o;
}

/// The material with the candidate effects and the campaign comparison it gives.
class CandidateModel {
 public:
  CandidateModel(const material::MaterialSpec& base, std::vector<material::EffectSpec> effects, const Campaign& campaign,
                 const std::vector<TestNoise>& noise, const DiagnoseOptions& options)
      : base_(base), effects_(std::move(effects)), campaign_(campaign), noise_(noise), options_(options) {
    // A memory parameter (mullins relaxation_share) is fitted only where there is a Prony memory to edit; else held at 0.
    const bool memory_blocked = base_.prony.empty();
    for (std::size_t e = 0; e < effects_.size(); ++e) {
      const material::EffectInfo* info = material::find_effect(effects_[e].kind);
      for (const auto& p : info->parameters) {
        if (p.name == info->memory_parameter && memory_blocked) {
          effects_[e].parameters[p.name] = 0.0;  // a pair started from a single's fit may carry the single's value
          continue;
        }
        const bool fitted = p.fit || (p.polished_only && options_.polishing);
        if (!fitted || !fitted_here(*info, p, effects_[e])) {
          if (p.diagnose_value && !effects_[e].parameters.count(p.name))
            effects_[e].parameters[p.name] = *p.diagnose_value;  // the form diagnose fits (pneumatic drag)
          continue;
        }
        // a log-scale parameter at 0 is a branch switched off: held there, where given as 0 (a second start, or a single
        // fitted from one) or started at 0 when not given (mullins strain_scale: the energy form unless a start sets it)
        if (p.log_scale && value_in_fit(p, effects_[e]) == 0.0) continue;
        FreeParameter f{e, BaseTarget::none, 0, &p};
        // the log range is centred on the catalogue's start, or on the given value where that start is 0 (branch off)
        const double start = p.log_scale && fit_start_of(p) == 0.0 ? value_in_fit(p, effects_[e]) : fit_start_of(p);
        if (p.log_scale) {
          const double lo = std::max(p.min_exclusive ? p.min * (1 + 1e-12) + 1e-300 : p.min, start * 1e-4);
          f.lower = std::log10(std::max(lo, 1e-300));
          f.upper = std::log10(std::min(p.max, start * 1e4));
        } else {
          f.lower = (p.min_exclusive ? p.min + 1e-12 * std::max(1.0, std::abs(p.min)) : p.min) / f.scale();
          f.upper = p.max / f.scale();
        }
        free_.push_back(f);
        if (!effects_[e].parameters.count(p.name)) effects_[e].parameters[p.name] = start;
      }
    }
  }

  /// Adds a log10 factor in [-1, 1] on the mu of every hyperfoam term and on the relative modulus
  /// a_i = g_i/(1 - sum g) of every Prony term of the base (the base-refit reference; no effect), with
  /// `times` one in [-b.time_decades, b.time_decades] on every Prony time tau_i, and with `exponents` one in
  /// [-b.exponent_decades, b.exponent_decades] on every hyperfoam exponent alpha_i (its sign kept). A Prony term the
  /// base holds at a_i = 0 stays there: the start that revives it belongs to the base `cushion fit` or the user placed
  /// (with_dead_prony_terms_revived, the reference's first fit), never to a fitted point.
  void free_base_moduli(bool times, bool exponents, const BaseFactorBounds& b) {
    static const material::EffectParameterInfo factor{"modulus_factor", "factor on a base modulus", 1.0, 0.1, 10.0,
                                                      true, true, true};
    // name and log scale (each fit's bounds: b)
    static const material::EffectParameterInfo time{
        "time_factor", "factor on a base Prony time", 1.0, 0.01, 100.0, true, true, true};
    static const material::EffectParameterInfo exponent{
        "exponent_factor", "factor on a hyperfoam exponent", 1.0, 0.01, 100.0, true, true, true};
    for (std::size_t t = 0; t < base_.hyperfoam.size(); ++t)
      free_.push_back({0, BaseTarget::hyperfoam_mu, t, &factor, -1.0, 1.0});
    for (std::size_t t = 0; t < base_.prony.size(); ++t)
      free_.push_back({0, BaseTarget::prony_modulus, t, &factor, -1.0, 1.0});
    if (times)
      for (std::size_t t = 0; t < base_.prony.size(); ++t)
        free_.push_back({0, BaseTarget::prony_time, t, &time, -b.time_decades, b.time_decades});
    if (exponents)
      for (std::size_t t = 0; t < base_.hyperfoam.size(); ++t)
        free_.push_back({0, BaseTarget::hyperfoam_exponent, t, &exponent, -b.exponent_decades, b.exponent_decades});
  }

  const std::vector<FreeParameter>& free() const { return free_; }

  std::vector<material::EffectSpec> effects_at(const double* u) const {
    std::vector<material::EffectSpec> e = effects_;
    for (std::size_t i = 0; i < free_.size(); ++i)
      if (!free_[i].is_base()) e[free_[i].effect].parameters[free_[i].info->name] = free_[i].to_x(u[i]);
    return e;
  }
  std::vector<double> start() const {
    std::vector<double> u;
    for (const auto& f : free_)
      u.push_back(f.is_base()
                      ? 0.0
                      : std::clamp(f.to_u(effects_[f.effect].parameters.at(f.info->name)), f.lower, f.upper));
    return u;
  }

  /// The spec with the effects at u (effects needing a viscoelastic model first).
  material::MaterialSpec spec_at(const double* u) const {
    material::MaterialSpec s = base_;
    std::vector<double> a = long_term_ratios(s.prony);  // Prony relative moduli, scaled, then back to the g_i
    bool prony_scaled = false;
    for (std::size_t i = 0; i < free_.size(); ++i) {
      const FreeParameter& f = free_[i];
      const double x = f.to_x(u[i]);
      switch (f.target) {
        case BaseTarget::hyperfoam_mu: s.hyperfoam[f.term].mu *= x; break;
        case BaseTarget::hyperfoam_exponent: s.hyperfoam[f.term].alpha *= x; break;
        case BaseTarget::prony_modulus: a[f.term] *= x, prony_scaled = true; break;
        case BaseTarget::prony_time: s.prony[f.term].tau *= x; break;
        case BaseTarget::none: break;
      }
    }
    if (prony_scaled) s.prony = with_long_term_ratios(s.prony, a);
    const std::vector<material::EffectSpec> candidate = effects_at(u);
    s.effects.insert(s.effects.end(), candidate.begin(), candidate.end());
    s.effects = material::composition_order(std::move(s.effects));
    return s;
  }

  /// Comparison at u; nullopt when the material cannot be built or a test run fails.
  /// u is clamped to the bounds first: a forward difference taken at a bound steps outside it (Ceres' numeric
  /// differentiation does not know the bounds), where the material may reject the value (a share above 1).
  /// A point among the last few run is answered from them, bit for bit (recent_runs.hpp, docs/physics.md 9.20).
  std::optional<CompareResult> compare_at(const double* u) const {
    std::vector<double> inside = clamped(u);
    if (auto known = recent_.find(inside)) return *known;
    ++evaluations_;
    std::optional<CompareResult> r = run_at(inside, options_.compare);
    recent_.keep(std::move(inside), r);
    return r;
  }
  double chi2_at(const double* u) const {
    const auto r = compare_at(u);
    if (!r) return std::numeric_limits<double>::infinity();
    return chi2_of(*r, options_.quasi_static_points);
  }
  bool residuals_at(const double* u, double* out, std::size_t n) const { return copy_residuals(compare_at(u), out, n); }
  /// The residuals at u of the cheaper model Levenberg-Marquardt's Jacobian is taken from (jacobian_compare_options;
  /// not kept among the recent runs).
  bool jacobian_residuals_at(const double* u, double* out, std::size_t n) const {
    ++evaluations_;
    return copy_residuals(run_at(clamped(u), jacobian_compare_options(options_)), out, n);
  }
  /// Model runs made, at either step (a point answered from the recent runs is not one).
  int evaluations() const { return evaluations_; }
  /// Whether jacobian_residuals_at runs a cheaper model than residuals_at (DiagnoseOptions::jacobian_steps_per_cycle).
  bool jacobian_is_cheaper() const {
    return options_.jacobian_steps_per_cycle > 0 &&
           options_.jacobian_steps_per_cycle < options_.compare.dynamic_steps_per_cycle;
  }

 private:
  /// u clamped to the bounds.
  std::vector<double> clamped(const double* u) const {
    std::vector<double> inside(u, u + free_.size());
    for (std::size_t i = 0; i < free_.size(); ++i) inside[i] = std::clamp(inside[i], free_[i].lower, free_[i].upper);
    return inside;
  }
  /// The noise-normalised residuals of r into out (n of them); false when r failed or has another count.
  bool copy_residuals(const std::optional<CompareResult>& r, double* out, std::size_t n) const {
    if (!r) return false;
    const std::vector<double> v = normalised_residuals(*r, options_.quasi_static_points);
    if (v.size() != n) return false;
    std::copy(v.begin(), v.end(), out);
    return true;
  }

  /// The model run at u (inside the bounds) with the forward-model options o: nullopt when the material cannot be built
  /// or a test run fails.
  std::optional<CompareResult> run_at(const std::vector<double>& u, const CompareOptions& o) const {
    try {
      const material::MaterialDefinition def = material::build_material(spec_at(u.data()), "candidate");
      CompareResult r = compare_campaign(*def.model, campaign_, o, noise_);
      for (const auto& t : r.tests)
        if (!t.failure.empty()) return std::nullopt;
      return r;
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }

  material::MaterialSpec base_;
  std::vector<material::EffectSpec> effects_;
  const Campaign& campaign_;
  const std::vector<TestNoise>& noise_;
  const DiagnoseOptions& options_;
  std::vector<FreeParameter> free_;
  mutable std::atomic<int> evaluations_{0};
  mutable RecentRuns<CompareResult> recent_;
};

/// How a candidate's start is searched before Levenberg-Marquardt.
enum class Scan {
  none,
  /// Each parameter in turn (others held) over a coarse set of values, keeping the best.
  all_in_turn,
  /// The effects' parameters only, in turn, the base factors held (a joint candidate starts from a fitted base). Both
  /// of a two-parameter effect scanned together (all combinations) found foreign Jenkins campaign c047 (bench seed
  /// 2025: friction named, 21/40 singles) but led LM into a worse basin on the Bouc-Wen case of
  /// DiagnoseForeignFittedBaseline (friction chi2 3248 against 2167 from the scan in turn; 4 LM iterations from each
  /// start did not tell which would end lower): not taken (measured 2026-11-25). A parameter the catalogue pairs with
  /// another (scan_with: the air flow's trapped-air modulus with its permeability, which set the Maxwell time between
  /// them; the dashpot's rate exponent with its permeability exponent) is scanned with it on every combination
  /// (scan_pair) instead; only here, not in added_effect.
  effect,
  /// The parameters of the candidate's last effect only, in turn, the base and the other effects held: a pair starts
  /// from the best single's fit (its base and effect) and the added effect's own single fit, and only the added effect
  /// needs a start beside the other. Bench seed 2025 (2026-11-25): rescanning both effects led the two air-flow pairs
  /// c015 (+ Jenkins) and c023 (+ strain-dependent Prony) to a worse basin (dBIC 1392 and 151 against 1964 and 472
  /// from this start; both now named); no scan at all left c007's stiffness damping + air flow at dBIC 675, below the
  /// single's 2559 (the air flow's own single-fit values on the other base).
  added_effect,
};

/// Whether the start scan moves parameter f in decades: log-scale (fitted as log10 x) or scan_decades.
bool scanned_in_decades(const FreeParameter& f) { return f.info->log_scale || f.info->scan_decades; }

/// u moved by d decades: u + d for a log-scale parameter (u = log10 x), u 10^d for a scan_decades one.
double decades_from(const FreeParameter& f, double u, double d) {
  return f.info->log_scale ? u + d : u * std::pow(10.0, d);
}

/// The trial values of a parameter about u (u itself excluded): log-scale and scan_decades ones a decade apart over 3
/// decades either side (a scan_decades one at 0, switched off, about its catalogue start), others u x {0, 0.3, 3, 10};
/// only values within the bounds.
std::vector<double> scan_values(const FreeParameter& f, double u) {
  std::vector<double> v;
  if (scanned_in_decades(f)) {
    const double centre = f.info->scan_decades && u <= 0.0 ? f.to_u(fit_start_of(*f.info)) : u;
    for (int d = -3; d <= 3; ++d) v.push_back(decades_from(f, centre, d));
  } else {
    for (double s : {0.0, 0.3, 3.0, 10.0}) v.push_back(u * s);
  }
  std::erase_if(v, [&](double t) { return t < f.lower || t > f.upper || t == u; });
  return v;
}

/// A scan value replaces the current one only when it lowers chi2 by 0.1 %: where the effect is all but switched off
/// chi2 is flat, and following its round-off there leaves Levenberg-Marquardt no gradient (foreign campaign c023, air
/// flow + strain-dependent Prony: a half-decade step that saved 0.03 of chi2 747.9 left pneumatic at dBIC -60 after one
/// iteration, against 333 from the point before it).
bool clearly_better(double chi2, double best) {
  return std::isfinite(best) ? chi2 < best * (1.0 - 1e-3) : chi2 < best;  // best infinite: the model failed there
}

/// A start of Levenberg-Marquardt and its chi2.
struct Start {
  std::vector<double> u;
  double chi2 = 0.0;
};

/// How a start scan scores a trial u: its chi2, or, once compensate_base has run, the chi2 left after the best LINEAR
/// step of the base factors (the residual projected off the columns of their Jacobian at the scan's start; the
/// step itself by compensated). Without it an effect that the fitted base has partly absorbed (a Prony term at the air
/// flow's Maxwell time) only adds to the base's share at every trial, the scan keeps the effect off, and
/// Levenberg-Marquardt starts in another basin (foreign stretch-Maxwell air flow: seed 2025 c036 and c038;
/// docs/physics.md 9.12).
class TrialScore {
 public:
  TrialScore(const CandidateModel& m, std::size_t n_residuals) : m_(m), n_(n_residuals) {}
  const CandidateModel& model() const { return m_; }

  /// The base factors' residual Jacobian at u (forward differences of a fixed step in log10, a secant over the range a
  /// start's compensation moves; ForwardDifferenceCost's Ceres rule would step 1e-8 at a factor's start u = 0), on two
  /// threads while `spare` lends a core. No base factor free, or the model failing at u or a step: scores stay chi2.
  void compensate_base(const std::vector<double>& u, SpareCores* spare) {
    for (std::size_t i = 0; i < u.size(); ++i)
      if (m_.free()[i].is_base()) base_.push_back(i);
    if (base_.empty()) return;
    Eigen::MatrixXd J(static_cast<Eigen::Index>(n_),
                      static_cast<Eigen::Index>(base_.size() + 1));  // the last column: the residual at u
    std::vector<char> ok(base_.size() + 1, 0);
    parallel_for(base_.size() + 1, spare, [&](std::size_t k) {
      std::vector<double> x = u;
      if (k < base_.size()) x[base_[k]] += kStep;
      ok[k] = m_.residuals_at(x.data(), J.col(static_cast<Eigen::Index>(k)).data(), n_);
    });
    if (std::count(ok.begin(), ok.end(), 0) > 0) return base_.clear();
    // A new matrix, not J itself: assigning J a block of J resizes J first, freeing the memory the block reads (the
    // differences came from freed memory, different whenever the other thread had reused it: run-to-run variation).
    const Eigen::MatrixXd dr_du = (J.leftCols(J.cols() - 1).colwise() - J.col(J.cols() - 1)) / kStep;
    qr_.compute(dr_du);
    Q_ = qr_.householderQ() * Eigen::MatrixXd::Identity(dr_du.rows(), qr_.rank());
  }

  /// The score of u (infinite where the model fails).
  double operator()(const double* u) const {
    Eigen::VectorXd r(static_cast<Eigen::Index>(n_));
    if (!m_.residuals_at(u, r.data(), n_)) return std::numeric_limits<double>::infinity();
    if (!base_.empty()) r -= Q_ * (Q_.transpose() * r);  // what the base factors' linear step takes out
    return r.squaredNorm();
  }

  /// The start of Levenberg-Marquardt from the scan's point u: u with the base factors moved by the linear step that
  /// minimises the score (clamped to their bounds) where that lowers chi2, else u (chi2 infinite where the model fails).
  Start start_from(std::vector<double> u) const {
    Eigen::VectorXd r(static_cast<Eigen::Index>(n_));
    if (!m_.residuals_at(u.data(), r.data(), n_)) return {u, std::numeric_limits<double>::infinity()};
    Start plain{u, r.squaredNorm()};
    if (base_.empty()) return plain;
    const Eigen::VectorXd d = qr_.solve(-r);
    for (std::size_t k = 0; k < base_.size(); ++k) {
      const FreeParameter& f = m_.free()[base_[k]];
      u[base_[k]] = std::clamp(u[base_[k]] + d[static_cast<Eigen::Index>(k)], f.lower, f.upper);
    }
    const double chi2 = m_.chi2_at(u.data());
    return chi2 < plain.chi2 ? Start{u, chi2} : plain;
  }

 private:
  static constexpr double kStep = 1e-3;  ///< forward-difference step of a base factor's log10
  const CandidateModel& m_;
  std::size_t n_;
  std::vector<std::size_t> base_;                   ///< indices of the base factors in u
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;  ///< of the base factors' residual Jacobian
  Eigen::MatrixXd Q_;                               ///< orthonormal basis of its column space
};

/// The trials (each a whole u) scored, on two threads while `spare` lends a core, then taken in order: one replaces
/// u when clearly_better than the best so far. best: the score at u on entry; returns the score at u on return.
double keep_best(const TrialScore& score, std::vector<double>& u, const std::vector<std::vector<double>>& trials,
                 double best, SpareCores* spare) {
  std::vector<double> chi2(trials.size());
  parallel_for(trials.size(), spare, [&](std::size_t k) { chi2[k] = score(trials[k].data()); });
  for (std::size_t k = 0; k < trials.size(); ++k)
    if (clearly_better(chi2[k], best)) best = chi2[k], u = trials[k];
  return best;
}

/// The scan_values of parameter i tried (the others held), the best kept in u (keep_best).
double scan_parameter(const TrialScore& score, std::vector<double>& u, std::size_t i, double best, SpareCores* spare) {
  std::vector<std::vector<double>> trials;
  for (double t : scan_values(score.model().free()[i], u[i])) {
    trials.push_back(u);
    trials.back()[i] = t;
  }
  return keep_best(score, u, trials, best, spare);
}

/// Parameters i and j scanned together: u_i and u_j with every combination of their scan_values (each own value
/// included, the pair (u_i, u_j) itself excluded), the best kept in u (keep_best).
double scan_pair(const TrialScore& score, std::vector<double>& u, std::size_t i, std::size_t j, double best,
                 SpareCores* spare) {
  const CandidateModel& m = score.model();
  std::vector<double> vi = scan_values(m.free()[i], u[i]), vj = scan_values(m.free()[j], u[j]);
  vi.push_back(u[i]), vj.push_back(u[j]);
  std::vector<std::vector<double>> trials;
  for (double a : vi)
    for (double b : vj) {
      if (a == u[i] && b == u[j]) continue;
      trials.push_back(u);
      trials.back()[i] = a, trials.back()[j] = b;
    }
  return keep_best(score, u, trials, best, spare);
}

/// The free parameter of the same effect as parameter i that the catalogue scans together with it (scan_with), or
/// npos.
std::size_t scan_partner(const CandidateModel& m, std::size_t i) {
  const FreeParameter& f = m.free()[i];
  if (f.is_base() || f.info->scan_with.empty()) return FreeParameter::npos;
  for (std::size_t j = 0; j < m.free().size(); ++j)
    if (!m.free()[j].is_base() && m.free()[j].effect == f.effect && m.free()[j].info->name == f.info->scan_with)
      return j;
  return FreeParameter::npos;
}

/// Half a decade either side of each of the given effect parameters that is log-scale or scan_decades (in turn,
/// keep_best).
double refine_start(const TrialScore& score, std::vector<double>& u, const std::vector<std::size_t>& effect,
                    double best, SpareCores* spare) {
  for (std::size_t i : effect) {
    const FreeParameter& f = score.model().free()[i];
    if (!scanned_in_decades(f)) continue;
    std::vector<std::vector<double>> trials;
    for (double t : {decades_from(f, u[i], -0.5), decades_from(f, u[i], 0.5)}) {
      if (t == u[i] || t < f.lower || t > f.upper) continue;  // t == u: a scan_decades one left at 0
      trials.push_back(u);
      trials.back()[i] = t;
    }
    best = keep_best(score, u, trials, best, spare);
  }
  return best;
}

/// The start search of `scan` (see Scan) from u, then refine_start. A single's scan (Scan::effect) scores trials with
/// the base factors' linear compensation (TrialScore) and starts from the compensated point where its chi2 is lower.
Start scan_start(const CandidateModel& m, std::vector<double> u, Scan scan, std::size_t n_residuals,
                 SpareCores* spare) {
  if (scan == Scan::none) return {u, m.chi2_at(u.data())};
  TrialScore score(m, n_residuals);
  if (scan == Scan::effect) score.compensate_base(u, spare);
  std::size_t last_effect = 0;
  for (const FreeParameter& f : m.free())
    if (!f.is_base()) last_effect = std::max(last_effect, f.effect);
  std::vector<std::size_t> scanned;  // parameters scanned; all of them with all_in_turn
  for (std::size_t i = 0; i < u.size(); ++i) {
    const FreeParameter& f = m.free()[i];
    if (scan == Scan::all_in_turn || (!f.is_base() && (scan == Scan::effect || f.effect == last_effect)))
      scanned.push_back(i);
  }
  if (scanned.empty()) scanned.resize(u.size()), std::iota(scanned.begin(), scanned.end(), std::size_t{0});
  double best = score(u.data());
  // Scan partners only in a single's scan: a pair's added effect starts from its own single fit, whose time scale the
  // joint scan has placed already; rescanning both from there jumped to a lower-chi2 trial in a worse basin (the
  // hidden strain-dependent Prony case of test_diagnose.cpp: its pair with air flow ended at 3.7x noise, not 1.3x).
  auto partner = [&](std::size_t i) { return scan == Scan::added_effect ? FreeParameter::npos : scan_partner(m, i); };
  std::vector<std::size_t> in_turn;  // the scanned parameters without a scan partner among them
  for (std::size_t i : scanned) {
    const std::size_t j = partner(i);
    if (j != FreeParameter::npos && std::find(scanned.begin(), scanned.end(), j) != scanned.end())
      best = scan_pair(score, u, i, j, best, spare);
    else if (std::none_of(scanned.begin(), scanned.end(), [&](std::size_t k) { return partner(k) == i; }))
      in_turn.push_back(i);
  }
  for (std::size_t i : in_turn) best = scan_parameter(score, u, i, best, spare);
  std::erase_if(scanned, [&m](std::size_t i) { return m.free()[i].is_base(); });
  refine_start(score, u, scanned, best, spare);
  return score.start_from(std::move(u));
}

/// The lowest cost 0.5 |r|^2 among the points a fit evaluated, and where (safe from two threads).
class BestPoint {
 public:
  void offer(const double* u, std::size_t n, const double* r, std::size_t m) {
    double cost = 0.0;
    for (std::size_t i = 0; i < m; ++i) cost += 0.5 * r[i] * r[i];
    const std::lock_guard<std::mutex> lock(mutex_);
    if (cost < cost_) cost_ = cost, u_.assign(u, u + n);
  }
  double cost() const { return cost_; }
  const std::vector<double>& u() const { return u_; }

 private:
  std::mutex mutex_;
  double cost_ = std::numeric_limits<double>::infinity();
  std::vector<double> u_;
};

/// One bounded Levenberg-Marquardt solve of minimise from u (u holds its end), the Jacobian differenced from the model's
/// cheaper runs (CandidateModel::jacobian_residuals_at) or from its own; every point run is offered to `best`.
ceres::Solver::Summary solve_from(const CandidateModel& model, std::vector<double>& u, std::size_t n_residuals,
                                  int max_iterations, SpareCores* spare, const EarlyStop& stop, bool cheaper_jacobian,
                                  BestPoint& best) {
  ceres::Problem problem;
  const std::size_t n = u.size();
  std::vector<double> upper;
  for (const FreeParameter& f : model.free()) upper.push_back(f.upper);
  DifferenceCost::Residuals jacobian_model;
  if (cheaper_jacobian)
    jacobian_model = [&model, n_residuals](const double* x, double* r) {
      return model.jacobian_residuals_at(x, r, n_residuals);
    };
  auto* cost = new ForwardDifferenceCost(
      [&model, &best, n, n_residuals](const double* x, double* r) {
        if (!model.residuals_at(x, r, n_residuals)) return false;
        best.offer(x, n, r, n_residuals);
        return true;
      },
      static_cast<int>(u.size()), static_cast<int>(n_residuals), 1e-5, spare, std::move(upper),
      std::move(jacobian_model));
  problem.AddResidualBlock(cost, nullptr, u.data());
  for (std::size_t i = 0; i < u.size(); ++i) {
    problem.SetParameterLowerBound(u.data(), static_cast<int>(i), model.free()[i].lower);
    problem.SetParameterUpperBound(u.data(), static_cast<int>(i), model.free()[i].upper);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  use_cost_only_line_search(so);
  so.max_num_iterations = max_iterations;
  so.function_tolerance = 1e-6;
  so.parameter_tolerance = 1e-6;
  so.logging_type = ceres::SILENT;
  EarlyStopCallback stop_callback(stop);
  if (stop.active()) so.callbacks.push_back(&stop_callback);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  return summary;
}

/// Bounded Levenberg-Marquardt (Ceres, forward-difference Jacobian, on two threads while `spare` lends a core) on
/// the noise-normalised residuals, from u; u holds the solution on return. When Ceres stops with FAILURE (the model
/// failed on both sides of a Jacobian step; Ceres then leaves u at the start) u is the best point evaluated, if it is
/// below the start: foreign power-law air flow c013 reached cost 547 from 3401 in 9 iterations, then failed and was
/// ranked at its start. Ceres' own update_state_every_iteration does not do this: with it the same fit still ended at
/// its start (measured 2026-11-27).
/// With a cheaper Jacobian (DiagnoseOptions::jacobian_steps_per_cycle), a solve that CONVERGES before max_iterations
/// goes on from its end with the model's own Jacobian for the iterations left: an approximate Jacobian stops where
/// J_g^T r = 0, off the minimum, or where its direction no longer lowers the cost and the trust region shrinks to
/// nothing (seed-2027 c051, stiffness damping: dBIC -56 after 35 runs against 38 with the model's own Jacobian;
/// docs/physics.md 9.36).
ceres::Solver::Summary minimise(const CandidateModel& model, std::vector<double>& u, std::size_t n_residuals,
                                int max_iterations, SpareCores* spare, const EarlyStop& stop) {
  BestPoint best;
  const bool cheaper = model.jacobian_is_cheaper();
  ceres::Solver::Summary summary = solve_from(model, u, n_residuals, max_iterations, spare, stop, cheaper, best);
  const int used = static_cast<int>(summary.iterations.size()) - 1;  // iterations[0]: the start
  if (cheaper && summary.termination_type == ceres::CONVERGENCE && used < max_iterations) {
    EarlyStop rest = stop;  // the early stop counts the iterations of both solves
    rest.iteration = stop.iteration > used ? stop.iteration - used : 0;
    const double initial_cost = summary.initial_cost;
    summary = solve_from(model, u, n_residuals, max_iterations - used, spare, rest, false, best);
    summary.initial_cost = initial_cost;
  }
  if (summary.termination_type == ceres::FAILURE && best.cost() < summary.initial_cost) {
    u = best.u();  // a Jacobian column's point may lie a step beyond a bound: back inside, where it was evaluated
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = std::clamp(u[i], model.free()[i].lower, model.free()[i].upper);
  }
  return summary;
}

/// Fits one candidate (its effects' fitted parameters, and the base-refit factors with refit_base) and
/// scores it: chi2, BIC = chi2 + k ln N, dBIC against the baseline. A failure is reported in the result.
CandidateFit fit_candidate(const material::MaterialSpec& base, const std::vector<material::EffectSpec>& start_effects,
                           const Campaign& campaign, const std::vector<TestNoise>& noise, std::size_t n_residuals,
                           double baseline_bic, const DiagnoseOptions& options, Scan scan, bool refit_base = false,
                           SpareCores* spare = nullptr, const EarlyStop& stop = {}) {
  const auto t0 = Clock::now();
  CandidateFit fit;
  for (const auto& e : start_effects) fit.kinds.push_back(e.kind);
  CandidateModel model(base, start_effects, campaign, noise, options);
  if (refit_base) {
    // a joint candidate has every parameter of the reference
    model.free_base_moduli(options.base_times, options.base_exponents, options.base_bounds);
    fit.base_refitted = true;
    if (start_effects.empty())
      fit.kinds.push_back("base refit (" + refitted_base_parameters(options) + ")");
  }
  std::vector<double> u = model.start();
  fit.parameters = static_cast<int>(u.size());
  try {
    Start s = scan_start(model, u, scan, n_residuals, spare);
    u = std::move(s.u);
    if (!std::isfinite(s.chi2)) throw std::runtime_error("the model with this effect fails at every start value tried");
    const std::vector<double> start = u;
    const ceres::Solver::Summary summary = minimise(model, u, n_residuals, options.max_iterations, spare, stop);
    // Levenberg-Marquardt stopped where the model run fails close by, after moving: its best point is kept
    const bool stopped_at_failure = summary.termination_type == ceres::FAILURE && u != start;
    fit.converged = summary.IsSolutionUsable() || stopped_at_failure;
    fit.message = summary.BriefReport();
    fit.at_iteration_limit = summary.termination_type == ceres::NO_CONVERGENCE;
    if (fit.at_iteration_limit)
      fit.warning = "did not converge within " + std::to_string(options.max_iterations) +
                    " iterations; ranked with the best parameters found (chi2/N may still fall: raise --max-iterations)";
    if (summary.termination_type == ceres::USER_SUCCESS)
      fit.warning = "stopped after " + std::to_string(stop.iteration) + " iterations: " + stop.why;
    if (stopped_at_failure)
      fit.warning = "Levenberg-Marquardt stopped where the model run fails close by (" + summary.message +
                    "); ranked with the best parameters evaluated";
    const auto r = model.compare_at(u.data());
    if (!r) throw std::runtime_error("the model run fails at the fitted parameters");
    fit.compare = *r;
    fit.chi2 = chi2_of(fit.compare, options.quasi_static_points);
    fit.bic = fit.chi2 + fit.parameters * std::log(static_cast<double>(n_residuals));
    fit.delta_bic = baseline_bic - fit.bic;
    fit.effects = model.effects_at(u.data());
    fit.fitted = model.spec_at(u.data());
    if (!fit.converged) fit.message = "did not converge: " + fit.message;
  } catch (const std::exception& e) {
    fit.converged = false;
    fit.message = std::string("failed: ") + e.what();
    fit.delta_bic = -std::numeric_limits<double>::infinity();
  }
  fit.evaluations = model.evaluations();
  fit.seconds = seconds_since(t0);
  return fit;
}

/// The fitted spec of a candidate without the candidate's own effects: its (refitted) base.
material::MaterialSpec base_of(const CandidateFit& f) {
  material::MaterialSpec s = f.fitted;
  std::erase_if(s.effects, [&](const material::EffectSpec& e) {
    return std::find(f.kinds.begin(), f.kinds.end(), e.kind) != f.kinds.end();
  });
  return s;
}

/// `f` fitted once more from where it ended (its refitted base and effects, no start scan) with the base factors that
/// `more` frees; the evaluations and seconds of both runs counted.
CandidateFit refit_with_more_free(const CandidateFit& f, const Campaign& campaign, const std::vector<TestNoise>& noise,
                                  std::size_t n_residuals, double baseline_bic, const DiagnoseOptions& more,
                                  SpareCores* spare) {
  CandidateFit g =
      fit_candidate(base_of(f), f.effects, campaign, noise, n_residuals, baseline_bic, more, Scan::none, true, spare);
  g.evaluations += f.evaluations;
  g.seconds += f.seconds;
  return g;
}

/// The base-refit reference (no effect, every base factor scanned). With base_exponents it is fitted twice: with the
/// hyperfoam exponents fixed, then from there with them free; the joint candidates start from the first
/// (CandidateFit::fitted_fixed_exponents) and fit the exponents with their effect in one run (docs/physics.md 9.8).
CandidateFit fit_reference(const material::MaterialSpec& base, const Campaign& campaign,
                           const std::vector<TestNoise>& noise, std::size_t n_residuals, double baseline_bic,
                           const DiagnoseOptions& options, SpareCores* spare) {
  DiagnoseOptions fixed = options;
  fixed.base_exponents = false;
  CandidateFit first = fit_candidate(with_dead_prony_terms_revived(base), {}, campaign, noise, n_residuals,
                                     baseline_bic, fixed, Scan::all_in_turn, true, spare);
  if (!options.base_exponents || !first.converged) return first;
  CandidateFit f = refit_with_more_free(first, campaign, noise, n_residuals, baseline_bic, options, spare);
  f.fitted_fixed_exponents = std::move(first.fitted);
  return f;
}

}  // namespace

std::string CandidateFit::name() const {
  std::string s;
  for (const auto& k : kinds) s += (s.empty() ? "" : " + ") + k;
  return s;
}

namespace {

/// Rate dependence of the hysteresis (loop area) the model misses, slowest vs fastest quasi-static test.
std::string hysteresis_rate_evidence(const std::vector<const TestCompare*>& qs) {
  std::ostringstream o;
  o << "hysteresis (loop area) measured vs model:";
  for (const auto* t : qs)
    o << " " << fmt(t->rate_mm_min) << " mm/min " << fmt(t->hysteresis_measured * 1e3) << " vs "
      << fmt(t->hysteresis_model * 1e3) << " kPa;";
  const RegionError* slow = qs.front()->region("hysteresis_area");
  const RegionError* fast = qs.back()->region("hysteresis_area");
  const double ms = -slow->bias, mf = -fast->bias;  // missing = measured - model
  const bool sig_s = std::abs(ms) > 3.0 * slow->noise, sig_f = std::abs(mf) > 3.0 * fast->noise;
  if (!sig_s && !sig_f)
    o << " the model has the right hysteresis at every rate (within 3x noise)";
  else if (sig_s && ms > 0 && std::abs(mf) < 2.0 * std::abs(ms) && mf > 0.5 * ms)
    o << " the model misses " << fmt(ms * 1e0) << " kPa at " << fmt(qs.front()->rate_mm_min) << " mm/min and " << fmt(mf)
      << " kPa at " << fmt(qs.back()->rate_mm_min)
      << " mm/min: a missing dissipation that does NOT vanish at slow rates (rate-independent)";
  else if (sig_f && mf > 0 && mf > 2.0 * std::max(ms, 0.0))
    o << " the missing hysteresis grows with rate (" << fmt(ms) << " -> " << fmt(mf)
      << " kPa): a missing RATE-DEPENDENT dissipation";
  else
    o << " hysteresis error " << fmt(-ms) << " kPa (slowest) and " << fmt(-mf) << " kPa (fastest), model - measured";
  return o.str();
}

/// Loading vs unloading of one quasi-static test (first loading vs unloading/reloading below the previous
/// maximum); empty when both are within 2x noise.
std::string loading_unloading_evidence(const TestCompare& t) {
  const RegionError *l = t.region("loading"), *u = t.region("unloading");
  if (!(l->ratio() > 2.0 || u->ratio() > 2.0)) return {};
  return t.name + ": first loading error " + fmt(l->rms) + " kPa (" + fmt(l->ratio(), 2) + "x noise, bias " +
         fmt(l->bias) + "), unloading error " + fmt(u->rms) + " kPa (" + fmt(u->ratio(), 2) + "x noise, bias " +
         fmt(u->bias) + ")" +
         (u->ratio() > 2.0 * std::max(1.0, l->ratio()) ? ": the failure is on unloading, first loading fits" : "");
}

/// Phase and modulus error vs frequency of one dynamic test.
std::string frequency_evidence(const TestCompare& t) {
  const RegionError *pl = t.region("band_low_phase"), *ph = t.region("band_high_phase");
  const RegionError *ml = t.region("band_low_modulus"), *mh = t.region("band_high_modulus");
  std::ostringstream o;
  o << t.name << ": phase error (model - measured) " << fmt(pl->bias) << " deg in the low band, " << fmt(ph->bias)
    << " deg in the high band (noise " << fmt(t.noise.phase) << " deg)";
  if (std::abs(ph->bias - pl->bias) > 3.0 * t.noise.phase && std::abs(ph->bias) > std::abs(pl->bias))
    o << ": the phase error GROWS with frequency";
  else if (std::abs(pl->bias) > 3.0 * t.noise.phase && std::abs(ph->bias - pl->bias) < 0.5 * std::abs(pl->bias))
    o << ": a frequency-INDEPENDENT loss is missing or extra";
  o << "; |E*| error " << fmt(ml->bias) << " -> " << fmt(mh->bias) << " kPa (noise " << fmt(t.noise.modulus * 1e3) << ")";
  return o.str();
}

/// Preload dependence of the dynamic modulus across the dynamic tests.
std::string preload_evidence(const std::vector<const TestCompare*>& dyn) {
  std::ostringstream o;
  o << "|E*| bias (model - measured) by preload:";
  double lo = 1e300, hi = -1e300;
  for (const auto* t : dyn) {
    const RegionError* a = t->region("all_modulus");
    const double rel = a->bias / (a->nrmse > 0 ? a->rms / a->nrmse : 1.0);
    o << " " << fmt(100 * t->preload) << "% preload " << fmt(100 * rel, 2) << "%;";
    lo = std::min(lo, a->bias / std::max(a->noise, 1e-300));
    hi = std::max(hi, a->bias / std::max(a->noise, 1e-300));
  }
  if (hi - lo > 3.0) o << " the modulus error DEPENDS ON THE PRELOAD (" << fmt(hi - lo, 2) << " noise units apart)";
  else o << " no preload dependence beyond noise";
  return o.str();
}

}  // namespace

std::vector<std::string> signature_evidence(const CompareResult& b) {
  std::vector<std::string> ev;
  std::vector<const TestCompare*> qs, dyn;
  for (const auto& t : b.tests) {
    if (!t.failure.empty() || !t.noise.known) continue;
    (t.kind == "quasi_static" ? qs : dyn).push_back(&t);
  }
  std::sort(qs.begin(), qs.end(), [](auto a, auto c) { return a->rate_mm_min < c->rate_mm_min; });
  if (qs.size() >= 2) ev.push_back(hysteresis_rate_evidence(qs));
  for (const auto* t : qs)
    if (std::string e = loading_unloading_evidence(*t); !e.empty()) ev.push_back(std::move(e));
  for (const auto* t : dyn) ev.push_back(frequency_evidence(*t));
  if (dyn.size() >= 2) ev.push_back(preload_evidence(dyn));
  return ev;
}

namespace {

/// What the campaign cannot tell apart: too few tests, rates, preloads, or no test of a kind.
std::vector<std::string> campaign_warnings(const Campaign& campaign) {
  std::vector<std::string> w;
  const std::size_t tests = campaign.quasi_static.size() + campaign.dynamic.size();
  if (tests < 2)
    w.push_back(
        "the campaign has only " + std::to_string(tests) +
        " test: rate effects (viscous, pneumatic) cannot be told from rate-independent ones (friction, Mullins) "
        "without two rates, nor preload dependence without two preloads; the ranking below rests on one test");
  if (campaign.quasi_static.size() == 1)
    w.push_back("one quasi-static rate: rate dependence of the hysteresis cannot be observed");
  if (campaign.quasi_static.empty())
    w.push_back("no quasi-static test: loading vs unloading and hysteresis signatures unavailable");
  if (campaign.dynamic.size() == 1)
    w.push_back("one dynamic preload: preload dependence of the modulus cannot be observed");
  if (campaign.dynamic.empty()) w.push_back("no dynamic test: frequency signatures unavailable");
  return w;
}

/// Baseline: noise estimates, the baseline material on every test, its chi2 (= BIC, no added parameter),
/// the data signatures. Throws InputError when a baseline test run fails.
void compare_baseline(const material::Material& model, const Campaign& campaign, const DiagnoseOptions& options,
                      Diagnosis& d, std::ostream& log) {
  d.noise = estimate_noise(campaign);
  d.baseline = compare_campaign(model, campaign, options.compare, d.noise);
  for (const auto& w : d.baseline.warnings) d.warnings.push_back(w);
  for (const auto& t : d.baseline.tests)
    if (!t.failure.empty())
      throw InputError("baseline material: the model run of test " + t.name + " fails: " + t.failure);
  d.residuals = normalised_residuals(d.baseline, options.quasi_static_points).size();
  d.baseline_chi2 = chi2_of(d.baseline, options.quasi_static_points);
  d.baseline_bic = d.baseline_chi2;  // k = 0 added parameters
  d.evidence = signature_evidence(d.baseline);
  d.at_noise_level = d.baseline.at_noise_level(options.compare.noise_level_ratio);
  log << "diagnose: baseline compared on " << campaign.quasi_static.size() + campaign.dynamic.size() << " tests in "
      << fmt(d.baseline.seconds, 2) << " s, chi2/N " << fmt(d.baseline_chi2 / std::max<std::size_t>(1, d.residuals))
      << "\n";
}

/// The protocol values found with the baseline are kept only when they still fit better once the base is refitted
/// (the reference fit, without effect) under each: a base that is off can make another protocol look better, and
/// the base refit is what an effect must beat. Measured on the foreign 4-term base mismatch (baseline 30x noise):
/// the search with the baseline picked a 10 mm/min ramp, 300 s dwell and peak amplitude (dynamic chi2 2.96e4 ->
/// 1.87e4), which then let friction be named. Without a hyperfoam base to refit, the search's values stand. The refit
/// under the campaign kept becomes the reference of step 4 (d.base_refit; its dBIC is set once the baseline is
/// compared), so it is not fitted twice.
void confirm_protocol_with_base_refit(const material::MaterialSpec& baseline, const material::Material& model,
                                      const Campaign& campaign, const std::vector<TestNoise>& noise,
                                      const DiagnoseOptions& options, ProtocolSearch& p, Diagnosis& d, std::ostream& log) {
  if (!options.joint_base || baseline.base != material::MaterialSpec::Base::hyperfoam || baseline.hyperfoam.empty()) return;
  const std::size_t n = normalised_residuals(compare_campaign(model, campaign, options.compare, noise),
                                             options.quasi_static_points).size();
  SpareCores spare;
  const std::vector<std::function<CandidateFit()>> jobs{
      [&] { return fit_reference(baseline, campaign, noise, n, 0.0, options, &spare); },
      [&] { return fit_reference(baseline, p.campaign, noise, n, 0.0, options, &spare); }};
  std::vector<CandidateFit> refits = run_all(jobs, options.threads, {}, &spare);
  const double assumed = refits[0].converged ? refits[0].chi2 : std::numeric_limits<double>::infinity();
  const double found = refits[1].converged ? refits[1].chi2 : std::numeric_limits<double>::infinity();
  const bool kept = found < assumed - options.strong_evidence;
  log << "diagnose: protocol values found, checked with the base refitted under each: chi2 " << fmt(assumed, 4)
      << " with the defaults, " << fmt(found, 4) << " with the values found: " << (kept ? "kept" : "defaults kept") << "\n";
  d.base_refit = std::move(refits[kept ? 1 : 0]);
  if (kept) return;
  std::string found_values;
  for (auto& k : p.keys) {
    if (k.chosen != k.assumed) found_values += (found_values.empty() ? "" : ", ") + k.key + " " + k.chosen;
    k.chosen = k.assumed;
  }
  d.warnings.push_back("protocol values " + found_values + " fit the baseline better than the defaults, but not a refitted "
                       "base (chi2 " + fmt(found, 4) + " vs " + fmt(assumed, 4) + " with the defaults): the defaults are kept");
  p.campaign = campaign;
  p.moved = false;
  p.chi2_chosen = p.chi2_assumed;
}

/// Step 0: the unrecorded dynamic protocol keys searched with the baseline material (options.search_protocol); the
/// campaign to diagnose: the search's (values kept) or `campaign` as given.
const Campaign& search_unrecorded_protocol(const material::MaterialSpec& baseline, const material::Material& model,
                                           const Campaign& campaign, const DiagnoseOptions& options, Diagnosis& d,
                                           std::ostream& log) {
  if (!options.search_protocol) return campaign;
  const std::vector<TestNoise> noise = estimate_noise(campaign);
  d.protocol = search_protocol(model, campaign, noise, options.compare, options.strong_evidence);
  ProtocolSearch& p = *d.protocol;
  if (p.keys.empty()) return campaign;
  if (p.changed()) confirm_protocol_with_base_refit(baseline, model, campaign, noise, options, p, d, log);
  log << "diagnose: protocol keys not recorded, searched (" << p.runs << " runs, " << fmt(p.seconds, 2) << " s):";
  for (const auto& k : p.keys) log << " " << k.key << " " << k.chosen << (k.chosen == k.assumed ? " (default)" : "");
  log << "; dynamic chi2 " << fmt(p.chi2_assumed, 4) << " -> " << fmt(p.chi2_chosen, 4) << "\n";
  for (const auto& k : p.keys)
    if (k.chi2_range() > options.strong_evidence)
      d.warnings.push_back("the campaign does not record " + k.key + " (" + io::join(k.tests, ", ") + "): the values tried change the " +
                           "dynamic chi2 by up to " + fmt(k.chi2_range(), 3) + "; " +
                           (k.chosen == k.assumed ? "the default " + k.assumed + " fits best and is kept"
                                                  : k.chosen + " fits better than the default " + k.assumed + " and is used") +
                           ": record it in the campaign");
  return p.campaign;
}

/// The verdict's sentence on the protocol assumptions: the keys whose searched value replaced the default.
std::string protocol_sentence(const Diagnosis& d) {
  if (!d.protocol || !d.protocol->changed()) return "";
  std::ostringstream o;
  o << " Protocol: the campaign does not record";
  bool first = true;
  for (const auto& k : d.protocol->keys)
    if (k.chosen != k.assumed) o << (first ? " " : "; ") << k.key << ": " << k.chosen << " (default " << k.assumed << ")", first = false;
  o << " fit the dynamic tests better (chi2 " << fmt(d.protocol->chi2_assumed, 4) << " -> "
    << fmt(d.protocol->chi2_chosen, 4) << ") and are assumed throughout; record them in the campaign to be sure.";
  return o.str();
}

/// The verdict of a baseline that is already at the noise level, with the best candidate's evidence when the
/// candidates were fitted.
std::string at_noise_verdict(const DiagnoseOptions& options, const Diagnosis& d) {
  double worst = 0.0;
  std::string name;
  for (const auto& t : d.baseline.tests)
    if (t.noise_ratio() > worst) worst = t.noise_ratio(), name = t.name;
  std::ostringstream o;
  o << "No effect is missing: every test is within " << fmt(options.compare.noise_level_ratio, 2)
    << "x its measurement noise (worst: " << name << " at " << fmt(worst, 3) << "x)";
  if (!d.candidates.empty() && std::isfinite(d.candidates.front().delta_bic))
    o << ", and no catalogue effect beats a refitted base by dBIC > " << fmt(options.strong_evidence)
      << " (best: " << d.candidates.front().name() << ", dBIC " << fmt(d.candidates.front().delta_bic, 4)
      << " against the base refit's " << (d.base_refit ? fmt(d.base_refit->delta_bic, 4) : std::string("n/a")) << ")";
  o << ". Adding parameters cannot be justified by these data.";
  return o.str();
}

/// The verdict when no candidate is to be fitted: no noise estimate, or (options.stop_at_noise) the baseline already
/// at the noise level; false otherwise.
bool verdict_without_candidates(const DiagnoseOptions& options, Diagnosis& d) {
  if (d.residuals == 0) {
    d.warnings.push_back("no test has a noise estimate: cannot judge any effect against noise");
    d.verdict = "Cannot diagnose: no test has enough samples to estimate the measurement noise.";
    return true;
  }
  if (!d.at_noise_level || !options.stop_at_noise) return false;
  d.verdict = at_noise_verdict(options, d);
  d.fragment = nullptr;
  return true;
}

/// Single candidates: each catalogue effect (or the requested ones) not already in the material;
/// needs_viscoelastic ones only on a Prony material (else a warning).
std::vector<std::vector<material::EffectSpec>> single_candidates(const material::MaterialSpec& baseline,
                                                                 const DiagnoseOptions& options,
                                                                 std::vector<std::string>& warnings) {
  std::vector<std::vector<material::EffectSpec>> singles;
  for (const auto& info : material::effect_catalog()) {
    if (!options.candidates.empty() &&
        std::find(options.candidates.begin(), options.candidates.end(), info.kind) == options.candidates.end())
      continue;
    if (std::any_of(baseline.effects.begin(), baseline.effects.end(), [&](const auto& e) { return e.kind == info.kind; }))
      continue;
    if (info.needs_viscoelastic && baseline.prony.empty()) {
      warnings.push_back(info.kind + ": not a candidate (needs a viscoelastic material)");
      continue;
    }
    singles.push_back({material::EffectSpec{info.kind, {}}});
  }
  return singles;
}

/// One log line per candidate fit: dBIC, model runs, time, and the failure message when asked.
void log_fit(std::ostream& log, const CandidateFit& f, bool with_failure) {
  log << "diagnose: " << f.name() << ": dBIC " << fmt(f.delta_bic, 4) << ", " << f.evaluations << " runs, "
      << fmt(f.seconds, 2) << " s" << (with_failure && !f.converged ? " (" + f.message + ")" : "") << "\n";
}

/// What every candidate fit shares: the baseline, the campaign, its noise, N and the baseline BIC.
struct CandidateJobs {
  const material::MaterialSpec& baseline;
  const Campaign& campaign;
  const DiagnoseOptions& options;
  const Diagnosis& d;
  SpareCores& spare;  ///< cores lent by the threads of a stage that have run out of candidates
  /// The base refit reference is possible: a hyperfoam base with terms.
  bool base_ref() const {
    return baseline.base == material::MaterialSpec::Base::hyperfoam && !baseline.hyperfoam.empty();
  }
  /// The base that joint candidates start from: the base refit when it converged (its factors are the best
  /// base without any effect, so a joint candidate starts no worse than the reference), else the baseline with its dead
  /// Prony terms revived, as the reference started. With base_exponents the refit's first run, before its exponents
  /// were freed: from the refit with its exponents moved, every candidate of the foreign Bouc-Wen case stayed at
  /// 8.6-12.5x noise (friction at 9.8x, strain-dependent Prony + friction named); from its first run friction reaches
  /// 2.5x (docs/physics.md 9.8).
  material::MaterialSpec joint_start() const {
    if (!d.base_refit || !d.base_refit->converged) return with_dead_prony_terms_revived(baseline);
    return d.base_refit->fitted_fixed_exponents ? *d.base_refit->fitted_fixed_exponents : d.base_refit->fitted;
  }
  /// A job fitting these effects (scan: coarse start scan first; refit_base: with the base-refit factors, from
  /// joint_start()).
  std::function<CandidateFit()> job(std::vector<material::EffectSpec> effects, Scan scan, bool refit_base) const {
    return [this, effects = std::move(effects), scan, refit_base] {
      if (refit_base && effects.empty())
        return fit_reference(baseline, campaign, d.noise, d.residuals, d.baseline_bic, options, &spare);
      const material::MaterialSpec base = refit_base ? joint_start() : baseline;
      return fit_candidate(base, effects, campaign, d.noise, d.residuals, d.baseline_bic, options, scan, refit_base,
                           &spare);
    };
  }
};

/// The starts of a single's fit: the catalogue's, and one more per parameter with a second_start (that parameter
/// there, the others at their starts).
std::vector<std::vector<material::EffectSpec>> single_starts(const std::vector<material::EffectSpec>& single) {
  std::vector<std::vector<material::EffectSpec>> starts{single};
  for (const auto& p : material::find_effect(single[0].kind)->parameters)
    if (p.second_start) {
      starts.push_back(single);
      starts.back()[0].parameters[p.name] = *p.second_start;
    }
  return starts;
}

/// The early stop of a damage start (DiagnoseOptions::damage_start_stop_iteration): chi2 still above the base refit's
/// by then is a damage that explains nothing (the estimate took viscous or frictional hysteresis for damage: seed-2027
/// friction c002's damage start ended at dBIC -1711 after 200 model runs).
EarlyStop damage_start_stop(const CandidateJobs& c) {
  return {c.options.damage_start_stop_iteration, c.d.base_refit->chi2,
          "the damage start was still above the base refit without the effect"};
}

/// The damage start of a single whose effect has damage parameters (EffectInfo::damage_limit_parameter): d_inf and e_d
/// estimated from the slowest quasi-static test (logged), the recoverable softening off (EffectInfo::
/// recoverable_softening_parameter at its maximum: the estimate is that of a damage alone, and from the catalogue's
/// Ogden-Roxburgh start r = 2 the exponential damage of seed-2026 c000 ended at dBIC 64 against 294 from there,
/// docs/physics.md 9.48), and a job that refits the base refit's hyperfoam to the first
/// loadings over 1 - d(e) (calibration/damage_start.hpp; inside the job, so that it runs beside the other singles) and
/// then fits the single from there with Levenberg-Marquardt (no start scan: the scan of the effect's six parameters
/// cost about 250 model runs on seed-2027 c017 and c036 and ended no better). None when options.damage_start is off,
/// the base refit did not converge or the estimate finds no damage (d_inf 0: on 13 air-flow and damping campaigns of
/// seeds 2026 and 2027 that start never gave Mullins its best fit); a job whose base cannot be refitted returns a failed
/// fit (dBIC -inf).
std::optional<std::function<CandidateFit()>> damage_start_job(const CandidateJobs& c,
                                                              const std::vector<material::EffectSpec>& single,
                                                              std::ostream& log) {
  const material::EffectInfo* info = material::find_effect(single[0].kind);
  if (!c.options.damage_start || info->damage_limit_parameter.empty() || !c.d.base_refit || !c.d.base_refit->converged)
    return std::nullopt;
  const std::optional<LoadingDamage> damage = estimate_loading_damage(c.campaign, &c.d.base_refit->compare);
  if (!damage) return std::nullopt;
  if (damage->limit <= 0.0) {  // no hysteresis beyond the base refit's: the start would be the base's, fitted twice
    log << "diagnose: " << single[0].kind << " damage start: not made (the slowest quasi-static test's unloading "
        << "over loading shows no damage beyond the base refit's hysteresis)\n";
    return std::nullopt;
  }
  log << "diagnose: " << single[0].kind << " damage start: d_inf " << fmt(damage->limit) << ", e_d "
      << fmt(damage->strain) << " from the slowest quasi-static test's unloading over loading relative to the base "
      << "refit's, the hyperfoam refitted to the first loadings over 1 - d\n";
  std::vector<material::EffectSpec> start = single;
  start[0].parameters[info->damage_limit_parameter] = std::max(damage->limit, 0.01);  // 0 would hold the branch off
  start[0].parameters[info->damage_strain_parameter] = damage->strain;
  for (const material::EffectParameterInfo& p : info->parameters)  // the recoverable softening off: all is damage
    if (p.name == info->recoverable_softening_parameter) start[0].parameters[p.name] = p.max;
  return [&c, start = std::move(start), damage = *damage] {
    const std::optional<material::MaterialSpec> base =
        damaged_loading_base(c.d.base_refit->fitted, c.campaign, c.d.noise, damage);
    if (base)
      return fit_candidate(*base, start, c.campaign, c.d.noise, c.d.residuals, c.d.baseline_bic, c.options, Scan::none,
                           true, &c.spare, damage_start_stop(c));
    CandidateFit failed;
    failed.kinds = {start[0].kind};
    failed.message = "failed: no hyperfoam fits the first loadings over 1 - d (the damage start)";
    failed.delta_bic = -std::numeric_limits<double>::infinity();
    return failed;
  };
}

/// Each single's fit with the larger dBIC among its starts' fits (single_of[j]: the single fit j belongs to), with the
/// model runs and seconds of all its starts.
std::vector<CandidateFit> best_of_starts(std::vector<CandidateFit> all, const std::vector<std::size_t>& single_of,
                                         std::size_t singles) {
  std::vector<std::optional<CandidateFit>> best(singles);
  for (std::size_t j = 0; j < all.size(); ++j) {
    std::optional<CandidateFit>& b = best[single_of[j]];
    if (!b) {
      b = std::move(all[j]);
      continue;
    }
    const int evaluations = b->evaluations + all[j].evaluations;
    const double seconds = b->seconds + all[j].seconds;
    if (all[j].delta_bic > b->delta_bic) b = std::move(all[j]);
    b->evaluations = evaluations, b->seconds = seconds;
  }
  std::vector<CandidateFit> fits;
  for (std::optional<CandidateFit>& b : best) fits.push_back(std::move(*b));
  return fits;
}

/// Candidates: every single effect (with the base-refit factors under joint_base) and the reference, the
/// base refitted WITHOUT any effect. An effect must beat the reference too, else the residual is as well
/// explained by a base calibration that is slightly off. Under joint_base the reference is fitted first and every
/// candidate starts from it (else a joint candidate, 8 base factors plus its own parameters from a cold start,
/// could end worse than the base refit alone within its iteration limit). Returns the singles in catalogue order.
std::vector<CandidateFit> fit_singles_and_reference(const CandidateJobs& c,
                                                    const std::vector<std::vector<material::EffectSpec>>& singles,
                                                    Diagnosis& d, std::ostream& log) {
  const bool joint = c.options.joint_base && c.base_ref();
  std::vector<std::function<CandidateFit()>> jobs;
  if (joint) {  // the reference first: the joint candidates start from it (step 0 may have fitted it already)
    if (!d.base_refit)  // alone: the other threads lend their cores to its Jacobians
      d.base_refit =
          std::move(run_all<CandidateFit>({c.job({}, Scan::all_in_turn, true)}, c.options.threads, {}, &c.spare)[0]);
    log_fit(log, *d.base_refit, false);
  }
  std::vector<std::size_t> single_of;  // the single each job fits (a second start: the same single again)
  for (std::size_t k = 0; k < singles.size(); ++k) {
    for (const auto& start : single_starts(singles[k])) {
      jobs.push_back(c.job(start, Scan::effect, joint));
      single_of.push_back(k);
    }
    if (!joint) continue;
    if (auto damaged = damage_start_job(c, singles[k], log)) {
      jobs.push_back(std::move(*damaged));
      single_of.push_back(k);
    }
  }
  if (c.base_ref() && !joint) jobs.push_back(c.job({}, Scan::all_in_turn, true));
  std::vector<CandidateFit> all = run_all(jobs, c.options.threads, {}, &c.spare);
  if (c.base_ref() && !joint) {
    d.base_refit = std::move(all.back());
    all.pop_back();
    log_fit(log, *d.base_refit, false);
  }
  std::vector<CandidateFit> fits = best_of_starts(std::move(all), single_of, singles.size());
  for (const auto& f : fits) log_fit(log, f, true);
  return fits;
}

/// Indices of `fits`, largest dBIC first.
std::vector<std::size_t> best_first(const std::vector<CandidateFit>& fits) {
  std::vector<std::size_t> order(fits.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return fits[a].delta_bic > fits[b].delta_bic; });
  return order;
}

/// The best leader and the challengers put_leader_ahead ranked after it.
struct LeaderAhead {
  std::size_t leader = 0;           ///< index into the fits
  std::vector<std::size_t> behind;  ///< the challengers moved after it, indices into the fits
};

/// `order` (indices into `fits`, ranked best first) with the challengers ranked before the best leader (a converged
/// single polished because it was supported before its polish) that do not beat it by `margin` moved to just after
/// it, the rest in order: a near miss polished only because a leader was must beat that leader by the evidence
/// threshold to rank ahead of it; within that it is the leader's equal (the rival of the verdict, find_rival), not its
/// successor (docs/physics.md 9.48). Returns the leader and the challengers moved, nothing when none was.
std::optional<LeaderAhead> put_leader_ahead(std::vector<std::size_t>& order, const std::vector<CandidateFit>& fits,
                                            double margin) {
  const auto leader = std::find_if(order.begin(), order.end(), [&](std::size_t i) {
    return fits[i].converged && fits[i].polished && !fits[i].challenger && fits[i].kinds.size() == 1;
  });
  if (leader == order.end()) return std::nullopt;
  LeaderAhead moved{*leader, {}};
  for (auto i = order.begin(); i != leader; ++i)
    if (fits[*i].challenger && fits[*i].delta_bic <= fits[moved.leader].delta_bic + margin) moved.behind.push_back(*i);
  if (moved.behind.empty()) return std::nullopt;
  std::stable_partition(order.begin(), leader + 1, [&](std::size_t i) {
    return std::find(moved.behind.begin(), moved.behind.end(), i) == moved.behind.end();
  });
  return moved;
}

/// Indices of the singles `fits`, best first: by dBIC, the challengers that do not beat the best leader by
/// strong_evidence after it (put_leader_ahead).
std::vector<std::size_t> singles_best_first(const std::vector<CandidateFit>& fits, const DiagnoseOptions& options) {
  std::vector<std::size_t> order = best_first(fits);
  put_leader_ahead(order, fits, options.strong_evidence);
  return order;
}

/// The best single's continuation (fit_polished_only, continue_unfinished_polish): `fit`, the single `single` (index
/// into the singles) fitted once more from its polished fit, with its polished_only parameters free too where it has
/// them.
struct Continuation {
  std::size_t single = 0;
  CandidateFit fit;
};

/// The singles to combine in pairs, best dBIC first: the `pairs_from` best converged ones with dBIC > strong_evidence,
/// none when the best single already brings every test to the noise level (nothing left for a second effect). A single
/// that explains nothing on its own (dBIC 0 to 10) was never part of a right pair: bench seed 2025, three such pairs of
/// 60 campaigns, 5-12 s each, none right. One that explains less alone than two others may still be the second
/// family: seed c001 (Qi-Boyce-like Mullins + exponential strain-dependent Prony), strain-dependent Prony 4th at dBIC 31.7
/// (docs/physics.md 9.15). The best single's continuation (fit_polished_only) at the noise level counts as well.
std::vector<std::size_t> pair_sources(const std::vector<CandidateFit>& fits, const std::optional<Continuation>& more,
                                      const DiagnoseOptions& options) {
  const std::vector<std::size_t> order = singles_best_first(fits, options);
  std::vector<std::size_t> top;
  auto at_noise = [&](const CandidateFit& f) {
    return f.converged && f.compare.at_noise_level(options.compare.noise_level_ratio);
  };
  const bool single_enough = !order.empty() && (at_noise(fits[order.front()]) || (more && at_noise(more->fit)));
  if (!single_enough)
    for (std::size_t i : order)
      if (fits[i].converged && fits[i].delta_bic > options.strong_evidence &&
          static_cast<int>(top.size()) < options.pairs_from)
        top.push_back(i);
  return top;
}

/// A joint pair's fit from `base` (the best single's refitted base) with both effects at their single fits' values:
/// `scan` Scan::added_effect rescans the added effect first, Scan::none starts Levenberg-Marquardt right there.
std::function<CandidateFit()> joint_pair_job(const CandidateJobs& c, const material::MaterialSpec& base,
                                             const std::vector<material::EffectSpec>& e, Scan scan,
                                             const EarlyStop& stop) {
  return [&c, base, e, scan, stop] {
    return fit_candidate(base, e, c.campaign, c.d.noise, c.d.residuals, c.d.baseline_bic, c.options, scan, true,
                         &c.spare, stop);
  };
}

/// The share of the chi2 its best single leaves that a pair's second effect explains, (chi2_single - chi2_pair) /
/// chi2_single (0 when the single leaves nothing).
double pair_share_explained(const CandidateFit& pair, const CandidateFit& single) {
  return single.chi2 > 0.0 ? (single.chi2 - pair.chi2) / single.chi2 : 0.0;
}

/// The parameters of `effects` the catalogue fits in the polish only (EffectParameterInfo::polished_only), "kind name"
/// each, comma-separated; empty when none.
std::string polished_only_names(const std::vector<material::EffectSpec>& effects) {
  std::string names;
  for (const auto& e : effects)
    for (const auto& p : material::find_effect(e.kind)->parameters)
      if (p.polished_only) names += (names.empty() ? "" : ", ") + e.kind + " " + p.name;
  return names;
}

/// The freedoms of the polish (step 2b): `o` with every Prony time and hyperfoam exponent free too, within
/// o.polish_bounds.
DiagnoseOptions polish_freedoms(const DiagnoseOptions& o) {
  DiagnoseOptions free_all = o;
  free_all.base_times = free_all.base_exponents = true;
  free_all.base_bounds = o.polish_bounds;
  return free_all;
}

/// The polish of one single (or of the base refit): refitted from its fit with the freedoms of `free_all`.
CandidateFit polish_single(const CandidateFit& f, const CandidateJobs& c, const DiagnoseOptions& free_all) {
  return refit_with_more_free(f, c.campaign, c.d.noise, c.d.residuals, c.d.baseline_bic, free_all, &c.spare);
}

/// Levenberg-Marquardt stopped `f` at max_iterations with a test still beyond noise: its fit is not finished.
bool stopped_beyond_noise(const CandidateFit& f, const DiagnoseOptions& o) {
  return f.at_iteration_limit && !f.compare.at_noise_level(o.compare.noise_level_ratio);
}

/// The ranking's judgement of a single (supported, its note, challenger), carried from `from` to a refit of it.
void carry_support(CandidateFit& to, const CandidateFit& from) {
  to.supported = from.supported;
  to.support_note = from.support_note;
  to.challenger = from.challenger;
}

/// Where a fit runs: alone in its stage (run_all of the one job: the idle thread lends its core to the fit's
/// Jacobian), or as one job of a stage that runs others (it borrows only the cores their threads lend).
enum class Stage { alone, beside_others };

/// One more run of the single `from` (polished, or the named single of step 4c) from where it ended, with the freedoms
/// of `more`: the new fit when it converged at a lower BIC, with from's polish bookkeeping (and support) carried over,
/// else nothing; its runs and time are charged to `from` either way. `what` and `kept_note` word the log line.
std::optional<CandidateFit> fit_on(CandidateFit& from, const CandidateJobs& c, const DiagnoseOptions& more,
                                   const std::string& what, const std::string& kept_note, Stage stage,
                                   std::ostream& log) {
  const std::function<CandidateFit()> job = [&c, &from, more] { return polish_single(from, c, more); };
  CandidateFit q =
      stage == Stage::alone ? run_all<CandidateFit>({job}, c.options.threads, {}, &c.spare).front() : job();
  const bool kept = q.converged && q.bic < from.bic;
  log << "diagnose: " << from.name() << what << ": dBIC " << fmt(from.delta_bic, 4) << " -> " << fmt(q.delta_bic, 4)
      << ", " << q.evaluations - from.evaluations << " runs, " << fmt(q.seconds - from.seconds, 2) << " s"
      << (kept          ? kept_note
          : q.converged ? " (not kept: no lower BIC)"
                        : " (failed, not kept: " + q.message + ")")
      << "\n";
  from.evaluations = q.evaluations;  // the run's model runs and time count, kept or not
  from.seconds = q.seconds;
  if (!kept) return std::nullopt;
  q.polished = from.polished;
  carry_support(q, from);
  q.polish_added = from.polish_added + (q.parameters - from.parameters);
  q.delta_bic_unpolished = from.delta_bic_unpolished;
  return q;
}

/// Step 2b, continued (DiagnoseOptions::fit_polished_only, continue_unfinished_polish): the best single after the
/// polish, when it was polished and its effect has polished_only parameters (mullins beta) or its polish stopped at the
/// iteration limit with a test beyond noise, fitted once more from its polished fit with those parameters free too;
/// returned when its BIC is lower (the pairs still start from and are judged against the polished fit:
/// rank_candidates). The continuation starts where the polish ended (no dead Prony term revived from a fitted point:
/// with_dead_prony_terms_revived), so it can only lower the chi2: freed together
/// with the Prony times and exponents from the single's fit, beta took two Ogden-Roxburgh campaigns to worse minima
/// than the polish with beta held (docs/physics.md 9.41). Only the best single: it refines the family the singles
/// rank first and does not re-rank the families, since a freedom only one family gets tips near ties (the in-repository
/// Bouc-Wen friction: Mullins polished 3138, with beta 3353, past friction's 3292; docs/physics.md 9.42).
std::optional<Continuation> continue_best_single(const CandidateJobs& c, std::vector<CandidateFit>& fits,
                                                 std::ostream& log) {
  const DiagnoseOptions& o = c.options;
  const std::vector<std::size_t> order = singles_best_first(fits, o);
  if (order.empty()) return std::nullopt;
  CandidateFit& best = fits[order.front()];
  const std::string names = o.fit_polished_only ? polished_only_names(best.effects) : "";
  const bool unfinished = o.continue_unfinished_polish && stopped_beyond_noise(best, o);
  if (!best.converged || !best.polished || (names.empty() && !unfinished)) return std::nullopt;
  DiagnoseOptions more = polish_freedoms(o);
  more.polishing = !names.empty();  // beta free only where fit_polished_only asks for it
  std::optional<CandidateFit> q = fit_on(
      best, c, more,
      " continued from its polish" + (names.empty() ? std::string(" (stopped by the iteration limit beyond noise)")
                                                    : " with " + names + " free too"),
      " (ranks the single; its pairs start from the polish)", Stage::alone, log);
  if (!q) return std::nullopt;
  return Continuation{order.front(), std::move(*q)};
}

/// Rounds 2 .. continuation_rounds of a single whose continuation (continue_best_single) was kept: while its last fit
/// stopped at max_iterations with a test beyond noise, it is fitted on from there with the continuation's freedoms
/// (fit_on, max_iterations a round), and again only while a round lowers the BIC by at least strong_evidence. `named`
/// ends as the last fit kept, every round's runs and time charged to it.
void fit_in_rounds(CandidateFit& named, const CandidateJobs& c, Stage stage, std::ostream& log) {
  const DiagnoseOptions& o = c.options;
  DiagnoseOptions more = polish_freedoms(o);
  more.polishing = o.fit_polished_only && !polished_only_names(named.effects).empty();
  for (int round = 2; round <= o.continuation_rounds; ++round) {
    if (!stopped_beyond_noise(named, o)) return;
    const std::string what =
        ", named, fitted on (round " + std::to_string(round) + " of " + std::to_string(o.continuation_rounds) + ")";
    std::optional<CandidateFit> q = fit_on(named, c, more, what, "", stage, log);
    if (!q) return;
    const bool small_gain = named.bic - q->bic < o.strong_evidence;
    named = std::move(*q);
    if (small_gain) return;
  }
}

/// The rounds (fit_in_rounds) of the continued best single, fitted ahead as one job of the pair stage (fit_pairs)
/// before the ranking says whether that single is named alone: `end` and `log` are what fit_in_rounds made of the
/// continuation and wrote. Results and log lines are those of the rounds run after the ranking; only the wall time
/// differs (a round is a chain of serial fits whose trial steps use one core: beside the pairs the other core is kept
/// busy; docs/physics.md 9.46). Unused (its time spent for nothing) when a pair or another single is named.
struct RoundsAhead {
  std::string name;  ///< the continuation it starts from: name, BIC and runs, to recognise it after the ranking
  double start_bic = 0.0;
  int start_evaluations = 0;
  CandidateFit end;
  std::string log;
  bool starts_from(const CandidateFit& f) const {
    return f.name() == name && f.bic == start_bic && f.evaluations == start_evaluations;
  }
};

/// A single of the kind refine_named_single fits on in rounds when named alone: polished, one effect, the
/// continuations on.
bool fitted_on_when_named(const CandidateFit& f, const DiagnoseOptions& o) {
  return o.continue_unfinished_polish && f.kinds.size() == 1 && f.polished;
}

/// Whether the continuation `more` would be fitted on in rounds if named alone (refine_named_single), and on more than
/// one thread, so that fitting them ahead can overlap the pairs (on one it would only add their time when unused).
bool rounds_ahead_worth(const std::optional<Continuation>& more, const DiagnoseOptions& o) {
  return more && o.threads > 1 && o.continuation_rounds >= 2 && fitted_on_when_named(more->fit, o) &&
         stopped_beyond_noise(more->fit, o);
}

/// The job of the pair stage that fits the rounds ahead from the continuation `more` (rounds_ahead_worth).
std::function<RoundsAhead()> rounds_ahead_job(const CandidateJobs& c, const Continuation& more) {
  return [&c, &more] {
    RoundsAhead r{more.fit.name(), more.fit.bic, more.fit.evaluations, more.fit, ""};
    std::ostringstream log;
    fit_in_rounds(r.end, c, Stage::beside_others, log);
    r.log = log.str();
    return r;
  };
}

/// Step 4b (DiagnoseOptions::continuation_rounds): a single named alone whose continuation (continue_best_single) was
/// kept and still stopped at max_iterations with a test beyond noise is fitted on in rounds (fit_in_rounds; taken
/// from `ahead` when the pair stage fitted them for this continuation). Every candidate was ranked at the same budget;
/// this only takes the named model to where its fit ends, for its parameters and its error after (seed-2026 c059,
/// Ogden-Roxburgh: 3.83 -> 1.31x noise; docs/physics.md 9.45). It runs after the ranking so that it cannot rank a
/// single above a pair fitted at the budget of the others (seed-2026 c055's friction + Mullins fell below Mullins
/// fitted for three rounds).
void refine_named_single(const CandidateJobs& c, bool continued, std::optional<RoundsAhead> ahead, Diagnosis& d,
                         std::ostream& log) {
  const DiagnoseOptions& o = c.options;
  if (!continued || d.candidates.empty()) return;
  CandidateFit& named = d.candidates.front();
  if (!named.supported || !fitted_on_when_named(named, o)) return;
  if (!ahead || !ahead->starts_from(named)) return fit_in_rounds(named, c, Stage::alone, log);
  CandidateFit& end = ahead->end;
  carry_support(end, named);  // as the ranking judged the single, as fit_on carries it in the serial rounds
  named = std::move(end);
  log << ahead->log;
}

/// The named single's effect with each held parameter that has a catalogue named_value (not at it already) set to it,
/// and those parameters in words ("stretch_exponent 1"); nothing when there is none.
std::optional<std::pair<material::EffectSpec, std::string>> named_form(const material::EffectSpec& e) {
  std::pair<material::EffectSpec, std::string> alt{e, ""};
  for (const auto& p : material::find_effect(e.kind)->parameters) {
    if (p.fit || !p.named_value) continue;
    const auto it = e.parameters.find(p.name);
    if ((it != e.parameters.end() ? it->second : p.default_value) == *p.named_value) continue;
    alt.first.parameters[p.name] = *p.named_value;
    alt.second += (alt.second.empty() ? "" : ", ") + p.name + " " + fmt(*p.named_value);
  }
  if (alt.second.empty()) return std::nullopt;
  return alt;
}

/// Step 4c (catalogue EffectParameterInfo::named_value): the single named alone, fitted once more from its own fit
/// (its base and effect; the polish's freedoms when it was polished) with its effect's held parameters at their
/// named_value (fit_on), kept when its BIC is lower and then fitted on in rounds as the named single would be
/// (fitted_on_when_named, fit_in_rounds). After the ranking and the rounds, so that it chooses the named family's form,
/// not the family (docs/physics.md 9.49).
void refit_named_form(const CandidateJobs& c, Diagnosis& d, std::ostream& log) {
  if (d.candidates.empty() || !d.candidates.front().supported) return;
  CandidateFit& named = d.candidates.front();
  if (named.kinds.size() != 1 || !named.converged) return;
  const auto alt = named_form(named.effects.front());
  if (!alt) return;
  CandidateFit start = named;  // its BIC, support and bookkeeping are the named fit's: fit_on compares with them
  start.effects = {alt->first};
  DiagnoseOptions more = named.polished ? polish_freedoms(c.options) : c.options;
  more.polishing = c.options.fit_polished_only && !polished_only_names(named.effects).empty();
  std::optional<CandidateFit> q = fit_on(start, c, more, ", named, fitted again with " + alt->second,
                                         " (kept: the named model)", Stage::alone, log);
  named.evaluations = start.evaluations;  // its runs and time count, kept or not
  named.seconds = start.seconds;
  if (!q) return;
  if (fitted_on_when_named(*q, c.options)) fit_in_rounds(*q, c, Stage::alone, log);
  q->support_note += std::string(q->support_note.empty() ? "" : "; ") + "named: fitted again with " + alt->second +
                     ", dBIC " + fmt(named.delta_bic, 4) + " before";
  named = std::move(*q);
}

/// The early stop of a pair whose best single leaves chi2_single: after pair_stop_iteration iterations, chi2 above
/// (1 - pair_stop_share) chi2_single (DiagnoseOptions::pair_stop_share; none when it is 0).
EarlyStop pair_stop(const DiagnoseOptions& o, double chi2_single) {
  if (o.pair_stop_share <= 0.0 || !std::isfinite(chi2_single)) return {};
  return {
      o.pair_stop_iteration, (1.0 - o.pair_stop_share) * chi2_single,
      "its second effect explained too little of the chi2 the best single leaves to reach the pair share by the end "
      "(--pair-stop-share)"};
}

/// A pair's fit and, when its scanned fit ended no better than the best single, the refit from the plain sum (both in
/// one job, so that a thread that has finished its pair goes on with its own refit instead of waiting for the others).
struct PairOutcome {
  CandidateFit kept;      ///< the lower-BIC fit, reporting both fits' runs and seconds
  std::string refit_log;  ///< the log line of the refit from the plain sum (empty: none was needed)
};

/// A pair started from the polished best single's base also counts the parameters that polish freed.
void count_inherited_polish(CandidateFit& f, const CandidateFit& best, const Diagnosis& d) {
  if (best.polish_added > 0 && std::isfinite(f.bic)) {
    f.polish_added = best.polish_added;  // its base's Prony times and exponents were refitted, in that single's polish
    f.parameters += best.polish_added;
    f.bic += best.polish_added * std::log(static_cast<double>(d.residuals));
    f.delta_bic = d.baseline_bic - f.bic;
  }
}

/// A joint pair of `best` with one more effect (`effects`: best's, then the added one) from best's base: the scanned
/// fit and, when its second effect explains less than pair_stop_share of the chi2 best leaves (or it fails), the refit
/// from the plain sum, the lower BIC kept (fit_pairs).
PairOutcome fit_joint_pair(const CandidateJobs& c, const CandidateFit& best,
                           const std::vector<material::EffectSpec>& effects, const EarlyStop& stop) {
  const material::MaterialSpec base = base_of(best);
  PairOutcome out;
  CandidateFit& scanned = out.kept;
  scanned = joint_pair_job(c, base, effects, Scan::added_effect, stop)();
  count_inherited_polish(scanned, best, c.d);
  const double share = pair_share_explained(scanned, best);
  const bool switched_off = share < c.options.pair_stop_share;
  if (scanned.converged && scanned.delta_bic > best.delta_bic && !switched_off) return out;
  CandidateFit sum = joint_pair_job(c, base, effects, Scan::none, stop)();
  count_inherited_polish(sum, best, c.d);
  const std::string why = !scanned.converged ? "its scanned fit failed"
                          : switched_off ? "its second effect explains " + fmt(100.0 * share, 2) + " % of the chi2 " +
                                               best.name() + " leaves (the scan switched it off below " +
                                               fmt(100.0 * c.options.pair_stop_share, 2) + " %)"
                                         : "no better than " + best.name() + " alone";
  out.refit_log = "diagnose: " + scanned.name() + ": " + why +
                  ": fitted again from both single fits without a scan: dBIC " + fmt(scanned.delta_bic, 4) + " -> " +
                  fmt(sum.delta_bic, 4) + ", " + std::to_string(sum.evaluations) + " runs, " + fmt(sum.seconds, 2) +
                  " s" + (sum.converged ? "" : " (failed: " + sum.message + ")") + "\n";
  const int runs = scanned.evaluations + sum.evaluations;  // the kept fit reports both fits' cost
  const double seconds = scanned.seconds + sum.seconds;
  if (sum.converged && (!scanned.converged || sum.bic < scanned.bic)) scanned = std::move(sum);
  scanned.evaluations = runs;
  scanned.seconds = seconds;
  return out;
}

/// The pair stage: the pairs and, fitted beside them, the continued best single's rounds (RoundsAhead).
struct PairStage {
  std::vector<CandidateFit> pairs;
  std::optional<RoundsAhead> rounds;
};

/// Pairs of the best single with each of the next best, started from their single fits (a pair without the best single
/// was never within strong_evidence of the best pair: bench seed 2025, session-14 code, 20 campaigns with three pairs,
/// dBIC 151 to 4643 below it, and the slowest of the three in 7); a joint pair starts from the better
/// single's refitted base, so that it starts where that single ended, and then scans the effects' parameters (the second
/// effect's parameters were fitted with another base and both effects explain part of the same residual, so the
/// plain sum can start far worse than either single: measured on a foreign stiffness-proportional campaign,
/// stiffness_damping + pneumatic ended at dBIC -1198 after 955 runs and 65 s without the scan).
///
/// A joint pair whose scanned fit leaves its second effect switched off (explaining less than pair_stop_share of the
/// chi2 the best single leaves, the share below which a pair's fit is stopped early) is fitted again from the plain sum
/// (Scan::none), and the lower BIC kept: where the best single's base has absorbed part of the added effect, the sum
/// overshoots, the scan steps the added effect down until it is switched off (chi2 then equals the single's), and
/// Levenberg-Marquardt has no gradient left there. Foreign c046 (Jenkins friction + Ogden-Roxburgh Mullins, scale set):
/// the scan ended with the friction stiffness at 1.1e-3 kPa (single fit 2.69, truth 2.29), dBIC 578 against the
/// single's 590; from the sum, 675 with every test within 1.16x noise (docs/physics.md 9.19). Until 2026-12-06 the refit
/// ran only when the scanned fit ended no better than the single: seed-2026 c011 (stretch-Maxwell air flow +
/// Ogden-Roxburgh Mullins) kept a scanned Mullins + air flow 4 dBIC above Mullins alone (0.4 % of its chi2) and named
/// Mullins alone; from the sum the pair explains 70 % and is named. A refit of every pair below pair_share gained no
/// other verdict on three sets and named four spurious or wrong second families, all from scanned fits at 13-23 %
/// (docs/physics.md 9.37).
///
/// Both fits of a pair stop after pair_stop_iteration iterations when the second effect still explains less than
/// pair_stop_share of the chi2 the best single leaves (pair_stop; a stopped scanned fit is then fitted from the sum).
/// A pair's refit runs in the pair's own job, right after its scanned fit (PairOutcome): as two stages, the refits
/// waited for the slowest scanned pair (docs/physics.md 9.32).
///
/// The rounds of the continued best single are fitted beside the pairs, as one more job of the stage, when it would be
/// fitted on if named alone (rounds_ahead_worth; RoundsAhead), and only when there are pairs to fit beside.
PairStage fit_pairs(const CandidateJobs& c, const std::vector<CandidateFit>& fits, const std::vector<std::size_t>& top,
                    const std::optional<Continuation>& more, std::ostream& log) {
  const bool joint = c.options.joint_base && c.base_ref();
  const CandidateFit* best = top.empty() ? nullptr : &fits[top.front()];
  const EarlyStop stop = best ? pair_stop(c.options, best->chi2) : EarlyStop{};
  using Outcome = std::variant<PairOutcome, RoundsAhead>;
  std::vector<std::function<Outcome()>> jobs;
  std::vector<double> expected_seconds;  // a pair costs about what its two singles cost together
  for (std::size_t b = 1; b < top.size(); ++b) {
    expected_seconds.push_back(best->seconds + fits[top[b]].seconds);
    std::vector<material::EffectSpec> effects = best->effects;
    effects.push_back(fits[top[b]].effects.front());
    if (joint)
      jobs.push_back([&c, best, effects, stop] { return Outcome{fit_joint_pair(c, *best, effects, stop)}; });
    else
      jobs.push_back([job = c.job(effects, Scan::none, false)] {
        PairOutcome out;
        out.kept = job();
        return Outcome{std::move(out)};
      });
  }
  if (!jobs.empty() && rounds_ahead_worth(more, c.options)) {
    jobs.push_back([rounds = rounds_ahead_job(c, *more)] { return Outcome{rounds()}; });
    // Started first: up to continuation_rounds - 1 fits one after another, each about a pair's cost.
    expected_seconds.push_back(std::numeric_limits<double>::infinity());
  }
  std::vector<Outcome> outcomes = run_all(jobs, c.options.threads, expected_seconds, &c.spare);
  PairStage stage;
  for (Outcome& o : outcomes) {
    if (RoundsAhead* r = std::get_if<RoundsAhead>(&o)) {
      stage.rounds = std::move(*r);
      continue;
    }
    PairOutcome& pair = std::get<PairOutcome>(o);
    log << pair.refit_log;
    stage.pairs.push_back(std::move(pair.kept));
  }
  for (const auto& f : stage.pairs) log_fit(log, f, false);
  return stage;
}

/// The base-refit reference converged and brings every test to the noise level: nothing is left for an effect.
bool base_refit_at_noise(const Diagnosis& d, const DiagnoseOptions& options) {
  return d.base_refit && d.base_refit->converged &&
         d.base_refit->compare.at_noise_level(options.compare.noise_level_ratio);
}

/// The dBIC a candidate must beat the reference by: strong_evidence, infinite (nothing is named) when the base refit
/// brings every test to the noise level from a baseline that is not there (a base that had to move that far may be
/// of the wrong form: DiagnoseForeign.BaseMismatchInventsNoEffect, whose best effect beats the refit by 69). From a
/// baseline already at the noise level the refit barely moves and the margin stays strong_evidence
/// (DiagnoseOptions::stop_at_noise, docs/physics.md 9.33).
double support_margin(const Diagnosis& d, const DiagnoseOptions& options) {
  return !d.at_noise_level && base_refit_at_noise(d, options) ? std::numeric_limits<double>::infinity()
                                                              : options.strong_evidence;
}

/// dBIC of the base-refit reference when it converged (0 when below 0 or absent).
double base_gain(const Diagnosis& d) {
  return d.base_refit && d.base_refit->converged ? std::max(0.0, d.base_refit->delta_bic) : 0.0;
}

/// dBIC a single must beat by support_margin: the base-refit reference's (0 when below 0 or absent), except from a
/// baseline already at the noise level with joint candidates, where it is the reference's own dBIC even below 0. There the baseline and its
/// refit are the same material within the noise (the refit's dBIC is its parameters' penalty, -36 to -45 on the
/// benchmark's at-noise campaigns) and every joint candidate nests the refit, so the nested comparison is the one
/// that counts: on the 20 controls of two benchmark sets every candidate ends 6.6-12 below the refit (about its own
/// penalty, no chi2 gained), while weak effects the fitted base holds within 1.5x end 17-101 above it (docs/physics.md 9.33).
double support_gain(const Diagnosis& d, const DiagnoseOptions& options) {
  const bool nested = options.joint_base && d.at_noise_level && d.base_refit && d.base_refit->converged;
  return nested ? d.base_refit->delta_bic : base_gain(d);
}

/// dBIC of the polished base refit when it converged (the unpolished reference's gain when larger or absent): the
/// reference a challenger must beat.
double polished_base_gain(const Diagnosis& d) {
  const double gain = base_gain(d);
  const auto& p = d.polished_base_refit;
  return p && p->converged ? std::max(gain, p->delta_bic) : gain;
}

/// Step 2b: the options.polished_singles best singles that beat the reference by strong_evidence (leaders) and, when
/// there is a leader, the options.polished_challengers best near misses (challengers: above the reference's dBIC but
/// not by strong_evidence beyond it) with the base refit beside them, each refitted from its own fit with every Prony
/// time and hyperfoam exponent free as well (DiagnoseOptions::polished_singles, polished_challengers); the polished
/// fit replaces the single's whenever it converged (so that the singles are ranked on the same footing), keeping the
/// dBIC before it. Returns the polished base refit (Diagnosis::polished_base_refit) when a challenger was polished.
std::optional<CandidateFit> polish_leading_singles(const CandidateJobs& c, std::vector<CandidateFit>& fits,
                                                   std::ostream& log) {
  const DiagnoseOptions& o = c.options;
  const Diagnosis& d = c.d;
  const double margin = support_margin(d, o);
  if (o.polished_singles <= 0 || !o.joint_base || !c.base_ref() || !std::isfinite(margin)) return std::nullopt;
  const bool reference = d.base_refit && d.base_refit->converged;
  // near miss: above the reference's own dBIC, below it + strong_evidence (a single below the reference explains
  // less than the base refit already does)
  auto near_miss = [&](const CandidateFit& f) { return reference && f.delta_bic > d.base_refit->delta_bic; };
  std::vector<std::size_t> leaders, challengers;
  for (std::size_t i : best_first(fits)) {
    if (!fits[i].converged) continue;
    if (fits[i].delta_bic > support_gain(d, o) + margin) {
      if (static_cast<int>(leaders.size()) < o.polished_singles) leaders.push_back(i);
    } else if (near_miss(fits[i]) && static_cast<int>(challengers.size()) < o.polished_challengers) {
      challengers.push_back(i);
    }
  }
  if (leaders.empty()) challengers.clear();
  const DiagnoseOptions free_all = polish_freedoms(o);
  std::vector<std::size_t> singles = leaders;  // the singles to polish: the leaders, then the challengers
  singles.insert(singles.end(), challengers.begin(), challengers.end());
  std::vector<const CandidateFit*> polish;  // their fits, then the base refit when there are challengers
  for (std::size_t i : singles) polish.push_back(&fits[i]);
  if (!challengers.empty()) polish.push_back(&*d.base_refit);
  std::vector<std::function<CandidateFit()>> jobs;
  std::vector<double> expected_seconds;
  for (const CandidateFit* f : polish) {
    expected_seconds.push_back(f->seconds);
    jobs.push_back([&c, f, free_all] { return polish_single(*f, c, free_all); });
  }
  std::vector<CandidateFit> polished = run_all(jobs, o.threads, expected_seconds, &c.spare);
  for (std::size_t j = 0; j < polish.size(); ++j) {
    const CandidateFit& p = polished[j];
    const bool reference_job = j == singles.size();  // kept even when it failed
    const char* role = j < leaders.size() ? "" : reference_job ? " (the challengers' reference)" : " (challenger)";
    log << "diagnose: " << polish[j]->name() << role << " polished (Prony times and hyperfoam exponents free): dBIC "
        << fmt(polish[j]->delta_bic, 4) << " -> " << fmt(p.delta_bic, 4) << ", " << p.evaluations << " runs, "
        << fmt(p.seconds, 2) << " s"
        << (p.converged ? "" : (reference_job ? " (failed: " : " (failed, not kept: ") + p.message + ")") << "\n";
  }
  std::optional<CandidateFit> polished_reference;
  if (!challengers.empty()) {
    polished_reference = std::move(polished.back());
    polished.pop_back();
  }
  for (std::size_t j = 0; j < polished.size(); ++j) {
    CandidateFit& f = fits[singles[j]];
    CandidateFit& p = polished[j];
    if (!p.converged) continue;
    p.polished = true;
    p.challenger = j >= leaders.size();  // judged against the polished reference
    p.polish_added = p.parameters - f.parameters;
    p.delta_bic_unpolished = f.delta_bic;
    f = std::move(p);
  }
  return polished_reference;
}

/// `ranked` (supported first, then by dBIC) with the supported challengers that do not beat the best leader by
/// `margin` ranked after it (put_leader_ahead), each saying so.
void rank_leader_ahead(std::vector<CandidateFit>& ranked, double margin) {
  std::vector<std::size_t> order(ranked.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const std::optional<LeaderAhead> moved = put_leader_ahead(order, ranked, margin);
  if (!moved) return;
  for (std::size_t i : moved->behind)
    ranked[i].support_note = "ranked after " + ranked[moved->leader].name() +
                             ": a challenger must beat the leader by the evidence threshold, dBIC " + fmt(margin);
  std::vector<CandidateFit> reordered;
  for (std::size_t i : order) reordered.push_back(std::move(ranked[i]));
  ranked = std::move(reordered);
}

/// Ranking: a single is supported when it beats the reference by strong_evidence, a pair when it beats the
/// best single and the reference by strong_evidence and explains pair_share of the chi2 the best single leaves, none
/// when the reference alone brings every test to the noise level; supported first, then by dBIC; warnings for failed or
/// unconverged candidates. The pairs are judged against the best single they started from (its polish); the single is
/// then ranked by its continuation (`more`, fit_polished_only) where there is one.
void rank_candidates(std::vector<CandidateFit> fits, std::vector<CandidateFit> pairs,
                     const std::vector<std::size_t>& top, std::optional<Continuation> more,
                     const DiagnoseOptions& options, Diagnosis& d) {
  const double gain = support_gain(d, options);
  const double margin = support_margin(d, options);  // infinite: nothing is supported
  const double best_single = top.empty() ? 0.0 : fits[top.front()].delta_bic;
  for (auto& f : pairs) {
    f.supported = f.converged && f.delta_bic > std::max(best_single, gain) + margin;
    const double share = top.empty() ? 0.0 : pair_share_explained(f, fits[top.front()]);
    if (f.supported && !top.empty() && share < options.pair_share) {
      f.supported = false;
      f.support_note = "its second effect explains " + fmt(100.0 * share, 2) + " % of the chi2 that " +
                       fits[top.front()].name() + " leaves; a pair must explain " + fmt(100.0 * options.pair_share, 2) +
                       " %";
    }
  }
  if (more) fits[more->single] = std::move(more->fit);
  for (auto& f : fits)
    f.supported = f.converged && f.support_delta_bic() > (f.challenger ? polished_base_gain(d) : gain) + margin;
  for (auto& f : fits) d.candidates.push_back(std::move(f));
  for (auto& f : pairs) d.candidates.push_back(std::move(f));
  for (const auto& f : d.candidates)
    if (!f.converged) d.warnings.push_back("candidate " + f.name() + ": " + f.message);
    else if (!f.warning.empty()) d.warnings.push_back("candidate " + f.name() + ": " + f.warning);
  if (d.base_refit && !d.base_refit->converged)
    d.warnings.push_back("candidate " + d.base_refit->name() + ": " + d.base_refit->message);
  std::stable_sort(d.candidates.begin(), d.candidates.end(), [](const CandidateFit& a, const CandidateFit& b) {
    if (a.supported != b.supported) return a.supported;
    return a.delta_bic > b.delta_bic;
  });
  rank_leader_ahead(d.candidates, options.strong_evidence);
}

/// A campaign reduced to some of its material-level tests (index order: quasi-static, then dynamic) with
/// the noise estimates of the tests kept; structure-level tests are kept as they are.
struct CampaignSubset {
  Campaign campaign;
  std::vector<TestNoise> noise;
};

CampaignSubset subset(const Campaign& c, const std::vector<TestNoise>& noise, const std::function<bool(std::size_t)>& keep) {
  CampaignSubset s{c, {}};
  s.campaign.quasi_static.clear();
  s.campaign.dynamic.clear();
  const std::size_t nq = c.quasi_static.size();
  for (std::size_t k = 0; k < nq + c.dynamic.size(); ++k) {
    if (!keep(k)) continue;
    if (k < nq) s.campaign.quasi_static.push_back(c.quasi_static[k]);
    else s.campaign.dynamic.push_back(c.dynamic[k - nq]);
    if (k < noise.size()) s.noise.push_back(noise[k]);
  }
  return s;
}

/// chi2 of one test of a comparison.
double test_chi2(const TestCompare& t, int points) {
  CompareResult one;
  one.tests = {t};
  return chi2_of(one, points);
}


/// Refits `f` (from its full-campaign fit) on every material-level test but `held`, then predicts `held`:
/// its chi2, or NaN when the refit or the prediction fails.
double held_out_chi2(const CandidateFit& f, const CandidateJobs& c, std::size_t held) {
  const auto& points = c.options.quasi_static_points;
  const CampaignSubset rest = subset(c.campaign, c.d.noise, [&](std::size_t k) { return k != held; });
  const CampaignSubset one = subset(c.campaign, c.d.noise, [&](std::size_t k) { return k == held; });
  CompareResult kept = f.compare;
  kept.tests.erase(kept.tests.begin() + static_cast<std::ptrdiff_t>(held));
  DiagnoseOptions o = c.options;
  o.max_iterations = c.options.held_out_iterations;
  const std::size_t n_rest = normalised_residuals(kept, points).size();
  if (n_rest == 0) return std::numeric_limits<double>::quiet_NaN();
  const CandidateFit refit =
      fit_candidate(base_of(f), f.effects, rest.campaign, rest.noise, n_rest, 0.0, o, Scan::none, f.base_refitted);
  if (refit.message.rfind("failed", 0) == 0) return std::numeric_limits<double>::quiet_NaN();
  try {
    const material::MaterialDefinition def = material::build_material(refit.fitted, "held-out refit");
    const CompareResult r = compare_campaign(*def.model, one.campaign, c.options.compare, one.noise);
    if (r.tests.empty() || !r.tests.front().failure.empty()) return std::numeric_limits<double>::quiet_NaN();
    return test_chi2(r.tests.front(), points);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

/// The leave-one-test-out check of candidate `f` (HeldOutCheck) against the base refit (or, without one, the
/// baseline as given, which has nothing to refit).
HeldOutCheck check_held_out(const CandidateFit& f, const CandidateJobs& c, std::ostream& log) {
  const auto t0 = Clock::now();
  HeldOutCheck h;
  h.candidate = f.name();
  const Diagnosis& d = c.d;
  const bool reference_refit = d.base_refit && d.base_refit->converged;
  std::vector<std::size_t> held;
  for (std::size_t i = 0; i < d.noise.size() && i < f.compare.tests.size(); ++i)
    if (d.noise[i].known) held.push_back(i);
  if (held.size() < 2) {  // nothing would be left to fit on
    h.possible = false;
    h.failure = "fewer than two tests with a noise estimate: nothing to hold out";
    log << "diagnose: held-out check of " << h.candidate << ": not possible (" << h.failure << ")\n";
    return h;
  }
  std::vector<std::function<double()>> jobs;  // held-out chi2 of the candidate (and the reference) per test
  for (std::size_t i : held) {
    jobs.push_back([&f, &c, i] { return held_out_chi2(f, c, i); });
    if (reference_refit) jobs.push_back([&d, &c, i] { return held_out_chi2(*d.base_refit, c, i); });
  }
  const std::vector<double> out = run_all(jobs, c.options.threads);
  const std::size_t per = reference_refit ? 2 : 1;
  for (std::size_t j = 0; j < held.size(); ++j) {
    const double cand = out[per * j];
    const double ref = reference_refit ? out[per * j + 1] : test_chi2(d.baseline.tests[held[j]], c.options.quasi_static_points);
    h.tests.push_back(d.baseline.tests[held[j]].name);
    h.chi2_candidate.push_back(cand);
    h.chi2_reference.push_back(ref);
    h.total_candidate += cand;
    h.total_reference += ref;
    if (!std::isfinite(cand) || !std::isfinite(ref))
      h.failure = "the refit without " + h.tests.back() + " or its prediction failed";
  }
  h.confirmed = h.failure.empty() && h.total_candidate < h.total_reference - c.options.held_out_margin;
  h.seconds = seconds_since(t0);
  log << "diagnose: held-out check of " << h.candidate << ": chi2 of the left-out tests " << fmt(h.total_candidate, 4)
      << " vs " << fmt(h.total_reference, 4) << (reference_refit ? " (base refit)" : " (baseline)") << ": "
      << (h.confirmed ? "confirmed" : "NOT confirmed" + (h.failure.empty() ? "" : " (" + h.failure + ")")) << ", "
      << fmt(h.seconds, 2) << " s\n";
  return h;
}

/// Checks the supported candidates out of sample, best first (at most three), and moves the first confirmed
/// one to the front; the ones that fail lose their support. No-op unless options.held_out.
void confirm_out_of_sample(const CandidateJobs& c, Diagnosis& d, std::ostream& log) {
  if (!c.options.held_out) return;
  for (std::size_t i = 0; i < d.candidates.size() && i < 3 && d.candidates[i].supported; ++i) {
    d.held_out.push_back(check_held_out(d.candidates[i], c, log));
    if (!d.held_out.back().possible) return;  // a campaign too small to hold a test out: in-sample evidence only
    if (d.held_out.back().confirmed) {
      std::rotate(d.candidates.begin(), d.candidates.begin() + static_cast<std::ptrdiff_t>(i),
                  d.candidates.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      return;
    }
    d.candidates[i].supported = false;
  }
}

/// One effect as a material-file entry: {"kind": ..., parameter: value, ...}.
nlohmann::json effect_json(const material::EffectSpec& e) {
  nlohmann::json j{{"kind", e.kind}};
  for (const auto& [k, v] : e.parameters) j[k] = v;
  return j;
}

/// The "effects" fragment: the baseline's effects plus the winner's, in material::composition_order.
nlohmann::json effects_fragment(const material::MaterialSpec& baseline, const CandidateFit& w) {
  std::vector<material::EffectSpec> all = baseline.effects;
  all.insert(all.end(), w.effects.begin(), w.effects.end());
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : material::composition_order(std::move(all))) effects.push_back(effect_json(e));
  nlohmann::json fragment = {{"effects", effects}};
  return fragment;
}

/// The winner's kinds as `--candidates` takes them, comma-separated.
std::string candidates_option(const CandidateFit& w) {
  std::string kinds;
  for (const auto& k : w.kinds) kinds += (kinds.empty() ? "" : ",") + k;
  return kinds;
}

/// The follow-up for a polished winner left beyond noise while the polish kept the base's Prony times and exponents
/// within narrower bounds (DiagnoseOptions::polish_bounds) than follow_up_polish_bounds; empty otherwise.
std::string wider_polish_sentence(const DiagnoseOptions& options, const CandidateFit& w) {
  const BaseFactorBounds& now = options.polish_bounds;
  const BaseFactorBounds& wide = follow_up_polish_bounds;
  if (w.polish_added == 0 || (now.time_decades >= wide.time_decades && now.exponent_decades >= wide.exponent_decades))
    return "";
  const std::string kinds = candidates_option(w);
  std::ostringstream o;
  o << " The polish moved the base's Prony times by at most a factor " << fmt(std::pow(10.0, now.time_decades), 3)
    << " and its hyperfoam exponents by " << fmt(std::pow(10.0, now.exponent_decades), 3)
    << ": if the base `cushion fit` placed is further off, diagnose again with `--candidates " << kinds
    << " --polish-bounds " << fmt(wide.time_decades) << "," << fmt(wide.exponent_decades) << "` (factors up to "
    << fmt(std::pow(10.0, wide.time_decades), 3) << " and " << fmt(std::pow(10.0, wide.exponent_decades), 3)
    << "; docs/physics.md 9.35).";
  return o.str();
}

/// The follow-up for a polished winner left beyond noise whose first effect (the polished single's) holds a
/// polished_only parameter at its default (mullins beta) because options.fit_polished_only is off
/// (`--no-polish-mullins-beta`); empty otherwise (docs/physics.md 9.41).
std::string polished_only_sentence(const DiagnoseOptions& options, const CandidateFit& w) {
  const std::string names = w.effects.empty() ? "" : polished_only_names({w.effects.front()});
  if (options.fit_polished_only || w.polish_added == 0 || names.empty()) return "";
  const std::string kinds = candidates_option(w);
  return " It held " + names + " at its default (`--no-polish-mullins-beta`): `--candidates " + kinds +
         " --polish-mullins-beta` fits it after the polish (docs/physics.md 9.41-9.42).";
}

/// Verdict with a supported winner (candidates.front()): add it, its fragment, the extended material, and
/// the tests still beyond noise.
void winner_verdict(const material::MaterialSpec& baseline, const DiagnoseOptions& options, Diagnosis& d) {
  d.winner = 0;
  const CandidateFit& w = d.candidates.front();
  d.winner_at_noise_level = w.compare.at_noise_level(options.compare.noise_level_ratio);
  d.fragment = effects_fragment(baseline, w);
  d.extended = w.fitted;
  std::ostringstream o;
  o << "Add " << w.name() << " (dBIC " << fmt(w.delta_bic, 4) << " for " << w.parameters
    << " parameters; chi2/N " << fmt(d.baseline_chi2 / d.residuals) << " -> " << fmt(w.chi2 / d.residuals) << "). ";
  if (w.base_refitted)
    o << "Fitted together with the base (joint): use material_extended.json, whose "
      << refitted_base_parameters(options, w.polish_added > 0)
      << " are refitted too; the fragment alone on the old base is not the fitted model. ";
  if (d.winner_at_noise_level) {
    o << "With it every test falls to the noise level (within " << fmt(options.compare.noise_level_ratio, 2) << "x).";
  } else {
    o << "Tests still beyond noise after adding it:";
    for (const auto& t : w.compare.tests)
      if (t.noise_ratio() > options.compare.noise_level_ratio) o << " " << t.name << " (" << fmt(t.noise_ratio(), 3) << "x)";
    o << ": the effect's form in cushion may not follow the data's (its family can be right while the measured effect "
         "has another functional form, e.g. an air flow whose resistance is a power of the rate), the base calibration is "
         "off there, or a further effect outside the catalogue is missing (rerun `cushion fit`, then diagnose again).";
    o << wider_polish_sentence(options, w) << polished_only_sentence(options, w);
  }
  d.verdict = o.str();
}

/// The winner's sweeps run once more at half the steps per cycle (CompareOptions::step_check, add_step_errors on the
/// winner's comparison): each dynamic test's step_error, the warnings of a step that moves a sweep beyond
/// step_error_warning, and a sentence in the verdict then: the fitted parameters carry that error, and a finer step is
/// proposed. Half a model run's sweeps after the fits (docs/physics.md 9.39).
void check_winner_time_step(const Campaign& campaign, const DiagnoseOptions& options, Diagnosis& d) {
  if (!d.winner) return;
  CandidateFit& w = d.candidates[*d.winner];
  const CompareOptions& o = options.compare;
  add_step_errors(*material::build_material(w.fitted, "winner").model, campaign, o, w.compare);
  for (const auto& warning : step_warnings(w.compare, o)) d.warnings.push_back("with " + w.name() + ": " + warning);
  std::string moved;
  for (const auto& t : w.compare.tests)
    if (t.step_error > o.step_error_warning)
      moved += (moved.empty() ? "" : ", ") + t.name + " " + fmt(t.step_error, 3) + "x";
  if (moved.empty()) return;
  const int finer = std::min(2 * o.dynamic_steps_per_cycle, max_steps_per_cycle);
  d.verdict += " The named model's sweeps move by " + moved +
               " noise when the steps per cycle are halved: the fitted parameters "
               "carry that time-step error (a dashpot's rate is first order in the step), so the same material gives "
               "other sweeps at another step or in the frequency domain, and part of a misfit left beyond noise can be "
               "the step; diagnose again with `--steps-per-cycle " +
               std::to_string(finer) + " --transient-steps-per-cycle " +
               std::to_string(std::min(2 * o.dynamic_transient_steps_per_cycle, max_steps_per_cycle)) +
               "` to halve it; the ranking of the damping families can change with the step (three of 16 air-flow "
               "and stiffness-damping verdicts did on step-converged benchmark data; docs/physics.md 9.39).";
}

/// chi2 of each test of a candidate's comparison, in test order.
std::vector<double> chi2_per_test(const CandidateFit& f, int quasi_static_points) {
  std::vector<double> chi2;
  for (const TestCompare& t : f.compare.tests) chi2.push_back(test_chi2(t, quasi_static_points));
  return chi2;
}

/// Step 7: the best converged candidate whose families do not include all of the winner's, when the winner's BIC
/// advantage over it is within strong_evidence with the tests reweighted within their noise estimates' uncertainty
/// (the plain dBIC difference is the case of exact noise estimates); the proposals of
/// separating_test.hpp run with both fitted models. Measured on two benchmark sets (docs/physics.md 9.31).
void find_rival(const Campaign& campaign, const DiagnoseOptions& options, Diagnosis& d, std::ostream& log) {
  const CandidateFit& w = d.candidates.front();
  auto nests_winner = [&](const CandidateFit& f) {
    return std::all_of(w.kinds.begin(), w.kinds.end(), [&](const std::string& k) {
      return std::find(f.kinds.begin(), f.kinds.end(), k) != f.kinds.end();
    });
  };
  // the winner's least BIC advantage over f with each test reweighted within its noise estimate's uncertainty
  // (rival_gap.hpp; the penalty difference as the two BICs count it, polish included)
  const std::vector<double> chi2_w = chi2_per_test(w, options.quasi_static_points);
  std::vector<double> u;
  for (const TestCompare& t : w.compare.tests) u.push_back(options.noise_uncertainty.of(t.kind));
  for (std::size_t i = 1; i < d.candidates.size(); ++i) {
    const CandidateFit& f = d.candidates[i];
    if (!f.converged || !std::isfinite(f.delta_bic) || nests_winner(f)) continue;
    const double gap =
        least_bic_gap(chi2_w, chi2_per_test(f, options.quasi_static_points), u, (f.bic - f.chi2) - (w.bic - w.chi2));
    if (!(gap <= options.strong_evidence)) continue;
    const auto t0 = Clock::now();
    try {
      const material::MaterialDefinition a = material::build_material(w.fitted, "winner");
      const material::MaterialDefinition b = material::build_material(f.fitted, "rival");
      d.rival =
          Rival{f.name(), f.delta_bic, gap,
                separating_tests(*a.model, *b.model, campaign, d.noise, options.compare, options.quasi_static_points)};
    } catch (const std::exception& e) {
      d.warnings.push_back("the tests that would separate " + w.name() + " from " + f.name() +
                           " could not be run: " + e.what());
      return;
    }
    log << "diagnose: " << f.name() << " explains the data about as well as " << w.name() << " (dBIC "
        << fmt(f.delta_bic, 4) << " vs " << fmt(w.delta_bic, 4) << ", least gap with the tests reweighted "
        << fmt(gap, 4) << "); " << d.rival->tests.size() << " separating tests run in " << fmt(seconds_since(t0), 2)
        << " s\n";
    return;
  }
}

/// The verdict's sentences on a rival: the campaign cannot tell it from the winner, and the test that would.
std::string rival_sentence(const Diagnosis& d, const DiagnoseOptions& options) {
  if (!d.rival || !d.winner) return "";
  const Rival& r = *d.rival;
  const CandidateFit& w = d.candidates[*d.winner];
  std::ostringstream o;
  o << " " << r.name << " explains these tests about as well (dBIC " << fmt(r.delta_bic, 4) << " vs "
    << fmt(w.delta_bic, 4);
  if (w.delta_bic - r.delta_bic > options.strong_evidence)
    o << "; within " << fmt(options.strong_evidence)
      << " once each test's noise estimate may be off by its uncertainty, x"
      << fmt(options.noise_uncertainty.quasi_static, 3) << " quasi-static and x"
      << fmt(options.noise_uncertainty.dynamic, 3) << " dynamic: least gap " << fmt(r.least_gap, 3)
      << ", so the preference rests on the noise estimates";
  else
    o << ", within " << fmt(options.strong_evidence);
  o << "): this campaign cannot tell " << w.name() << " from " << r.name << ".";
  if (r.tests.empty() || !std::isfinite(r.tests.front().separation)) {
    o << " No separating test could be run.";
    return o.str();
  }
  const SeparatingTest& best = r.tests.front();
  if (!(best.delta_chi2() > options.strong_evidence)) {
    o << " None of the " << r.tests.size() << " tests tried would add chi2 " << fmt(options.strong_evidence)
      << " between them (best: " << best.name << ", " << fmt(best.separation, 2) << "x noise, chi2 "
      << fmt(best.delta_chi2(), 2) << ").";
    return o.str();
  }
  o << " The test that would separate them: " << best.name << " (their predictions differ by "
    << fmt(best.separation, 3) << "x noise over its " << best.residuals << " residuals: chi2 "
    << fmt(best.delta_chi2(), 3) << " between them)";
  if (r.tests.size() > 1 && std::isfinite(r.tests[1].separation) && r.tests[1].delta_chi2() > options.strong_evidence)
    o << "; next: " << r.tests[1].name << " (chi2 " << fmt(r.tests[1].delta_chi2(), 3) << ")";
  o << ".";
  return o.str();
}

/// Verdict without a supported candidate: recalibrate the base, either because the base refit explains the
/// residual as well as any effect or because no effect reduces the penalised error convincingly.
void no_winner_verdict(const DiagnoseOptions& options, Diagnosis& d) {
  d.fragment = nullptr;
  std::ostringstream o;
  if (!d.held_out.empty()) {
    const HeldOutCheck& h = d.held_out.front();
    o << "No effect is named: " << h.candidate << " improves the fit of the tests it is fitted on, but it does not "
      << "predict tests left out of its fit better than a refitted base (held-out chi2 " << fmt(h.total_candidate, 4)
      << " vs " << fmt(h.total_reference, 4) << (h.failure.empty() ? "" : "; " + h.failure) << ")";
    if (d.held_out.size() > 1) o << ", nor do the next " << d.held_out.size() - 1 << " supported candidate(s)";
    o << ". The misfit is more likely a base calibration or protocol detail than a missing effect: recalibrate "
         "(`cushion fit`, e.g. --refit-on all), check the campaign's protocol keys, or add a test that separates "
         "the candidates (another rate or preload). ";
  }
  if (d.at_noise_level) {
    o << at_noise_verdict(options, d);
  } else if (base_refit_at_noise(d, options)) {
    const CandidateFit& b = *d.base_refit;
    o << "No effect is missing: refitting only the base (" << refitted_base_parameters(options)
      << ", no effect) brings every test within " << fmt(options.compare.noise_level_ratio, 2) << "x its noise (chi2/N "
      << fmt(d.baseline_chi2 / d.residuals) << " -> " << fmt(b.chi2 / d.residuals) << "): the misfit is a base calibration "
      << "that is slightly off, which an effect must not be named for";
    if (!d.candidates.empty() && std::isfinite(d.candidates.front().delta_bic))
      o << " (best effect: " << d.candidates.front().name() << ", dBIC " << fmt(d.candidates.front().delta_bic, 4)
        << " against the base refit's " << fmt(b.delta_bic, 4) << ")";
    o << ". Recalibrate the base (rerun `cushion fit`, e.g. with --refit-on all --refit-weights noise).";
  } else if (base_gain(d) > options.strong_evidence) {
    const CandidateFit& b = *d.base_refit;
    o << "No effect can be told from a base calibration that is slightly off: refitting only the base "
         "(" << refitted_base_parameters(options) << ", no effect) gives dBIC "
      << fmt(b.delta_bic, 4) << " (chi2/N " << fmt(d.baseline_chi2 / d.residuals) << " -> " << fmt(b.chi2 / d.residuals)
      << (b.compare.at_noise_level(options.compare.noise_level_ratio) ? ", every test at the noise level" : "")
      << ") and no catalogue effect beats it by dBIC > " << fmt(options.strong_evidence);
    if (!d.candidates.empty() && std::isfinite(d.candidates.front().delta_bic))
      o << " (best: " << d.candidates.front().name() << ", dBIC " << fmt(d.candidates.front().delta_bic, 4) << ")";
    o << ". Recalibrate the base first (rerun `cushion fit`, e.g. with --refit-on all), then diagnose again";
    if (!options.joint_base)
      o << "; if the baseline was fitted on this same campaign, the fit may have absorbed the effect: rerun with "
           "--joint-base (each effect fitted together with the base moduli)";
    o << ".";
  } else {
    o << "The model fails beyond noise, but no catalogue effect reduces the penalised error convincingly (dBIC > "
      << fmt(options.strong_evidence) << "): the base calibration is the first suspect (rerun `cushion fit`, e.g. with "
      << "--refit-on all).";
  }
  d.verdict = o.str();
}

}  // namespace

Diagnosis diagnose(const material::MaterialSpec& baseline, const Campaign& campaign, const DiagnoseOptions& options,
                   std::ostream& log) {
  const auto t0 = Clock::now();
  Diagnosis d;
  d.extended = baseline;
  const material::MaterialDefinition def = material::build_material(baseline, "baseline material");
  d.warnings = campaign_warnings(campaign);
  const Campaign& diagnosed = search_unrecorded_protocol(baseline, *def.model, campaign, options, d, log);
  compare_baseline(*def.model, diagnosed, options, d, log);
  if (d.base_refit && std::isfinite(d.base_refit->bic)) d.base_refit->delta_bic = d.baseline_bic - d.base_refit->bic;
  if (!verdict_without_candidates(options, d)) {
    SpareCores spare;
    const CandidateJobs jobs{baseline, diagnosed, options, d, spare};
    std::vector<CandidateFit> singles =
        fit_singles_and_reference(jobs, single_candidates(baseline, options, d.warnings), d, log);
    d.polished_base_refit = polish_leading_singles(jobs, singles, log);
    std::optional<Continuation> more = continue_best_single(jobs, singles, log);
    const bool continued = more.has_value();
    const std::vector<std::size_t> top = pair_sources(singles, more, options);
    PairStage stage = fit_pairs(jobs, singles, top, more, log);
    rank_candidates(std::move(singles), std::move(stage.pairs), top, std::move(more), options, d);
    refine_named_single(jobs, continued, std::move(stage.rounds), d, log);
    refit_named_form(jobs, d, log);
    confirm_out_of_sample(jobs, d, log);
    if (!d.candidates.empty() && d.candidates.front().supported) {
      winner_verdict(baseline, options, d);
      check_winner_time_step(diagnosed, options, d);
      find_rival(diagnosed, options, d, log);
    } else {
      no_winner_verdict(options, d);
    }
  }
  d.verdict += rival_sentence(d, options) + protocol_sentence(d);
  d.seconds = seconds_since(t0);
  return d;
}

}  // namespace cushion::calibration
