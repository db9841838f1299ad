#include "calibration/refit.hpp"

#include "calibration/ceres_options.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <thread>

#include "calibration/prony_fit.hpp"
#include "material/hyperfoam.hpp"
#include "material/stability.hpp"

namespace cushion::calibration {

namespace {

/// One quasi-static test as residuals: its in-contact path and the measured samples used.
struct QuasiStaticResiduals {
  UniaxialPath path;
  double c = 0.0;                     ///< lateral exponent of the test
  std::vector<std::size_t> samples;   ///< path samples with a measurement
  std::vector<double> stress;         ///< measured [MPa] at those samples
  double weight = 0.0;                ///< 1 / (peak sqrt(K T))
};

/// Everything the residuals compare against, prepared once. Residual order: quasi-static tests, then
/// (storage, loss) per frequency.
struct Targets {
  std::vector<QuasiStaticResiduals> quasi_static;
  std::size_t quasi_static_residuals = 0;
  DynamicPath dynamic;
  double c_dynamic = 0.0;             ///< the dynamic test is laterally free
  DynamicModuli moduli;
  double dynamic_weight = 0.0;        ///< 1 / sqrt(2 F)
  std::size_t N = 0, M = 0;
  double nu = 0.0;
  double mu_scale = 1.0;              ///< [MPa] the parameters hold mu / mu_scale (O(1) for the solver)
  std::vector<double> tau;
  std::size_t residuals() const { return quasi_static_residuals + 2 * moduli.frequency.size(); }
  std::size_t parameters() const { return 2 * N + M; }
};

/// Residuals at x = [mu_1..N, alpha_1..N, a_1..M] (any scalar type: double or ceres::Jet).
template <typename T>
bool residuals(const Targets& g, const T* x, T* r) {
  std::vector<T> mu_scaled(g.N);
  for (std::size_t j = 0; j < g.N; ++j) mu_scaled[j] = x[j] * g.mu_scale;
  const T* mu = mu_scaled.data();
  const T* alpha = x + g.N;
  const T* a = x + 2 * g.N;
  std::size_t o = 0;
  for (const QuasiStaticResiduals& q : g.quasi_static) {
    const std::vector<T> s = uniaxial_nominal_stress(q.path, mu, alpha, g.N, T(q.c), a);
    for (std::size_t k = 0; k < q.samples.size(); ++k) r[o++] = (s[q.samples[k]] - q.stress[k]) * q.weight;
  }
  const std::size_t F = g.moduli.frequency.size();
  std::vector<T> storage(F), loss(F);
  uniaxial_dynamic_moduli(g.dynamic, mu, alpha, g.N, T(g.c_dynamic), a, storage.data(), loss.data());
  for (std::size_t f = 0; f < F; ++f) {
    r[o++] = (storage[f] / g.moduli.storage[f] - 1.0) * g.dynamic_weight;
    r[o++] = (loss[f] / g.moduli.loss[f] - 1.0) * g.dynamic_weight;
  }
  return true;
}

struct JointResidual {
  const Targets* g;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    return residuals(*g, p[0], r);
  }
};

/// One hyperfoam term with unit mu and exponent alpha as a linear piece of the residual vector:
/// model (in residual units) = sum_j mu_j (B_j + Hm_j a), over the rows `rows` of the full residual vector.
struct TermBasis {
  Eigen::VectorXd B;
  Eigen::MatrixXd Hm;
};

TermBasis term_basis(const Targets& g, double alpha, const std::vector<std::size_t>& rows) {
  const std::size_t R = g.residuals(), M = g.M;
  Eigen::VectorXd B(R);
  Eigen::MatrixXd Hm(R, M);
  std::size_t o = 0;
  const double one = 1.0;
  for (const QuasiStaticResiduals& q : g.quasi_static) {
    const std::vector<double> S = long_term_S11(q.path, &one, &alpha, 1, q.c);
    std::vector<double> H(S.size() * M);
    viscous_states(q.path, S.data(), H.data());
    for (std::size_t k = 0; k < q.samples.size(); ++k, ++o) {
      const std::size_t n = q.samples[k];
      const double f = -q.path.stretch[n] * q.weight;
      B(o) = f * S[n];
      for (std::size_t i = 0; i < M; ++i) Hm(o, i) = f * H[n * M + i];
    }
  }
  // Dynamic rows: the model is affine in a for fixed mu, so B and the columns of Hm follow from M + 1 evaluations.
  const std::size_t F = g.moduli.frequency.size();
  std::vector<double> a(M, 0.0), storage0(F), loss0(F), storage(F), loss(F);
  uniaxial_dynamic_moduli(g.dynamic, &one, &alpha, 1, g.c_dynamic, a.data(), storage0.data(), loss0.data());
  for (std::size_t f = 0; f < F; ++f) {
    B(o + 2 * f) = storage0[f] * g.dynamic_weight / g.moduli.storage[f];
    B(o + 2 * f + 1) = loss0[f] * g.dynamic_weight / g.moduli.loss[f];
  }
  for (std::size_t i = 0; i < M; ++i) {
    a.assign(M, 0.0);
    a[i] = 1.0;
    uniaxial_dynamic_moduli(g.dynamic, &one, &alpha, 1, g.c_dynamic, a.data(), storage.data(), loss.data());
    for (std::size_t f = 0; f < F; ++f) {
      Hm(o + 2 * f, i) = (storage[f] - storage0[f]) * g.dynamic_weight / g.moduli.storage[f];
      Hm(o + 2 * f + 1, i) = (loss[f] - loss0[f]) * g.dynamic_weight / g.moduli.loss[f];
    }
  }
  TermBasis t{Eigen::VectorXd(rows.size()), Eigen::MatrixXd(rows.size(), M)};
  for (std::size_t k = 0; k < rows.size(); ++k) {
    t.B(k) = B(rows[k]);
    t.Hm.row(k) = Hm.row(rows[k]);
  }
  return t;
}

/// The measurements in residual units (model - this = residual) over `rows`.
Eigen::VectorXd target_vector(const Targets& g, const std::vector<std::size_t>& rows) {
  Eigen::VectorXd y(g.residuals());
  std::size_t o = 0;
  for (const QuasiStaticResiduals& q : g.quasi_static)
    for (double s : q.stress) y(o++) = s * q.weight;
  for (std::size_t f = 0; f < g.moduli.frequency.size(); ++f) {
    y(o++) = g.dynamic_weight;
    y(o++) = g.dynamic_weight;
  }
  Eigen::VectorXd out(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) out(k) = y(rows[k]);
  return out;
}

Eigen::VectorXd least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
  return (A * scale.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(b).cwiseQuotient(scale);
}

/// Inner problem for fixed exponents: alternating linear least squares in mu (free) and a (>= 0).
struct InnerSolution {
  Eigen::VectorXd mu, a;
  double cost = 0.0;
};
InnerSolution alternating(const std::vector<const TermBasis*>& terms, const Eigen::VectorXd& y, Eigen::VectorXd a,
                          int iterations, bool non_negative_mu = false) {
  const std::size_t N = terms.size();
  const Eigen::Index R = y.size();
  InnerSolution s;
  s.cost = std::numeric_limits<double>::infinity();
  Eigen::VectorXd mu(N);
  for (int it = 0; it < iterations; ++it) {
    Eigen::MatrixXd A(R, N);
    for (std::size_t j = 0; j < N; ++j) A.col(j) = terms[j]->B + terms[j]->Hm * a;
    mu = non_negative_mu ? non_negative_least_squares(A, y) : least_squares(A, y);
    Eigen::VectorXd base = Eigen::VectorXd::Zero(R);
    Eigen::MatrixXd Hm = Eigen::MatrixXd::Zero(R, a.size());
    for (std::size_t j = 0; j < N; ++j) {
      base += mu(j) * terms[j]->B;
      Hm += mu(j) * terms[j]->Hm;
    }
    a = non_negative_least_squares(Hm, y - base);
    const double cost = 0.5 * (base + Hm * a - y).squaredNorm();
    const bool settled = cost > s.cost * (1.0 - 1e-9);
    if (cost < s.cost) s = {mu, a, cost};
    if (settled) break;
  }
  return s;
}

/// Every N-subset of the grid (indices, increasing).
std::vector<std::vector<std::size_t>> subsets(std::size_t size, std::size_t N) {
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::size_t> pick(N);
  std::function<void(std::size_t, std::size_t)> choose = [&](std::size_t depth, std::size_t from) {
    if (depth == N) {
      out.push_back(pick);
      return;
    }
    for (std::size_t k = from; k < size; ++k) {
      pick[depth] = k;
      choose(depth + 1, k + 1);
    }
  };
  choose(0, 0);
  return out;
}

std::vector<double> pack(const Targets& g, const ViscoHyperfoam& m) {
  std::vector<double> x;
  for (const auto& t : m.terms) x.push_back(t.mu / g.mu_scale);
  for (const auto& t : m.terms) x.push_back(t.alpha);
  for (double a : long_term_ratios(m.prony)) x.push_back(a);
  return x;
}

ViscoHyperfoam unpack(const Targets& g, const std::vector<double>& x) {
  ViscoHyperfoam m;
  for (std::size_t i = 0; i < g.N; ++i) m.terms.push_back({x[i] * g.mu_scale, x[g.N + i], g.nu});
  m.prony = prony_from_long_term_ratios(std::vector<double>(x.begin() + 2 * g.N, x.end()), g.tau);
  return m;
}

double norm_of(const std::vector<double>& r, std::size_t begin, std::size_t end) {
  double s = 0.0;
  for (std::size_t k = begin; k < end; ++k) s += r[k] * r[k];
  return std::sqrt(s);  // residuals already carry 1/sqrt(count)
}

Targets make_targets(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                     const DynamicTest& dynamic, const RefitOptions& options) {
  Targets g;
  g.N = start.terms.size();
  g.M = start.prony.size();
  g.nu = start.terms.front().nu;
  for (const auto& t : start.terms)
    if (t.nu != g.nu) throw std::invalid_argument("refit: the hyperfoam terms must share one nu");
  for (const auto& t : start.prony) g.tau.push_back(t.tau);
  double peak = 0.0;
  for (const QuasiStaticTarget& target : quasi_static) peak = std::max(peak, target.segments.peak_stress);
  g.mu_scale = peak > 0.0 ? peak : 1.0;
  for (const QuasiStaticTarget& target : quasi_static) {
    const ContactSamples c = contact_samples(*target.test, target.segments, specimen);
    QuasiStaticResiduals q;
    q.path = make_uniaxial_path(c.time, c.strain, g.tau);
    q.c = lateral_exponent(g.nu, target.test->lateral);
    for (std::size_t n = 0; n < c.stress.size(); ++n)
      if (std::isfinite(c.stress[n])) {
        q.samples.push_back(n);
        q.stress.push_back(c.stress[n]);
      }
    q.weight = 1.0 / (target.segments.peak_stress * std::sqrt(double(q.samples.size() * quasi_static.size())));
    g.quasi_static_residuals += q.samples.size();
    g.quasi_static.push_back(std::move(q));
  }
  g.dynamic = dynamic_path(dynamic.preload_strain, dynamic.moduli.frequency, options.schedule ? &*options.schedule : nullptr,
                           g.tau, options.finite_amplitude ? strain_amplitudes(dynamic, specimen.thickness) : std::vector<double>{});
  g.c_dynamic = lateral_exponent(g.nu, Lateral::free);
  g.moduli = dynamic.moduli;
  g.dynamic_weight = 1.0 / std::sqrt(2.0 * double(g.moduli.frequency.size()));
  return g;
}

}  // namespace

RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const DynamicTest& dynamic, const RefitOptions& options) {
  const auto clock0 = std::chrono::steady_clock::now();
  if (quasi_static.empty()) throw std::invalid_argument("refit: no quasi-static test");
  if (start.terms.empty()) throw std::invalid_argument("refit: no hyperfoam term");
  const Targets g = make_targets(start, specimen, quasi_static, dynamic, options);
  const std::size_t N = g.N, M = g.M, n = g.parameters(), R = g.residuals();
  double peak_strain = 0.0;
  for (const QuasiStaticTarget& t : quasi_static) peak_strain = std::max(peak_strain, t.segments.peak_strain);

  RefitResult result;
  result.start = start;
  result.material = start;
  std::vector<double> r(R);
  auto evaluate = [&](const std::vector<double>& x, double& qs, double& dyn) {
    residuals(g, x.data(), r.data());
    ++result.evaluations;
    qs = norm_of(r, 0, g.quasi_static_residuals);
    dyn = norm_of(r, g.quasi_static_residuals, R);
    return 0.5 * (qs * qs + dyn * dyn);
  };
  result.cost_start = evaluate(pack(g, start), result.quasi_static_rms_start, result.dynamic_rms_start);

  // 1. Global search over the exponents: alternating linear least squares on a subsample of the rows.
  std::vector<std::size_t> screen_rows;
  {
    std::size_t o = 0;
    for (const QuasiStaticResiduals& q : g.quasi_static) {
      const std::size_t stride = std::max<std::size_t>(1, q.samples.size() / 100);
      for (std::size_t k = 0; k < q.samples.size(); ++k)
        if (k % stride == 0 || k + 1 == q.samples.size()) screen_rows.push_back(o + k);
      o += q.samples.size();
    }
    for (; o < R; ++o) screen_rows.push_back(o);
  }
  std::vector<double> grid = options.alpha_grid;
  std::vector<std::vector<std::size_t>> combos;
  std::vector<std::size_t> start_combo;
  for (const auto& t : start.terms) {
    start_combo.push_back(grid.size());
    grid.push_back(std::clamp(std::abs(t.alpha), 0.2, 50.0) * (t.alpha < 0 ? -1.0 : 1.0));
  }
  combos = subsets(options.alpha_grid.size(), N);
  combos.push_back(start_combo);
  std::vector<TermBasis> basis;
  for (double alpha : grid) basis.push_back(term_basis(g, alpha, screen_rows));
  const Eigen::VectorXd y_screen = target_vector(g, screen_rows);
  const std::vector<double> a_start = long_term_ratios(start.prony);
  Eigen::VectorXd a0(M);
  for (std::size_t i = 0; i < M; ++i) a0(i) = std::max(0.0, a_start[i]);
  // Each subset twice: mu free, and mu_i >= 0 (with nu >= 0 sufficient for Drucker stability, so that a
  // stable candidate exists whenever the free optimum is unstable).
  struct Candidate {
    std::vector<double> x;
    double cost;
    bool non_negative;
  };
  std::vector<Candidate> free_candidates, nn_candidates;
  for (const auto& combo : combos) {
    std::vector<const TermBasis*> terms;
    for (std::size_t k : combo) terms.push_back(&basis[k]);
    for (const bool nn : {false, true}) {
      const InnerSolution s = alternating(terms, y_screen, a0, options.alternating_iterations, nn);
      ++result.starts;
      if (!std::isfinite(s.cost) || !s.mu.allFinite() || (nn && !(s.mu.maxCoeff() > 0.0))) continue;
      std::vector<double> x;
      for (std::size_t j = 0; j < N; ++j) x.push_back(s.mu(j) / g.mu_scale);
      for (std::size_t k : combo) x.push_back(grid[k]);
      for (std::size_t i = 0; i < M; ++i) x.push_back(s.a(i));
      (nn ? nn_candidates : free_candidates).push_back({x, s.cost, nn});
    }
  }
  const std::size_t polished_starts = std::size_t(std::max(1, options.polished_starts));
  for (auto* list : {&free_candidates, &nn_candidates}) {
    std::stable_sort(list->begin(), list->end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    if (list->size() > polished_starts) list->resize(polished_starts);
  }

  // 2. Joint polish of the best starts (automatic derivatives), 3. the best stable one.
  // Dogleg: LM crawled along the (mu, a) valley (5x more iterations).
  const ceres::Solver::Options so = dense_fit_options(
      {options.function_tolerance, options.gradient_tolerance, options.parameter_tolerance, options.max_iterations},
      ceres::DOGLEG);
  struct Polished {
    std::vector<double> x;
    double cost;
    bool usable, stable;
    std::string report;
  };
  auto is_stable = [&](const std::vector<double>& x) {
    try {
      std::vector<material::HyperfoamTerm> terms;
      for (std::size_t j = 0; j < N; ++j) terms.push_back({x[j] * g.mu_scale, x[N + j], g.nu});
      return material::check_stability(material::Hyperfoam(terms), -peak_strain, options.stability_tension).stable() &&
             material_problem(unpack(g, x)).empty();
    } catch (const std::exception&) {
      return false;
    }
  };
  // Each polish is independent and deterministic: two at a time, each on its own thread. First the best
  // free-mu starts; if none of them ends Drucker-stable, the best mu >= 0 starts (bounded polish).
  std::vector<Polished> polished;
  auto polish_all = [&](const std::vector<Candidate>& candidates) {
    std::vector<Polished> out(candidates.size());
    std::vector<int> iterations(candidates.size(), 0), evaluations(candidates.size(), 0);
    auto polish = [&](std::size_t k) {
      std::vector<double> x = candidates[k].x;
      auto* cost = new ceres::DynamicAutoDiffCostFunction<JointResidual, 12>(new JointResidual{&g});
      cost->AddParameterBlock(static_cast<int>(n));
      cost->SetNumResiduals(static_cast<int>(R));
      ceres::Problem problem;
      problem.AddResidualBlock(cost, nullptr, x.data());
      for (std::size_t j = 0; j < N; ++j) {
        const bool negative = x[N + j] < 0.0;
        problem.SetParameterLowerBound(x.data(), int(N + j), negative ? -50.0 : 0.2);
        problem.SetParameterUpperBound(x.data(), int(N + j), negative ? -0.2 : 50.0);
        if (candidates[k].non_negative) problem.SetParameterLowerBound(x.data(), int(j), 0.0);
      }
      for (std::size_t i = 2 * N; i < n; ++i) {
        problem.SetParameterLowerBound(x.data(), int(i), 0.0);
        problem.SetParameterUpperBound(x.data(), int(i), 1e3);
      }
      ceres::Solver::Summary summary;
      ceres::Solve(so, &problem, &summary);
      iterations[k] = static_cast<int>(summary.iterations.size());
      evaluations[k] = summary.num_residual_evaluations + summary.num_jacobian_evaluations;
      out[k] = Polished{x, summary.final_cost, summary.IsSolutionUsable(), is_stable(x), summary.BriefReport()};
    };
    for (std::size_t k = 0; k < candidates.size(); k += 2) {
      std::thread second;
      if (k + 1 < candidates.size()) second = std::thread(polish, k + 1);
      polish(k);
      if (second.joinable()) second.join();
    }
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      result.iterations += iterations[k];
      result.evaluations += evaluations[k];
    }
    polished.insert(polished.end(), out.begin(), out.end());
  };
  auto any_stable = [&] {
    for (const auto& p : polished)
      if (p.usable && p.stable) return true;
    return false;
  };
  polish_all(free_candidates);
  if (!any_stable()) polish_all(nn_candidates);
  std::stable_sort(polished.begin(), polished.end(), [](const Polished& a, const Polished& b) {
    if (a.usable != b.usable) return a.usable;
    if (a.stable != b.stable) return a.stable;
    return a.cost < b.cost;
  });
  if (!polished.empty() && polished.front().usable) {
    const Polished& best = polished.front();
    result.converged = true;
    result.report = best.report;
    result.material = unpack(g, best.x);
    result.cost = evaluate(best.x, result.quasi_static_rms, result.dynamic_rms);
  } else {
    result.report = polished.empty() ? "no usable start" : polished.front().report;
    result.quasi_static_rms = result.quasi_static_rms_start;
    result.dynamic_rms = result.dynamic_rms_start;
    result.cost = result.cost_start;
  }
  result.improved = result.cost < result.cost_start;
  const material::Hyperfoam refitted(result.material.terms);
  result.stable = material::check_stability(refitted, -peak_strain, options.stability_tension).stable();
  result.stability = material::check_stability(refitted).summary();
  {
    std::vector<std::string> why;
    if (!result.converged) why.push_back("no polish gave a usable solution (" + result.report + ")");
    if (!result.stable) {
      const auto required = material::check_stability(refitted, -peak_strain, options.stability_tension);
      std::string modes;
      for (const auto& m : required.modes)
        if (m.first_unstable_compression || m.first_unstable_tension)
          modes += (modes.empty() ? "" : ", ") + material::to_string(m.mode) +
                   (m.first_unstable_compression ? " from compression " + std::to_string(*m.first_unstable_compression) : "") +
                   (m.first_unstable_tension ? " from tension " + std::to_string(*m.first_unstable_tension) : "");
      why.push_back("the refitted hyperfoam is Drucker-unstable within nominal strain [" + std::to_string(-peak_strain) + ", " +
                    std::to_string(options.stability_tension) + "]" + (modes.empty() ? "" : " (" + modes + ")"));
    }
    if (!result.improved)
      why.push_back("no improvement: joint cost " + std::to_string(result.cost_start) + " -> " + std::to_string(result.cost));
    for (const auto& w : why) result.rejection += (result.rejection.empty() ? "" : "; ") + w;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  return result;
}

}  // namespace cushion::calibration
