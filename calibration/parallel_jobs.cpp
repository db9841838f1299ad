#include "calibration/parallel_jobs.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace cushion::calibration {

ForwardDifferenceCost::ForwardDifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step,
                                             SpareCores* spare, std::vector<double> upper_bounds)
    : residuals_(std::move(residuals)),
      parameters_(parameters),
      n_residuals_(n_residuals),
      relative_step_(relative_step),
      spare_(spare),
      upper_(std::move(upper_bounds)) {
  if (!upper_.empty() && upper_.size() != static_cast<std::size_t>(parameters))
    throw std::invalid_argument("ForwardDifferenceCost: one upper bound per parameter");
  mutable_parameter_block_sizes()->push_back(parameters);
  set_num_residuals(n_residuals);
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
  double* J = jacobians[0];
  const double min_step = std::sqrt(std::numeric_limits<double>::epsilon());
  std::atomic<bool> ok{true};
  parallel_for(static_cast<std::size_t>(parameters_), spare_, [&](std::size_t column) {
    const int j = static_cast<int>(column);
    std::vector<double> x(u, u + parameters_), r_step(static_cast<std::size_t>(n_residuals_));
    const double step = std::max(min_step, relative_step_ * std::abs(u[j]));
    x[j] = u[j] + step;
    double signed_step = step;
    const bool beyond_bound = !upper_.empty() && x[j] > upper_[column];
    if (beyond_bound || !residuals_(x.data(), r_step.data())) {  // beyond the bound or the model fails: backward
      x[j] = u[j] - step;
      signed_step = -step;
      if (!residuals_(x.data(), r_step.data())) {
        ok = false;
        return;
      }
    }
    const double one_over_step = 1.0 / signed_step;
    double gradient = 0.0;  // d(cost)/du_j = sum_i r_i dr_i/du_j
    for (int i = 0; i < n_residuals_; ++i) {
      J[i * parameters_ + j] = (r_step[i] - residuals[i]) * one_over_step;
      gradient += residuals[i] * J[i * parameters_ + j];
    }
    // At the upper bound with the descent direction outward the bound is active: the zero column a clamping model
    // gives, so that the step of the other parameters is not the projection of one that leaves the box.
    if (beyond_bound && gradient < 0.0)
      for (int i = 0; i < n_residuals_; ++i) J[i * parameters_ + j] = 0.0;
  });
  return ok;
}

}  // namespace cushion::calibration
