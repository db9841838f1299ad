#include "calibration/hyperfoam_fit.hpp"

#include "calibration/ceres_options.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "calibration/uniaxial_model.hpp"
#include "material/stability.hpp"

namespace cushion::calibration {
namespace {

/// Compression-positive nominal stress -l S11 at strain e for one term (uniaxial_model.hpp).
template <typename T>
T term_stress(const T& mu, const T& alpha, const T& c, double e) {
  const double l = 1.0 - e;
  return -l * term_S11(mu, alpha, c, l);
}

struct CurveResidual {
  const std::vector<double>* e;
  const std::vector<double>* s;
  double peak;
  int N;
  Lateral lateral;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    const T c = lateral_exponent(p[2][0], lateral);
    for (std::size_t j = 0; j < e->size(); ++j) {
      T sum(0.0);
      for (int i = 0; i < N; ++i) sum += term_stress(p[0][i], p[1][i], c, (*e)[j]);
      r[j] = (sum - (*s)[j]) / peak;
    }
    return true;
  }
};

std::vector<std::vector<double>> alpha_starts(int N) {
  std::vector<std::vector<double>> starts;
  if (N == 1) {
    for (double a : {1.0, 2.0, 4.0, 10.0, 20.0, 40.0, -2.0}) starts.push_back({a});
    return starts;
  }
  for (auto [lo, hi] : {std::pair{1.0, 10.0}, std::pair{2.0, 20.0}, std::pair{4.0, 40.0}}) {
    std::vector<double> a(N);
    for (int i = 0; i < N; ++i) a[i] = lo * std::pow(hi / lo, double(i) / (N - 1));
    starts.push_back(a);
    a[0] = -a[0];
    starts.push_back(a);
  }
  return starts;
}

}  // namespace

std::vector<double> hyperfoam_uniaxial_stress(const std::vector<material::HyperfoamTerm>& terms, double nu,
                                              Lateral lateral, const std::vector<double>& strain) {
  std::vector<double> s(strain.size(), 0.0);
  const double c = lateral_exponent(nu, lateral);
  for (std::size_t j = 0; j < strain.size(); ++j)
    for (const auto& t : terms) s[j] += term_stress(t.mu, t.alpha, c, strain[j]);
  return s;
}

