#include "calibration/prony_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cushion::calibration {
namespace {

/// Rows: storage rows [1, a_r(w_i)] / Ebar'_i, loss rows [0, b_r(w_i)] / Ebar''_i; target 1.
Eigen::MatrixXd design(const DynamicModuli& d, const std::vector<double>& tau) {
  const std::size_t M = d.frequency.size(), n = tau.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * M, n + 1);
  for (std::size_t i = 0; i < M; ++i) {
    const double w = 2.0 * std::numbers::pi * d.frequency[i];
    A(i, 0) = 1.0 / d.storage[i];
    for (std::size_t r = 0; r < n; ++r) {
      const double wt = w * tau[r];
      A(i, r + 1) = wt * wt / (1.0 + wt * wt) / d.storage[i];
      A(M + i, r + 1) = wt / (1.0 + wt * wt) / d.loss[i];
    }
  }
  return A;
}


PronyFit finish(PronyFit fit, const Eigen::VectorXd& x, const Eigen::MatrixXd& A, const Eigen::VectorXd& ones,
                const DynamicModuli& d, const std::vector<double>& tau, bool fixed);

}  // namespace

/// Non-negative least squares min |A x - b| s.t. x >= 0 by the Lawson-Hanson active-set method
/// (Eigen 3.4 in Debian has no NNLS module, and Ceres' projected trust region stalled on this
/// ill-conditioned problem far from the KKT point). Columns are scaled to unit norm first.
Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& A0, const Eigen::VectorXd& b) {
  const Eigen::Index n = A0.cols();
  Eigen::VectorXd scale = A0.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < n; ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
  const Eigen::MatrixXd A = A0 * scale.cwiseInverse().asDiagonal();
  std::vector<bool> passive(n, false);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const double tol = 1e-12 * A.norm() * b.norm();
  auto solve_passive = [&]() {
    std::vector<Eigen::Index> P;
    for (Eigen::Index j = 0; j < n; ++j)
      if (passive[j]) P.push_back(j);
    Eigen::MatrixXd AP(A.rows(), Eigen::Index(P.size()));
    for (std::size_t k = 0; k < P.size(); ++k) AP.col(Eigen::Index(k)) = A.col(P[k]);
    const Eigen::VectorXd sP = AP.colPivHouseholderQr().solve(b);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
    for (std::size_t k = 0; k < P.size(); ++k) s(P[k]) = sP(Eigen::Index(k));
    return s;
  };
  for (int outer = 0; outer < 3 * int(n) + 10; ++outer) {
    const Eigen::VectorXd w = A.transpose() * (b - A * x);
    Eigen::Index t = -1;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!passive[j] && w(j) > tol && (t < 0 || w(j) > w(t))) t = j;
    if (t < 0) break;
    passive[t] = true;
    for (int inner = 0; inner < 3 * int(n) + 10; ++inner) {
      const Eigen::VectorXd s = solve_passive();
      bool feasible = true;
      double step = 1.0;
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[j] && s(j) <= 0.0) {
          feasible = false;
          step = std::min(step, x(j) / (x(j) - s(j)));
        }
      if (feasible) {
        x = s;
        break;
      }
      x += step * (s - x);
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[j] && x(j) <= 1e-15 * (1.0 + x.cwiseAbs().maxCoeff())) {
          passive[j] = false;
          x(j) = 0.0;
        }
    }
  }
  return x.cwiseQuotient(scale);
}

DynamicModuli prony_moduli(double E_inf, const std::vector<double>& E, const std::vector<double>& tau,
                           const std::vector<double>& frequency) {
  DynamicModuli d;
  d.frequency = frequency;
  for (double f : frequency) {
    const double w = 2.0 * std::numbers::pi * f;
    double s = E_inf, l = 0.0;
    for (std::size_t r = 0; r < E.size(); ++r) {
      const double wt = w * tau[r];
      s += E[r] * wt * wt / (1.0 + wt * wt);
      l += E[r] * wt / (1.0 + wt * wt);
    }
    d.storage.push_back(s);
    d.loss.push_back(l);
  }
  return d;
}

