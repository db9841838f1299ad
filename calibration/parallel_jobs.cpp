#include "calibration/parallel_jobs.hpp"

#include <cmath>
#include <limits>

namespace cushion::calibration {

ForwardDifferenceCost::ForwardDifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step,
                                             SpareCores* spare)
    : residuals_(std::move(residuals)),
      parameters_(parameters),
      n_residuals_(n_residuals),
      relative_step_(relative_step),
      spare_(spare) {
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
    if (!residuals_(x.data(), r_step.data())) {  // the model fails just beyond u: the backward difference instead
      x[j] = u[j] - step;
      signed_step = -step;
      if (!residuals_(x.data(), r_step.data())) {
        ok = false;
        return;
      }
    }
    const double one_over_step = 1.0 / signed_step;
    for (int i = 0; i < n_residuals_; ++i) J[i * parameters_ + j] = (r_step[i] - residuals[i]) * one_over_step;
  });
  return ok;
}

}  // namespace cushion::calibration
