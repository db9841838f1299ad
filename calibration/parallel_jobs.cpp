#include "calibration/parallel_jobs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cushion::calibration {

namespace {

/// Ceres' numeric-difference step for a parameter at u_j (ceres/internal/numeric_diff.h): never below sqrt(eps).
double numeric_step(double u_j, double relative_step) {
  return std::max(std::sqrt(std::numeric_limits<double>::epsilon()), relative_step * std::abs(u_j));
}

}  // namespace

DifferenceCost::DifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step,
                               SpareCores* spare)
    : residuals_(std::move(residuals)),
      parameters_(parameters),
      n_residuals_(n_residuals),
      relative_step_(relative_step),
      spare_(spare) {
  mutable_parameter_block_sizes()->push_back(parameters);
  set_num_residuals(n_residuals);
}

bool DifferenceCost::evaluate(double const* const* parameters, double* residuals, double** jacobians,
                              const Column& column) const {
  const double* u = parameters[0];
  if (!residuals_(u, residuals)) return false;
  if (!jacobians || !jacobians[0]) return true;
  std::atomic<bool> ok{true};
  parallel_for(static_cast<std::size_t>(parameters_), spare_, [&](std::size_t j) {
    if (!column(static_cast<int>(j), numeric_step(u[j], relative_step_), u, residuals, jacobians[0])) ok = false;
  });
  return ok;
}

ForwardDifferenceCost::ForwardDifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step,
                                             SpareCores* spare, std::vector<double> upper_bounds,
                                             Residuals jacobian_residuals)
    : DifferenceCost(std::move(residuals), parameters, n_residuals, relative_step, spare),
      upper_(std::move(upper_bounds)),
      jacobian_residuals_(std::move(jacobian_residuals)) {
  if (!upper_.empty() && upper_.size() != static_cast<std::size_t>(parameters))
    throw std::invalid_argument("ForwardDifferenceCost: one upper bound per parameter");
}

void parallel_for(std::size_t n, SpareCores* spare, const std::function<void(std::size_t)>& f) {
  if (n < 2 || !spare || !spare->borrow()) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next++) < n;) f(i);
  };
  std::thread helper(work);
  work();
  helper.join();
  spare->lend();
}

bool ForwardDifferenceCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const double* u = parameters[0];
  if (!residuals_(u, residuals)) return false;
  if (!jacobians || !jacobians[0]) return true;
  // The function the columns difference, g: `residuals` (g(u) = r(u), known), or the cheaper one, run at u beside the
  // columns' points (index `parameters_` of the parallel loop).
  const bool cheaper = static_cast<bool>(jacobian_residuals_);
  const Residuals& g = cheaper ? jacobian_residuals_ : residuals_;
  const auto n = static_cast<std::size_t>(n_residuals_), m = static_cast<std::size_t>(parameters_);
  std::vector<double> g_points((m + 1) * n), signed_step(m);  // g at u + signed_step_j e_j (row j), g(u) (row m)
  std::vector<char> ok(m + 1, 1), beyond_bound(m, 0);
  parallel_for(m + (cheaper ? 1 : 0), spare_, [&](std::size_t j) {
    double* g_j = g_points.data() + j * n;
    if (j == m) {
      ok[j] = jacobian_residuals_(u, g_j);
      return;
    }
    const double step = numeric_step(u[j], relative_step_);
    std::vector<double> x(u, u + m);
    x[j] = u[j] + step;
    signed_step[j] = step;
    beyond_bound[j] = !upper_.empty() && x[j] > upper_[j];
    if (beyond_bound[j] || !g(x.data(), g_j)) {  // beyond the bound or the model fails: backward
      x[j] = u[j] - step;
      signed_step[j] = -step;
      ok[j] = g(x.data(), g_j);
    }
  });
  if (std::count(ok.begin(), ok.end(), 0) > 0) return false;
  const double* g_u = cheaper ? g_points.data() + m * n : residuals;
  double* J = jacobians[0];
  for (std::size_t j = 0; j < m; ++j) {
    const double* g_j = g_points.data() + j * n;
    const double one_over_step = 1.0 / signed_step[j];
    double gradient = 0.0;  // d(cost)/du_j = sum_i r_i dr_i/du_j
    for (std::size_t i = 0; i < n; ++i) {
      J[i * m + j] = (g_j[i] - g_u[i]) * one_over_step;
      gradient += residuals[i] * J[i * m + j];
    }
    // At the upper bound with the descent direction outward the bound is active: the zero column a clamping model
    // gives, so that the step of the other parameters is not the projection of one that leaves the box.
    if (beyond_bound[j] && gradient < 0.0)
      for (std::size_t i = 0; i < n; ++i) J[i * m + j] = 0.0;
  }
  return true;
}

bool CentralDifferenceCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  return evaluate(parameters, residuals, jacobians,
                  [this](int j, double step, const double* u, const double*, double* J) {
                    std::vector<double> x(u, u + parameters_), r_plus(static_cast<std::size_t>(n_residuals_)),
                        r_minus(r_plus.size());
                    x[j] = u[j] + step;
                    if (!residuals_(x.data(), r_plus.data())) return false;
                    x[j] = u[j] - step;
                    if (!residuals_(x.data(), r_minus.data())) return false;
                    const double half_over_step = (1.0 / step) / 2;  // as Ceres: 1/step, then halved
                    for (int i = 0; i < n_residuals_; ++i)
                      J[i * parameters_ + j] = (r_plus[i] - r_minus[i]) * half_over_step;
                    return true;
                  });
}

}  // namespace cushion::calibration
