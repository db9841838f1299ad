#include "calibration/hyperfoam_fit.hpp"

#include "calibration/ceres_options.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "calibration/exponent_grid.hpp"
#include "calibration/prony_fit.hpp"
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
      for (int i = 0; i < N; ++i) sum += term_stress(p[0][i], p[1][i], c, (*e)[j]);  // mu in units of peak
      r[j] = sum - (*s)[j] / peak;
    }
    return true;
  }
};

std::string join(const std::vector<double>& v) {
  std::ostringstream o;
  for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
  return o.str();
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

  // 1. Global screen over exponent subsets (on at most ~150 evenly spread points), mu linear.
  std::vector<std::size_t> rows;
  const std::size_t stride = std::max<std::size_t>(1, e.size() / 150);
  for (std::size_t j = 0; j < e.size(); j += stride) rows.push_back(j);
  if (rows.back() + 1 != e.size()) rows.push_back(e.size() - 1);
  Eigen::VectorXd y(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) y(Eigen::Index(k)) = s[rows[k]] / peak;
  const std::vector<double> grid = alpha_grid(N, o.alpha_max);
  const std::vector<std::vector<int>> combos = subsets(int(grid.size()), N);
  const std::vector<double> nus = o.fit_nu ? std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4} : std::vector<double>{o.nu};

  struct Candidate {
    double cost;                  ///< 0.5 sum r^2 (all points)
    std::vector<double> mu, alpha;
    double nu;
    bool non_negative;            ///< mu_i >= 0 kept in the polish
  };
  std::vector<Candidate> screened_nn, screened_free;
  const std::size_t keep = std::size_t(std::max(1, o.polished));
  auto insert = [&](std::vector<Candidate>& list, Candidate c) {
    // Distinct exponent subsets only (a polish of two starts with the same exponents would repeat itself).
    for (const auto& other : list)
      if (other.alpha == c.alpha && other.nu == c.nu) return;
    list.push_back(std::move(c));
    std::sort(list.begin(), list.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    if (list.size() > keep) list.pop_back();
  };
  HyperfoamFit fit;
  for (double nu : nus) {
    const double c = lateral_exponent(nu, o.lateral);
    Eigen::MatrixXd columns(rows.size(), grid.size());
    for (std::size_t g = 0; g < grid.size(); ++g)
      for (std::size_t k = 0; k < rows.size(); ++k) columns(Eigen::Index(k), Eigen::Index(g)) = term_stress(1.0, grid[g], c, e[rows[k]]);  // unit mu: x = mu/peak
    for (const auto& combo : combos) {
      ++fit.starts;
      Eigen::MatrixXd A(rows.size(), N);
      std::vector<double> alpha(N);
      for (int i = 0; i < N; ++i) {
        A.col(i) = columns.col(combo[i]);
        alpha[i] = grid[combo[i]];
      }
      const Eigen::VectorXd m_nn = non_negative_least_squares(A, y);
      const double cost_nn = 0.5 * (A * m_nn - y).squaredNorm();
      if (std::isfinite(cost_nn) && m_nn.maxCoeff() > 0.0)
        insert(screened_nn, {cost_nn, std::vector<double>(m_nn.data(), m_nn.data() + N), alpha, nu, true});
      Eigen::VectorXd scale = A.colwise().norm().transpose();
      for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
      const Eigen::VectorXd m_ls =
          (A * scale.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(y).cwiseQuotient(scale);
      const double cost_ls = 0.5 * (A * m_ls - y).squaredNorm();
      if (m_ls.allFinite() && m_ls.minCoeff() < 0.0 && std::isfinite(cost_ls) && cost_ls < cost_nn)
        insert(screened_free, {cost_ls, std::vector<double>(m_ls.data(), m_ls.data() + N), alpha, nu, false});
    }
  }

  // 2. Polish (mu in units of the peak stress, all points).
  auto stable = [&](const std::vector<double>& mu, const std::vector<double>& alpha, double nu) {
    std::vector<material::HyperfoamTerm> t;
    for (int i = 0; i < N; ++i) t.push_back({mu[i] * peak, alpha[i], nu});
    double sum = 0.0;
    for (double m : mu) sum += m;
    return sum > 0.0 && material::check_stability(material::Hyperfoam(t), -e_max, o.stability_tension).stable();
  };
  auto full_cost = [&](const std::vector<double>& mu, const std::vector<double>& alpha, double nu) {
    std::vector<material::HyperfoamTerm> t;
    for (int i = 0; i < N; ++i) t.push_back({mu[i] * peak, alpha[i], nu});
    const auto model = hyperfoam_uniaxial_stress(t, nu, o.lateral, e);
    double sum = 0.0;
    for (std::size_t j = 0; j < e.size(); ++j) sum += std::pow((model[j] - s[j]) / peak, 2);
    return 0.5 * sum;
  };
  std::vector<Candidate> finals;
  std::vector<Candidate> starts = screened_nn;
  starts.insert(starts.end(), screened_free.begin(), screened_free.end());
  const ceres::Solver::Options so =
      dense_fit_options({o.function_tolerance, o.gradient_tolerance, o.parameter_tolerance, o.max_iterations});
  for (const Candidate& start : starts) {
    std::vector<double> mu = start.mu, alpha = start.alpha, nu{start.nu};
    auto* cost = new ceres::DynamicAutoDiffCostFunction<CurveResidual, 4>(new CurveResidual{&e, &s, peak, N, o.lateral});
    cost->AddParameterBlock(N);
    cost->AddParameterBlock(N);
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(int(e.size()));
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, mu.data(), alpha.data(), nu.data());
    for (int i = 0; i < N; ++i) {
      if (start.non_negative) problem.SetParameterLowerBound(mu.data(), i, 0.0);
      problem.SetParameterLowerBound(alpha.data(), i, alpha[i] > 0 ? 0.2 : -o.alpha_max);
      problem.SetParameterUpperBound(alpha.data(), i, alpha[i] > 0 ? o.alpha_max : -0.2);
    }
    if (o.fit_nu) {
      problem.SetParameterLowerBound(nu.data(), 0, 0.0);
      problem.SetParameterUpperBound(nu.data(), 0, 0.45);
    } else {
      problem.SetParameterBlockConstant(nu.data());
    }
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    ++fit.polishes;
    bool polished = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
    for (double m : mu) polished = polished && std::isfinite(m);
    if (polished) finals.push_back({summary.final_cost, mu, alpha, nu[0], start.non_negative});
    // The start itself (cost on all points) as a fallback when the polish turns unstable.
    finals.push_back({full_cost(start.mu, start.alpha, start.nu), start.mu, start.alpha, start.nu, start.non_negative});
  }
  std::stable_sort(finals.begin(), finals.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });

  // 3. The best Drucker-stable candidate.
  const Candidate* chosen = nullptr;
  for (const auto& c : finals) {
    if (stable(c.mu, c.alpha, c.nu)) {
      chosen = &c;
      break;
    }
    ++fit.rejected_unstable;
  }
  if (!chosen) {
    std::ostringstream msg;
    msg << "fit_hyperfoam: no Drucker-stable " << N << "-term fit over nominal strain [" << -e_max << ", "
        << o.stability_tension << "]: tried " << combos.size() << " exponent subsets of {" << join(grid) << "} at nu {"
        << join(nus) << "} with mu_i >= 0 and free mu_i, and " << fit.polishes << " polishes; all "
        << finals.size() << " candidates unstable (is the elastic curve increasing with compression?)";
    throw std::runtime_error(msg.str());
  }
  fit.stable = true;
  if (fit.rejected_unstable > 0)
    fit.warnings.push_back(std::to_string(fit.rejected_unstable) + " better fit(s) rejected as Drucker-unstable");
  auto to_terms = [&](const Candidate& c) {
    std::vector<material::HyperfoamTerm> t;
    for (int i = 0; i < N; ++i) t.push_back({c.mu[i] * peak, c.alpha[i], c.nu});
    return t;
  };
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
