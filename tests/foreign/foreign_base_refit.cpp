// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/: the
// generator's own base foam refitted to records that contain effects (Levenberg-Marquardt, Eigen).
#include "foreign_base_refit.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include <Eigen/Dense>

namespace foreign_bench {

namespace {

/// theta = [ln mu_i..., alpha_i..., ln a_j..., ln tau_j...].
Eigen::VectorXd pack(const BaseFoam& foam) {
  const std::size_t n = foam.hyperfoam.size(), m = foam.prony.size();
  Eigen::VectorXd theta(static_cast<Eigen::Index>(2 * n + 2 * m));
  for (std::size_t i = 0; i < n; ++i) {
    theta[static_cast<Eigen::Index>(i)] = std::log(foam.hyperfoam[i].mu_kPa);
    theta[static_cast<Eigen::Index>(n + i)] = foam.hyperfoam[i].alpha;
  }
  for (std::size_t j = 0; j < m; ++j) {
    theta[static_cast<Eigen::Index>(2 * n + j)] = std::log(foam.decorator_weight(j));
    theta[static_cast<Eigen::Index>(2 * n + m + j)] = std::log(foam.prony[j].tau_s);
  }
  return theta;
}

/// The foam of theta (the template gives the family, density and term counts); g_j = a_j/(1 + sum a).
BaseFoam unpack(const BaseFoam& like, const Eigen::VectorXd& theta) {
  BaseFoam foam = like;
  const std::size_t n = foam.hyperfoam.size(), m = foam.prony.size();
  double sum_a = 0.0;
  for (std::size_t j = 0; j < m; ++j) sum_a += std::exp(theta[static_cast<Eigen::Index>(2 * n + j)]);
  for (std::size_t i = 0; i < n; ++i)
    foam.hyperfoam[i] = {std::exp(theta[static_cast<Eigen::Index>(i)]), theta[static_cast<Eigen::Index>(n + i)]};
  for (std::size_t j = 0; j < m; ++j)
    foam.prony[j] = {std::exp(theta[static_cast<Eigen::Index>(2 * n + j)]) / (1.0 + sum_a),
                     std::exp(theta[static_cast<Eigen::Index>(2 * n + m + j)])};
  return foam;
}

/// An exponent that keeps the sign and the distance from 0 (0.2) of the start's: the term stays the plateau,
/// densification or extra term it was (alpha -> 0 is singular in the energy).
/// A kept effect's magnitude stays within 3 decades of its start.
bool admissible(const Eigen::VectorXd& theta, const Eigen::VectorXd& start, std::size_t terms, Eigen::Index kept_from) {
  for (std::size_t i = terms; i < 2 * terms; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (theta[k] * start[k] <= 0.0 || std::abs(theta[k]) < 0.2 || std::abs(theta[k]) > 40.0) return false;
  }
  for (Eigen::Index k = kept_from; k < theta.size(); ++k)
    if (std::abs(theta[k]) > 3.0 * std::log(10.0)) return false;
  return theta.allFinite();
}

/// The effects of `kept` with their magnitudes times exp(theta_k) for the entries after the base's.
std::vector<EffectSpec> scaled_effects(const std::vector<EffectSpec>& kept, const BaseFoam& like,
                                       const Eigen::VectorXd& theta) {
  std::vector<EffectSpec> out = kept;
  const auto first = static_cast<Eigen::Index>(2 * like.hyperfoam.size() + 2 * like.prony.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k].parameters[find_form(out[k].family, out[k].form).magnitude] *=
        std::exp(theta[first + static_cast<Eigen::Index>(k)]);
  return out;
}

struct Problem {
  const BaseFoam& like;
  const PlanRecords& data;
  const TestPlan& plan;
  const std::vector<EffectSpec>& kept;

  PlanRecords model(const Eigen::VectorXd& theta) const {
    return simulate_noise_free(unpack(like, theta), scaled_effects(kept, like, theta), plan);
  }
  Eigen::VectorXd residuals(const Eigen::VectorXd& theta) const {
    return normalised_differences(model(theta), data, plan);
  }
  /// Forward differences, columns shared among the hardware threads (each run builds its own records).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& theta, const Eigen::VectorXd& r0) const {
    Eigen::MatrixXd J(r0.size(), theta.size());
    const unsigned threads = std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(), 8u));
    auto column = [&](Eigen::Index k) {
      Eigen::VectorXd t = theta;
      const double h = 1e-6 * std::max(1.0, std::abs(theta[k]));
      t[k] += h;
      J.col(k) = (residuals(t) - r0) / h;
    };
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < threads; ++w)
      pool.emplace_back([&, w] {
        for (Eigen::Index k = w; k < theta.size(); k += threads) column(k);
      });
    for (auto& t : pool) t.join();
    return J;
  }
};

}  // namespace

BaseRefit refit_base(const BaseFoam& truth_base, const std::vector<EffectSpec>& effects, const TestPlan& plan,
                     const BaseFoam* start, int max_iterations, const std::vector<EffectSpec>& kept) {
  const PlanRecords data = simulate_noise_free(truth_base, effects, plan);
  const BaseFoam& from = start ? *start : truth_base;
  const Eigen::VectorXd base0 = pack(from);
  Eigen::VectorXd theta0 = Eigen::VectorXd::Zero(base0.size() + static_cast<Eigen::Index>(kept.size()));
  theta0.head(base0.size()) = base0;
  const Problem problem{from, data, plan, kept};
  Eigen::VectorXd theta = theta0, r = problem.residuals(theta);
  double cost = r.squaredNorm(), lambda = 1e-3;
  BaseRefit out;
  const PlanRecords truth_alone = simulate_noise_free(truth_base, {}, plan);
  out.ratio_before = ratios_between(truth_alone, data, plan);
  out.chi2_before = normalised_differences(truth_alone, data, plan).squaredNorm();
  int iteration = 0;
  for (; iteration < max_iterations; ++iteration) {
    const Eigen::MatrixXd J = problem.jacobian(theta, r);
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    const Eigen::VectorXd scale = A.diagonal().cwiseMax(1e-12 * std::max(1.0, A.diagonal().maxCoeff()));
    bool accepted = false;
    double new_cost = cost;
    for (int trial = 0; trial < 12 && !accepted; ++trial) {
      Eigen::MatrixXd M = A;
      M.diagonal() += lambda * scale;
      const Eigen::VectorXd step = M.ldlt().solve(-g);
      const Eigen::VectorXd candidate = theta + step;
      if (admissible(candidate, theta0, from.hyperfoam.size(), base0.size())) {
        const Eigen::VectorXd rc = problem.residuals(candidate);
        if (rc.allFinite() && rc.squaredNorm() < cost) {
          theta = candidate, r = rc, new_cost = rc.squaredNorm(), accepted = true;
          lambda = std::max(lambda / 3.0, 1e-9);
          break;
        }
      }
      lambda *= 4.0;
    }
    if (!accepted) break;
    const bool stalled = cost - new_cost < 1e-6 * cost;
    cost = new_cost;
    if (stalled || cost < 1e-12) break;
  }
  out.base = unpack(from, theta);
  out.kept = scaled_effects(kept, from, theta);
  out.chi2_after = cost;
  out.ratio_after = ratios_between(problem.model(theta), data, plan);
  out.iterations = iteration;
  return out;
}

}  // namespace foreign_bench
