#include "calibration/parallel_jobs.hpp"

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
                                             SpareCores* spare, std::vector<double> upper_bounds)
    : DifferenceCost(std::move(residuals), parameters, n_residuals, relative_step, spare),
      upper_(std::move(upper_bounds)) {
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
  return evaluate(
      parameters, residuals, jacobians, [this](int j, double step, const double* u, const double* r, double* J) {
        std::vector<double> x(u, u + parameters_), r_step(static_cast<std::size_t>(n_residuals_));
        x[j] = u[j] + step;
        double signed_step = step;
        const bool beyond_bound = !upper_.empty() && x[j] > upper_[static_cast<std::size_t>(j)];
        if (beyond_bound || !residuals_(x.data(), r_step.data())) {  // beyond the bound or the model fails: backward
          x[j] = u[j] - step;
          signed_step = -step;
          if (!residuals_(x.data(), r_step.data())) return false;
        }
        const double one_over_step = 1.0 / signed_step;
        double gradient = 0.0;  // d(cost)/du_j = sum_i r_i dr_i/du_j
        for (int i = 0; i < n_residuals_; ++i) {
          J[i * parameters_ + j] = (r_step[i] - r[i]) * one_over_step;
          gradient += r[i] * J[i * parameters_ + j];
        }
        // At the upper bound with the descent direction outward the bound is active: the zero column a clamping model
        // gives, so that the step of the other parameters is not the projection of one that leaves the box.
        if (beyond_bound && gradient < 0.0)
          for (int i = 0; i < n_residuals_; ++i) J[i * parameters_ + j] = 0.0;
        return true;
      });
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