namespace {

/// Least squares A x = b with x >= 0: column scaling, then rank-revealing QR (the 100 s term at 1-20 Hz is
/// nearly collinear with E_inf); Lawson-Hanson NNLS when a modulus comes out negative (`bounds_active` set).
Eigen::VectorXd non_negative_solution(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, bool& bounds_active) {
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
  const Eigen::VectorXd x = (A * scale.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(b).cwiseQuotient(scale);
  if (x.minCoeff() >= 0.0) return x;
  bounds_active = true;
  return non_negative_least_squares(A, b);
}

}  // namespace

PronyFit fit_prony(const DynamicModuli& d, const std::vector<double>& tau, std::optional<double> E_inf_fixed) {
  const std::size_t M = d.frequency.size();
  if (M < 3 || d.storage.size() != M || d.loss.size() != M)
    throw std::invalid_argument("fit_prony: need at least 3 frequencies with storage and loss moduli");
  for (std::size_t i = 0; i < M; ++i)
    if (!(d.frequency[i] > 0.0 && d.storage[i] > 0.0 && d.loss[i] > 0.0))
      throw std::invalid_argument("fit_prony: frequencies and moduli must be positive");
  if (tau.empty()) throw std::invalid_argument("fit_prony: no relaxation times");
  for (double t : tau)
    if (!(t > 0.0)) throw std::invalid_argument("fit_prony: relaxation times must be positive");

  if (E_inf_fixed && !(*E_inf_fixed >= 0.0 && std::isfinite(*E_inf_fixed)))
    throw std::invalid_argument("fit_prony: the given E_inf must be finite and >= 0");
  const Eigen::MatrixXd A_full = design(d, tau);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(A_full.rows());
  if (E_inf_fixed) {
    // E_inf given: fit E_r >= 0 to the rest (the E_inf column times E_inf moved to the target).
    const Eigen::MatrixXd A = A_full.rightCols(A_full.cols() - 1);
    const Eigen::VectorXd target = ones - A_full.col(0) * *E_inf_fixed;
    PronyFit fit;
    const Eigen::VectorXd Er = non_negative_solution(A, target, fit.bounds_active);
    Eigen::VectorXd x(A_full.cols());
    x(0) = *E_inf_fixed;
    x.tail(Er.size()) = Er;
    return finish(fit, x, A_full, ones, d, tau, true);
  }
  PronyFit fit;
  const Eigen::VectorXd x = non_negative_solution(A_full, ones, fit.bounds_active);
  return finish(fit, x, A_full, ones, d, tau, false);
}

namespace {
PronyFit finish(PronyFit fit, const Eigen::VectorXd& x, const Eigen::MatrixXd& A, const Eigen::VectorXd& ones,
                const DynamicModuli& d, const std::vector<double>& tau, bool fixed) {
  const std::size_t M = d.frequency.size();
  fit.tau = tau;
  fit.E_inf_fixed = fixed;
  fit.E_inf = x(0);
  fit.E.assign(x.data() + 1, x.data() + x.size());
  fit.chi2 = (A * x - ones).squaredNorm();

  const DynamicModuli model = prony_moduli(fit.E_inf, fit.E, tau, d.frequency);
  const double deg = 180.0 / std::numbers::pi;
  for (std::size_t i = 0; i < M; ++i) {
    PronyResidual r;
    r.frequency = d.frequency[i];
    r.storage = d.storage[i];
    r.loss = d.loss[i];
    r.storage_model = model.storage[i];
    r.loss_model = model.loss[i];
    r.magnitude = std::hypot(r.storage, r.loss);
    r.magnitude_model = std::hypot(r.storage_model, r.loss_model);
    r.phase = std::atan2(r.loss, r.storage) * deg;
    r.phase_model = std::atan2(r.loss_model, r.storage_model) * deg;
    fit.residuals.push_back(r);
  }
  return fit;
}
}  // namespace

}  // namespace cushion::calibration