HyperfoamFit fit_hyperfoam(const ElasticCurve& curve, const HyperfoamFitOptions& o) {
  const int N = o.terms;
  if (N < 1 || N > 6) throw std::invalid_argument("fit_hyperfoam: terms must be 1..6");
  std::vector<double> e, s;
  for (std::size_t j = 0; j < curve.strain.size(); ++j)
    if (curve.strain[j] >= 0.0 && curve.strain[j] < 0.99) {
      e.push_back(curve.strain[j]);
      s.push_back(curve.stress[j]);
    }
  if (e.size() < std::size_t(2 * N + (o.fit_nu ? 1 : 0)))
    throw std::invalid_argument("fit_hyperfoam: fewer curve points than parameters");
  double peak = 0.0, e_max = 0.0;
  for (std::size_t j = 0; j < e.size(); ++j) {
    peak = std::max(peak, std::abs(s[j]));
    e_max = std::max(e_max, e[j]);
  }
  if (!(peak > 0.0)) throw std::invalid_argument("fit_hyperfoam: the curve has no stress");

  struct Candidate {
    double cost;
    std::vector<double> mu, alpha;
    double nu;
  };
  std::vector<Candidate> candidates;
  HyperfoamFit fit;
  // Every start runs twice: free, and with mu_i >= 0 (with nu >= 0 a sufficient condition for Drucker
  // stability), so that a stable candidate exists whenever the free optimum is unstable.
  for (const bool positive_mu : {false, true})
  for (const auto& a0 : alpha_starts(N)) {
    std::vector<double> mu(N), alpha = a0, nu{o.nu};
    // Variable projection start: mu linear for fixed alpha, nu.
    Eigen::MatrixXd A(e.size(), N);
    Eigen::VectorXd b(e.size());
    const double c = lateral_exponent(nu[0], o.lateral);
    for (std::size_t j = 0; j < e.size(); ++j) {
      for (int i = 0; i < N; ++i) A(j, i) = term_stress(1.0, alpha[i], c, e[j]);
      b(j) = s[j];
    }
    const Eigen::VectorXd m0 = A.colPivHouseholderQr().solve(b);
    for (int i = 0; i < N; ++i) mu[i] = std::isfinite(m0(i)) ? m0(i) : 0.0;
    if (positive_mu)
      for (int i = 0; i < N; ++i) mu[i] = std::max(mu[i], 1e-3 * peak / N);

    auto* cost = new ceres::DynamicAutoDiffCostFunction<CurveResidual, 4>(
        new CurveResidual{&e, &s, peak, N, o.lateral});
    cost->AddParameterBlock(N);
    cost->AddParameterBlock(N);
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(int(e.size()));
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, mu.data(), alpha.data(), nu.data());
    for (int i = 0; i < N; ++i) {
      if (positive_mu) problem.SetParameterLowerBound(mu.data(), i, 0.0);
      problem.SetParameterLowerBound(alpha.data(), i, alpha[i] > 0 ? 0.2 : -o.alpha_max);
      problem.SetParameterUpperBound(alpha.data(), i, alpha[i] > 0 ? o.alpha_max : -0.2);
    }
    if (o.fit_nu) {
      problem.SetParameterLowerBound(nu.data(), 0, 0.0);
      problem.SetParameterUpperBound(nu.data(), 0, 0.45);
    } else {
      problem.SetParameterBlockConstant(nu.data());
    }
    const ceres::Solver::Options so =
        dense_fit_options({o.function_tolerance, o.gradient_tolerance, o.parameter_tolerance, o.max_iterations});
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    ++fit.starts;
    if (summary.IsSolutionUsable() && std::isfinite(summary.final_cost))
      candidates.push_back({summary.final_cost, mu, alpha, nu[0]});
  }
  if (candidates.empty()) throw std::runtime_error("fit_hyperfoam: no start converged");
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });

  auto to_terms = [](const Candidate& c) {
    std::vector<material::HyperfoamTerm> t;
    for (std::size_t i = 0; i < c.mu.size(); ++i) t.push_back({c.mu[i], c.alpha[i], c.nu});
    return t;
  };
  const Candidate* chosen = nullptr;
  for (const auto& c : candidates) {
    const material::Hyperfoam model(to_terms(c));
    if (material::check_stability(model, -e_max, o.stability_tension).stable()) {
      chosen = &c;
      break;
    }
    ++fit.rejected_unstable;
  }
  fit.stable = chosen != nullptr;
  if (!chosen) {
    chosen = &candidates.front();
    fit.warnings.push_back("no Drucker-stable fit over nominal strain [" + std::to_string(-e_max) + ", " +
                           std::to_string(o.stability_tension) + "]: returning the best (unstable) fit");
  } else if (fit.rejected_unstable > 0) {
    fit.warnings.push_back(std::to_string(fit.rejected_unstable) + " better fit(s) rejected as Drucker-unstable");
  }
  fit.terms = to_terms(*chosen);
  fit.nu = chosen->nu;
  const auto model = hyperfoam_uniaxial_stress(fit.terms, fit.nu, o.lateral, e);
  double sum2 = 0.0;
  for (std::size_t j = 0; j < e.size(); ++j) {
    const double d = std::abs(model[j] - s[j]) / peak;
    sum2 += d * d;
    fit.max_error = std::max(fit.max_error, d);
  }
  fit.rms_error = std::sqrt(sum2 / double(e.size()));
  fit.stability = material::check_stability(material::Hyperfoam(fit.terms)).summary();
  return fit;
}

}  // namespace cushion::calibration
