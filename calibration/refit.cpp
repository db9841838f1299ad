#include "calibration/refit.hpp"

#include "calibration/ceres_options.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>

#include "calibration/exponent_grid.hpp"
#include "calibration/parallel_jobs.hpp"
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
  std::vector<double> strain;         ///< nominal compression [-] at every path sample (to rebuild the path)
  std::vector<double> weight;         ///< per sample: 1 / (peak sqrt(K T)), or noise-weighted sqrt(P/K) / sigma_k
};

/// One dynamic test as residuals: its schedule and the measured moduli.
struct DynamicResiduals {
  DynamicPath path;
  std::optional<DynamicSchedule> schedule;  ///< the test's timing (empty: about a relaxed preload)
  DynamicModuli moduli;
  std::vector<double> weight;  ///< per row (storage, loss per frequency) [1/MPa]: residual = (model - measured) x weight
};

/// Everything the residuals compare against, prepared once for the Prony times `tau`. Residual order:
/// quasi-static tests, then (storage, loss) per frequency of each dynamic test.
struct Targets {
  std::vector<QuasiStaticResiduals> quasi_static;
  std::size_t quasi_static_residuals = 0;
  std::vector<DynamicResiduals> dynamic;
  double c_dynamic = 0.0;             ///< the dynamic tests are laterally free
  std::size_t N = 0, M = 0;
  double nu = 0.0;
  double mu_scale = 1.0;              ///< [MPa] the parameters hold mu / mu_scale (O(1) for the solver)
  std::vector<double> tau;
  std::size_t residuals() const {
    std::size_t n = quasi_static_residuals;
    for (const auto& d : dynamic) n += 2 * d.moduli.frequency.size();
    return n;
  }
  std::size_t parameters() const { return 2 * N + M; }
  double penalty_weight = 10.0;       ///< of the bound sum a_i <= a_sum_max (scaled with the residuals' size)
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
    for (std::size_t k = 0; k < q.samples.size(); ++k) r[o++] = (s[q.samples[k]] - q.stress[k]) * q.weight[k];
  }
  for (const DynamicResiduals& d : g.dynamic) {
    const std::size_t F = d.moduli.frequency.size();
    std::vector<T> storage(F), loss(F);
    uniaxial_dynamic_moduli(d.path, mu, alpha, g.N, T(g.c_dynamic), a, storage.data(), loss.data());
    for (std::size_t f = 0; f < F; ++f) {
      r[o++] = (storage[f] - d.moduli.storage[f]) * d.weight[2 * f];
      r[o++] = (loss[f] - d.moduli.loss[f]) * d.weight[2 * f + 1];
    }
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

/// The bound sum a_i <= a_sum_max (the long-term modulus at least 1/(1 + a_sum_max) of the instantaneous one) as a
/// penalty residual, zero inside: from one quasi-static rate the slow terms and the long-term curve trade off, and
/// without it the polish may carry the whole response by Prony terms on a vanishing long-term curve.
struct RatioSumBound {
  std::size_t first, count;  ///< a_i at x[first .. first + count)
  double a_sum_max, weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    T sum(0.0);
    for (std::size_t i = 0; i < count; ++i) sum += p[0][first + i];
    r[0] = sum > T(a_sum_max) ? weight * (sum - a_sum_max) : T(0.0);
    return true;
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
      const double f = -q.path.stretch[n] * q.weight[k];
      B(o) = f * S[n];
      for (std::size_t i = 0; i < M; ++i) Hm(o, i) = f * H[n * M + i];
    }
  }
  // Dynamic rows: the model is affine in a for fixed mu, so B and the columns of Hm follow from M + 1 evaluations.
  for (const DynamicResiduals& d : g.dynamic) {
    const std::size_t F = d.moduli.frequency.size();
    std::vector<double> a(M, 0.0), storage0(F), loss0(F), storage(F), loss(F);
    uniaxial_dynamic_moduli(d.path, &one, &alpha, 1, g.c_dynamic, a.data(), storage0.data(), loss0.data());
    for (std::size_t f = 0; f < F; ++f) {
      B(o + 2 * f) = storage0[f] * d.weight[2 * f];
      B(o + 2 * f + 1) = loss0[f] * d.weight[2 * f + 1];
    }
    for (std::size_t i = 0; i < M; ++i) {
      a.assign(M, 0.0);
      a[i] = 1.0;
      uniaxial_dynamic_moduli(d.path, &one, &alpha, 1, g.c_dynamic, a.data(), storage.data(), loss.data());
      for (std::size_t f = 0; f < F; ++f) {
        Hm(o + 2 * f, i) = (storage[f] - storage0[f]) * d.weight[2 * f];
        Hm(o + 2 * f + 1, i) = (loss[f] - loss0[f]) * d.weight[2 * f + 1];
      }
    }
    o += 2 * F;
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
    for (std::size_t k = 0; k < q.stress.size(); ++k) y(o++) = q.stress[k] * q.weight[k];
  for (const DynamicResiduals& d : g.dynamic)
    for (std::size_t f = 0; f < d.moduli.frequency.size(); ++f) {
      y(o++) = d.moduli.storage[f] * d.weight[2 * f];
      y(o++) = d.moduli.loss[f] * d.weight[2 * f + 1];
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

/// Relaxed screen of the exponent subsets. For fixed exponents the model sum_j mu_j (B_j + Hm_j a) is linear in
/// (mu_j, b_ji = mu_j a_i) once the rank-one structure b = mu a^T is dropped: one linear least-squares problem per
/// subset whose cost is a lower bound of the subset's true cost (zero at the true exponents of noise-free data),
/// solved on the Gram matrix of every grid column (unit-scaled, with a tiny ridge) so that a subset costs a small
/// dense solve whatever the number of rows.
class RelaxedScreen {
 public:
  RelaxedScreen(const std::vector<TermBasis>& basis, const Eigen::VectorXd& y) : block_(1 + basis.front().Hm.cols()) {
    Eigen::MatrixXd X(y.size(), Eigen::Index(basis.size()) * block_);
    for (std::size_t k = 0; k < basis.size(); ++k) {
      X.col(Eigen::Index(k) * block_) = basis[k].B;
      X.middleCols(Eigen::Index(k) * block_ + 1, block_ - 1) = basis[k].Hm;
    }
    scale_ = X.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < scale_.size(); ++j) scale_(j) = scale_(j) > 0.0 ? scale_(j) : 1.0;
    X = X * scale_.cwiseInverse().asDiagonal();
    gram_ = X.transpose() * X;
    rhs_ = X.transpose() * y;
    yy_ = y.squaredNorm();
  }

  /// Relaxed cost 0.5 |model - y|^2 of a subset (indices into the basis), and its moduli mu_j and ratios a
  /// (the rank-one projection of b, clipped at 0).
  double solve(const std::vector<std::size_t>& combo, Eigen::VectorXd& mu, Eigen::VectorXd& a) const {
    const Eigen::Index n = Eigen::Index(combo.size()) * block_;
    std::vector<Eigen::Index> idx;
    for (std::size_t k : combo)
      for (Eigen::Index i = 0; i < block_; ++i) idx.push_back(Eigen::Index(k) * block_ + i);
    Eigen::MatrixXd G(n, n);
    Eigen::VectorXd c(n);
    for (Eigen::Index r = 0; r < n; ++r) {
      c(r) = rhs_(idx[r]);
      for (Eigen::Index q = 0; q < n; ++q) G(r, q) = gram_(idx[r], idx[q]);
    }
    const Eigen::VectorXd x = (G + 1e-10 * Eigen::MatrixXd::Identity(n, n)).ldlt().solve(c);
    const double cost = 0.5 * std::max(0.0, yy_ - 2.0 * c.dot(x) + x.dot(G * x));
    const Eigen::Index N = Eigen::Index(combo.size()), M = block_ - 1;
    mu.resize(N);
    Eigen::MatrixXd b(N, M);
    for (Eigen::Index j = 0; j < N; ++j) {
      mu(j) = x(j * block_) / scale_(idx[j * block_]);
      for (Eigen::Index i = 0; i < M; ++i) b(j, i) = x(j * block_ + 1 + i) / scale_(idx[j * block_ + 1 + i]);
    }
    a = mu.squaredNorm() > 0.0 ? Eigen::VectorXd((b.transpose() * mu / mu.squaredNorm()).cwiseMax(0.0))
                               : Eigen::VectorXd::Zero(M);
    return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
  }

 private:
  Eigen::Index block_;
  Eigen::VectorXd scale_, rhs_;
  Eigen::MatrixXd gram_;
  double yy_ = 0.0;
};

/// A start of the joint polish: x = [mu_j / mu_scale, alpha_j, a_i] and its cost on the screen rows.
struct Candidate {
  std::vector<double> x;
  double cost;
  bool non_negative;  ///< mu_j >= 0 kept in the polish
};

/// Rows of the residual vector the screen uses: about 100 samples of each quasi-static test, every dynamic row.
std::vector<std::size_t> screen_rows(const Targets& g) {
  std::vector<std::size_t> rows;
  std::size_t o = 0;
  for (const QuasiStaticResiduals& q : g.quasi_static) {
    const std::size_t stride = std::max<std::size_t>(1, q.samples.size() / 100);
    for (std::size_t k = 0; k < q.samples.size(); ++k)
      if (k % stride == 0 || k + 1 == q.samples.size()) rows.push_back(o + k);
    o += q.samples.size();
  }
  for (; o < g.residuals(); ++o) rows.push_back(o);
  return rows;
}

/// Step 1: every N-subset of the exponent grid (and the start's exponents) through the relaxed screen; the best
/// `relaxed_kept` subsets solved by alternating least squares (from the screen's ratios and from the start's),
/// each twice: mu free, and mu_i >= 0 (with nu >= 0 sufficient for Drucker stability, so that a stable candidate
/// exists whenever the free optimum is unstable). Candidates sorted by cost, free and non-negative apart.
void screen_exponents(const Targets& g, const ViscoHyperfoam& start, const RefitOptions& options, int& starts,
                      std::vector<Candidate>& free_candidates, std::vector<Candidate>& nn_candidates) {
  const std::size_t N = g.N, M = g.M;
  std::vector<double> grid = options.alpha_grid.empty() ? alpha_grid(int(N), 50.0) : options.alpha_grid;
  std::vector<std::size_t> start_combo;
  for (const auto& t : start.terms) {
    start_combo.push_back(grid.size());
    grid.push_back(std::clamp(std::abs(t.alpha), 0.2, 50.0) * (t.alpha < 0 ? -1.0 : 1.0));
  }
  std::vector<std::vector<std::size_t>> combos;
  for (const auto& c : subsets(int(grid.size() - N), int(N))) combos.emplace_back(c.begin(), c.end());
  combos.push_back(start_combo);
  const std::vector<std::size_t> rows = screen_rows(g);
  std::vector<TermBasis> basis;
  for (double alpha : grid) basis.push_back(term_basis(g, alpha, rows));
  const Eigen::VectorXd y = target_vector(g, rows);
  const RelaxedScreen relaxed(basis, y);
  struct Screened {
    double cost;
    std::size_t combo;
    Eigen::VectorXd a;
  };
  std::vector<Screened> screened;
  for (std::size_t k = 0; k < combos.size(); ++k) {
    Eigen::VectorXd mu, a;
    const double cost = relaxed.solve(combos[k], mu, a);
    screened.push_back({cost, k, a});
  }
  const std::size_t kept = std::min(screened.size(), std::size_t(std::max(1, options.relaxed_kept)));
  std::partial_sort(screened.begin(), screened.begin() + std::ptrdiff_t(kept), screened.end(),
                    [](const Screened& a, const Screened& b) { return a.cost < b.cost; });
  screened.resize(kept);
  screened.push_back({0.0, combos.size() - 1, {}});  // the start's exponents always
  const std::vector<double> a_start = long_term_ratios(start.prony);
  Eigen::VectorXd a0(M);
  for (std::size_t i = 0; i < M; ++i) a0(i) = std::max(0.0, a_start[i]);
  for (const Screened& sc : screened) {
    std::vector<const TermBasis*> terms;
    for (std::size_t k : combos[sc.combo]) terms.push_back(&basis[k]);
    for (const bool nn : {false, true}) {
      InnerSolution s = alternating(terms, y, a0, options.alternating_iterations, nn);
      if (sc.a.size() == Eigen::Index(M)) {
        const InnerSolution t = alternating(terms, y, sc.a, options.alternating_iterations, nn);
        if (t.cost < s.cost) s = t;
      }
      ++starts;
      if (!std::isfinite(s.cost) || !s.mu.allFinite() || (nn && !(s.mu.maxCoeff() > 0.0))) continue;
      std::vector<double> x;
      for (std::size_t j = 0; j < N; ++j) x.push_back(s.mu(j) / g.mu_scale);
      for (std::size_t k : combos[sc.combo]) x.push_back(grid[k]);
      for (std::size_t i = 0; i < M; ++i) x.push_back(s.a(i));
      (nn ? nn_candidates : free_candidates).push_back({x, s.cost, nn});
    }
  }
  for (auto* list : {&free_candidates, &nn_candidates})
    std::stable_sort(list->begin(), list->end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
}

/// The polish starts: the best candidate of each kind (mu free, mu >= 0) and each sign pattern of the exponents
/// (the number of negative alpha_j; the polish keeps every sign, so each pattern is its own basin) whose cost is
/// within `start_cost_ratio` of the best, the lowest costs first, at most `count`.
std::vector<Candidate> diverse_starts(const std::vector<Candidate>& free_candidates,
                                      const std::vector<Candidate>& nn_candidates, std::size_t N, int count,
                                      double start_cost_ratio) {
  std::vector<Candidate> out;
  double best = std::numeric_limits<double>::infinity();
  for (const auto* list : {&free_candidates, &nn_candidates})
    if (!list->empty()) best = std::min(best, list->front().cost);
  for (const auto* list : {&free_candidates, &nn_candidates}) {
    std::vector<bool> taken(N + 1, false);
    for (const Candidate& c : *list) {  // sorted by cost
      std::size_t negative = 0;
      for (std::size_t j = 0; j < N; ++j) negative += c.x[N + j] < 0.0 ? 1 : 0;
      if (taken[negative] || !(c.cost <= start_cost_ratio * best)) continue;
      taken[negative] = true;
      const bool repeated = std::any_of(out.begin(), out.end(), [&](const Candidate& o) { return o.x == c.x; });
      if (!repeated) out.push_back(c);  // a non-negative solution that is also the free one
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  if (out.size() > std::size_t(std::max(1, count))) out.resize(std::size_t(std::max(1, count)));
  return out;
}

/// Box bounds of the polishes over x = [mu_j / mu_scale, alpha_j, a_i] and `extra` more parameters: alpha_j keeps
/// the sign of x0's with 0.2 <= |alpha_j| <= 50, |mu_j| <= mu_bound (mu_j >= 0 when non_negative), 0 <= a_i <= 1e3,
/// the extra ones within +-extra_range.
struct Bounds {
  std::vector<double> lower, upper;
};
Bounds polish_bounds(const Targets& g, const std::vector<double>& x0, bool non_negative, const RefitOptions& options,
                     std::size_t extra = 0, double extra_range = 0.0) {
  const std::size_t N = g.N, n = g.parameters();
  Bounds b{std::vector<double>(n + extra), std::vector<double>(n + extra)};
  for (std::size_t j = 0; j < N; ++j) {
    const bool negative = x0[N + j] < 0.0;
    b.lower[N + j] = negative ? -50.0 : 0.2;
    b.upper[N + j] = negative ? -0.2 : 50.0;
    b.lower[j] = non_negative ? 0.0 : -options.mu_bound;
    b.upper[j] = options.mu_bound;
  }
  for (std::size_t i = 2 * N; i < n; ++i) b.lower[i] = 0.0, b.upper[i] = 1e3;
  for (std::size_t i = n; i < n + extra; ++i) b.lower[i] = -extra_range, b.upper[i] = extra_range;
  return b;
}

/// Adds the penalty of the bound sum a_i <= a_sum_max on the parameter block x and its box bounds to `problem`.
void add_ratio_bound_and_box(ceres::Problem& problem, double* x, const Targets& g, const Bounds& b,
                             const RefitOptions& options) {
  const int size = static_cast<int>(b.lower.size());
  auto* bound = new ceres::DynamicAutoDiffCostFunction<RatioSumBound, 12>(
      new RatioSumBound{2 * g.N, g.M, options.a_sum_max, g.penalty_weight});
  bound->AddParameterBlock(size);
  bound->SetNumResiduals(1);
  problem.AddResidualBlock(bound, nullptr, x);
  for (int i = 0; i < size; ++i) {
    problem.SetParameterLowerBound(x, i, b.lower[std::size_t(i)]);
    problem.SetParameterUpperBound(x, i, b.upper[std::size_t(i)]);
  }
}

/// One joint polish of a start (automatic derivatives, Ceres bounded trust region).
struct PolishOutcome {
  std::vector<double> x;
  double cost = 0.0;
  bool usable = false;
  std::string report;
  int iterations = 0, evaluations = 0;
};

/// Polishes `start` within the bounds: alpha_j keeps its sign with 0.2 <= |alpha_j| <= 50, |mu_j| <= mu_bound (mu_j >= 0
/// for a non-negative start), 0 <= a_i <= 1e3. Ceres projects its steps onto the bounds, which stalls (parameter
/// tolerance after many rejected steps) while a bound is active, typically a_i = 0 for a decade without relaxation:
/// a second solve then holds the parameters at a bound constant and polishes the rest; it is kept if lower.
PolishOutcome polish_start(const Targets& g, const Candidate& start, const RefitOptions& options,
                           const ceres::Solver::Options& so) {
  const std::size_t n = g.parameters();
  const Bounds b = polish_bounds(g, start.x, start.non_negative, options);
  PolishOutcome out;
  out.x = start.x;
  for (std::size_t i = 0; i < n; ++i) out.x[i] = std::clamp(out.x[i], b.lower[i], b.upper[i]);
  auto solve = [&](std::vector<double>& x, const std::vector<int>& held) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<JointResidual, 12>(new JointResidual{&g});
    cost->AddParameterBlock(static_cast<int>(n));
    cost->SetNumResiduals(static_cast<int>(g.residuals()));
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, x.data());
    add_ratio_bound_and_box(problem, x.data(), g, b, options);
    if (!held.empty()) problem.SetManifold(x.data(), new ceres::SubsetManifold(int(n), held));
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    out.iterations += static_cast<int>(summary.iterations.size());
    out.evaluations += summary.num_residual_evaluations + summary.num_jacobian_evaluations;
    return summary;
  };
  const ceres::Solver::Summary first = solve(out.x, {});
  out.cost = first.final_cost;
  out.usable = first.IsSolutionUsable();
  out.report = first.BriefReport();
  std::vector<int> held;
  for (std::size_t i = 0; i < n; ++i)
    if (b.lower[i] == 0.0 && out.x[i] <= 0.0) held.push_back(int(i));
  if (!out.usable || held.empty() || held.size() == n) return out;
  std::vector<double> x = out.x;
  const ceres::Solver::Summary second = solve(x, held);
  if (second.IsSolutionUsable() && second.final_cost < out.cost) {
    out.x = x;
    out.cost = second.final_cost;
    out.report = first.BriefReport() + "; with the " + std::to_string(held.size()) + " parameter(s) at a bound held: " +
                 second.BriefReport();
  }
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

/// The paths of `g` rebuilt for Prony times `tau` [s] (the measured samples and weights kept).
Targets retimed(const Targets& g, const std::vector<double>& tau) {
  Targets t = g;
  t.tau = tau;
  for (QuasiStaticResiduals& q : t.quasi_static) q.path = make_uniaxial_path(q.path.time, q.strain, tau);
  for (DynamicResiduals& d : t.dynamic)
    d.path = dynamic_path(1.0 - d.path.preload_stretch, d.path.frequency, d.schedule ? &*d.schedule : nullptr, tau,
                          d.path.amplitude);
  return t;
}

/// sigma with every non-positive or non-finite entry replaced by the median of the positive ones; throws
/// std::invalid_argument naming `what` when none is positive.
std::vector<double> usable_sigma(std::vector<double> sigma, const std::string& what) {
  std::vector<double> positive;
  for (double x : sigma)
    if (std::isfinite(x) && x > 0.0) positive.push_back(x);
  if (positive.empty()) throw std::invalid_argument("refit: noise-weighted, but " + what + " has no noise estimate");
  std::nth_element(positive.begin(), positive.begin() + std::ptrdiff_t(positive.size() / 2), positive.end());
  const double median = positive[positive.size() / 2];
  for (double& x : sigma)
    if (!(std::isfinite(x) && x > 0.0)) x = median;
  return sigma;
}

/// Row weights [1/MPa] of one dynamic test; a row's residual is (model - measured) x weight. Unweighted: the relative
/// error over sqrt(2 F D) (F frequencies, D dynamic tests), weight 1 / (measured sqrt(2 F D)), and 0 on a loss row
/// whose measured E'' <= 0 (noise; no relative error). Noise-weighted: 1 / sigma with the absolute noise of
/// E' = A cos p and E'' = A sin p from the |E*| noise s_A and the phase noise s_p [rad] (first order, independent
/// errors): hypot(s_A cos p, A sin p s_p) and hypot(s_A sin p, A cos p s_p), whatever the sign of the measurement.
std::vector<double> dynamic_weights(const DynamicTarget& t, std::size_t tests, bool noise_weighted) {
  const DynamicModuli& m = t.test->moduli;
  const std::size_t F = m.frequency.size();
  std::vector<double> w;
  if (!noise_weighted) {
    const double share = 1.0 / std::sqrt(2.0 * double(F * tests));
    for (std::size_t f = 0; f < F; ++f) {
      w.push_back(share / m.storage[f]);
      w.push_back(m.loss[f] > 0.0 ? share / m.loss[f] : 0.0);
    }
    return w;
  }
  if (t.modulus_sigma.size() != F || t.phase_sigma.size() != F)
    throw std::invalid_argument("refit: noise-weighted, but " + t.test->name + " has no noise estimate per frequency");
  const std::vector<double> sa = usable_sigma(t.modulus_sigma, t.test->name + " (|E*|)");
  const std::vector<double> sp = usable_sigma(t.phase_sigma, t.test->name + " (phase)");
  for (std::size_t f = 0; f < F; ++f) {
    const double A = std::hypot(m.storage[f], m.loss[f]), p = std::atan2(m.loss[f], m.storage[f]);
    const double rad = sp[f] * std::numbers::pi / 180.0;
    w.push_back(1.0 / std::hypot(sa[f] * std::cos(p), A * std::sin(p) * rad));
    w.push_back(1.0 / std::hypot(sa[f] * std::sin(p), A * std::cos(p) * rad));
  }
  return w;
}

/// The refit's targets; `noise_weighted`: each residual divided by its noise (chi2), else relative to the peak.
Targets make_targets(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                     const std::vector<DynamicTarget>& dynamic, const RefitOptions& options, bool noise_weighted) {
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
    q.strain = c.strain;
    q.c = lateral_exponent(g.nu, target.test->lateral);
    const std::size_t first = target.segments.load_begin - (std::isfinite(c.stress.front()) ? 0 : 1);  // record index of n = 0
    std::vector<double> sigma;
    for (std::size_t n = 0; n < c.stress.size(); ++n)
      if (std::isfinite(c.stress[n])) {
        q.samples.push_back(n);
        q.stress.push_back(c.stress[n]);
        if (noise_weighted)
          sigma.push_back(first + n < target.stress_sigma.size() ? target.stress_sigma[first + n] : 0.0);
      }
    const double K = double(q.samples.size());
    if (noise_weighted) {
      for (double x : usable_sigma(sigma, target.test->name)) q.weight.push_back(std::sqrt(options.quasi_static_points / K) / x);
    } else {
      q.weight.assign(q.samples.size(), 1.0 / (target.segments.peak_stress * std::sqrt(K * double(quasi_static.size()))));
    }
    g.quasi_static_residuals += q.samples.size();
    g.quasi_static.push_back(std::move(q));
  }
  for (const DynamicTarget& t : dynamic) {
    DynamicResiduals d;
    d.schedule = options.schedule;
    if (d.schedule) {  // the test's own timing keys
      if (t.test->preload_rate_mm_min > 0.0) d.schedule->preload_rate_mm_min = t.test->preload_rate_mm_min;
      d.schedule->dwell_s = t.test->dwell_s;
    }
    d.path = dynamic_path(t.test->preload_strain, t.test->moduli.frequency, d.schedule ? &*d.schedule : nullptr, g.tau,
                          options.finite_amplitude ? strain_amplitudes(*t.test, specimen.thickness) : std::vector<double>{});
    d.moduli = t.test->moduli;
    d.weight = dynamic_weights(t, dynamic.size(), noise_weighted);
    g.dynamic.push_back(std::move(d));
  }
  g.c_dynamic = lateral_exponent(g.nu, Lateral::free);
  g.penalty_weight = noise_weighted ? 10.0 * std::sqrt(double(g.residuals())) : 10.0;
  return g;
}

/// The Prony times with the other parameters: x = [mu_j / mu_scale, alpha_j, a_i, u_i], tau_i = tau0_i 10^u_i, for
/// the numeric-difference polish of stage 4 (the paths are rebuilt for every set of times).
/// The Prony times [s] of `g`'s times scaled by 10^u_i.
std::vector<double> times_at(const Targets& g, const double* u) {
  std::vector<double> tau = g.tau;
  for (std::size_t i = 0; i < g.M; ++i) tau[i] *= std::pow(10.0, u[i]);
  return tau;
}

/// The residuals at x = [mu_j / mu_scale, alpha_j, a_i, u_i] for the times tau0_i 10^u_i. Safe to call from two threads
/// at once (the Jacobian's columns run on two, CentralDifferenceCost): the paths are rebuilt only when the times change,
/// in one of a few slots, each holding the paths of the last times it saw (a numeric Jacobian perturbs the other 2N + M
/// parameters on the same times); a caller takes a free slot, so no two threads share one.
class TimesResidual {
 public:
  explicit TimesResidual(const Targets& g) : g_(g) {}
  bool operator()(const double* x, double* r) {
    const std::vector<double> tau = times_at(g_, x + g_.parameters());
    const Lease lease{*this, acquire(tau)};
    Slot& slot = lease.slot;
    if (!slot.paths || tau != slot.tau) slot.paths = retimed(g_, tau), slot.tau = tau;
    return residuals(*slot.paths, x, r);
  }

 private:
  struct Slot {
    std::vector<double> tau;
    std::optional<Targets> paths;
    bool busy = false;
  };
  /// A free slot, one that holds `tau` when there is one.
  Slot& acquire(const std::vector<double>& tau) {
    std::lock_guard lock(mutex_);
    Slot* free = nullptr;
    for (auto& s : slots_) {
      if (s->busy) continue;
      if (s->paths && s->tau == tau) free = s.get();
      if (!free) free = s.get();
    }
    if (!free) free = slots_.emplace_back(std::make_unique<Slot>()).get();
    free->busy = true;
    return *free;
  }
  struct Lease {  // gives the slot back however the evaluation ends
    TimesResidual& owner;
    Slot& slot;
    ~Lease() {
      std::lock_guard lock(owner.mutex_);
      slot.busy = false;
    }
  };
  const Targets& g_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Slot>> slots_;
};

struct TimesOutcome {
  std::vector<double> x, tau;  ///< parameters as in Targets (for the new times) and the times [s]
  double cost = 0.0;
  bool usable = false;
  std::string report;
  int evaluations = 0;
};

/// Stage 4: from the polished x, the Prony times too, each within a factor 10^times_range of its start, jointly with
/// every other parameter (bounds of the polish; Levenberg-Marquardt, forward differences on the fast model).
TimesOutcome polish_times(const Targets& g, const std::vector<double>& x0, const RefitOptions& options) {
  const std::size_t n = g.parameters(), m = n + g.M;
  const Bounds b = polish_bounds(g, x0, false, options, g.M, options.times_range);
  std::vector<double> x = x0;
  x.resize(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) x[i] = std::clamp(x[i], b.lower[i], b.upper[i]);
  // Ceres' central differences (relative step 1e-6), the columns on two threads: nothing else runs while the base fit
  // polishes its times (the polishes of stage 2 ran on two threads before it).
  SpareCores second_core;
  second_core.lend();
  TimesResidual residual(g);  // outlives the problem below, which owns the cost
  auto* cost = new CentralDifferenceCost([&residual](const double* u, double* r) { return residual(u, r); },
                                         static_cast<int>(m), static_cast<int>(g.residuals()), 1e-6, &second_core);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  add_ratio_bound_and_box(problem, x.data(), g, b, options);
  ceres::Solver::Options so = dense_fit_options({1e-10, 1e-12, 1e-8, options.times_iterations});
  use_cost_only_line_search(so);  // numeric derivatives
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  TimesOutcome out;
  out.usable = summary.IsSolutionUsable();
  out.cost = summary.final_cost;
  out.report = summary.BriefReport();
  out.evaluations = summary.num_residual_evaluations + summary.num_jacobian_evaluations * int(2 * m + 1);
  out.tau = times_at(g, x.data() + n);
  x.resize(n);
  out.x = x;
  return out;
}

}  // namespace

namespace {

/// The largest peak strain of the quasi-static targets [-] (the range the hyperfoam must be stable over).
double peak_strain_of(const std::vector<QuasiStaticTarget>& quasi_static) {
  double peak = 0.0;
  for (const QuasiStaticTarget& t : quasi_static) peak = std::max(peak, t.segments.peak_strain);
  return peak;
}

/// One round of stages 1-4 from `start` (its exponents and Prony times seed the search).
RefitResult refit_round(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                        const std::vector<DynamicTarget>& dynamic, const RefitOptions& options) {
  const auto clock0 = std::chrono::steady_clock::now();
  if (quasi_static.empty()) throw std::invalid_argument("refit: no quasi-static test");
  if (start.terms.empty()) throw std::invalid_argument("refit: no hyperfoam term");
  Targets g = make_targets(start, specimen, quasi_static, dynamic, options, options.noise_weighted);
  Targets shown = options.noise_weighted ? make_targets(start, specimen, quasi_static, dynamic, options, false) : g;
  const std::size_t N = g.N, R = g.residuals();
  const double peak_strain = peak_strain_of(quasi_static);

  RefitResult result;
  result.start = start;
  result.material = start;
  std::vector<double> r(R), r_shown(R);
  // The cost in the refit's metric; qs, dyn: the RMS relative errors reported (peak-relative, E' and E'').
  auto evaluate = [&](const std::vector<double>& x, double& qs, double& dyn) {
    residuals(g, x.data(), r.data());
    residuals(shown, x.data(), r_shown.data());
    ++result.evaluations;
    qs = norm_of(r_shown, 0, shown.quasi_static_residuals);
    dyn = norm_of(r_shown, shown.quasi_static_residuals, R);
    return 0.5 * std::pow(norm_of(r, 0, R), 2);
  };
  result.cost_start = evaluate(pack(g, start), result.quasi_static_rms_start, result.dynamic_rms_start);

  // 1. Global search over the exponents (screen_exponents).
  std::vector<Candidate> free_candidates, nn_candidates;
  screen_exponents(g, start, options, result.starts, free_candidates, nn_candidates);
  const std::vector<Candidate> starts = diverse_starts(free_candidates, nn_candidates, N, options.polished_starts, options.start_cost_ratio);

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
  // Each polish is independent and deterministic: two workers on two threads. First the diverse starts;
  // if none of them ends Drucker-stable, the best mu >= 0 starts (bounded polish).
  std::vector<Polished> polished;
  auto polish_all = [&](const std::vector<Candidate>& candidates) {
    std::vector<Polished> out(candidates.size());
    std::vector<int> iterations(candidates.size(), 0), evaluations(candidates.size(), 0);
    auto polish = [&](std::size_t k) {
      const PolishOutcome p = polish_start(g, candidates[k], options, so);
      iterations[k] = p.iterations;
      evaluations[k] = p.evaluations;
      out[k] = Polished{p.x, p.cost, p.usable, is_stable(p.x), p.report};
    };
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      for (std::size_t k = next++; k < candidates.size(); k = next++) polish(k);
    };
    std::thread second(worker);  // two workers take the next start as they finish one
    worker();
    second.join();
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
  polish_all(starts);
  if (!any_stable()) {  // the next mu >= 0 starts (Drucker-stable with nu >= 0)
    nn_candidates.resize(std::min(nn_candidates.size(), std::size_t(std::max(1, options.polished_starts))));
    polish_all(nn_candidates);
  }
  std::stable_sort(polished.begin(), polished.end(), [](const Polished& a, const Polished& b) {
    if (a.usable != b.usable) return a.usable;
    if (a.stable != b.stable) return a.stable;
    return a.cost < b.cost;
  });
  if (!polished.empty() && polished.front().usable) {
    const Polished& best = polished.front();
    result.converged = true;
    result.report = best.report;
    std::vector<double> x = best.x;
    if (options.times_range > 0.0 && g.M > 0) {  // 4. the Prony times too, kept when lower and still stable
      const TimesOutcome t = polish_times(g, best.x, options);
      result.evaluations += t.evaluations;
      if (t.usable && t.cost < best.cost && is_stable(t.x)) {
        g = retimed(g, t.tau);
        shown = retimed(shown, t.tau);
        x = t.x;
        result.report += "; Prony times: " + t.report;
        result.times_moved = true;
      }
    }
    result.material = unpack(g, x);
    result.cost = evaluate(x, result.quasi_static_rms, result.dynamic_rms);
  } else {
    result.report = polished.empty() ? "no usable start" : polished.front().report;
    result.quasi_static_rms = result.quasi_static_rms_start;
    result.dynamic_rms = result.dynamic_rms_start;
    result.cost = result.cost_start;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  return result;
}

/// Stability, improvement and the rejection reason of a finished refit.
void judge(RefitResult& result, double peak_strain, const RefitOptions& options) {
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
}

}  // namespace

RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const std::vector<DynamicTarget>& dynamic, const RefitOptions& options) {
  RefitResult result = refit_round(start, specimen, quasi_static, dynamic, options);
  // Once the times moved, the exponents are searched again about them (the screen ran with the start's times).
  for (int round = 1; round < options.rounds && result.converged && result.times_moved; ++round) {
    RefitResult next = refit_round(result.material, specimen, quasi_static, dynamic, options);
    const bool better = next.converged && next.cost < result.cost;
    if (better) {  // the outcome of this round, measured from the original start
      next.start = result.start;
      next.cost_start = result.cost_start;
      next.quasi_static_rms_start = result.quasi_static_rms_start;
      next.dynamic_rms_start = result.dynamic_rms_start;
      next.times_moved = true;
      std::swap(result, next);
    }
    result.iterations += next.iterations;  // the effort of both rounds
    result.evaluations += next.evaluations;
    result.starts += next.starts;
    result.seconds += next.seconds;
    if (!better) break;
  }
  judge(result, peak_strain_of(quasi_static), options);
  return result;
}

}  // namespace cushion::calibration
