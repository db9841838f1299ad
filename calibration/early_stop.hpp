#pragma once
/// An early stop of a Ceres least-squares fit: after a given number of iterations, the fit stops when its chi2 is still
/// above a bound. diagnose stops a pair whose second effect explains too little of what the best single leaves to be
/// named (DiagnoseOptions::pair_stop_share, docs/physics.md 9.21).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <ceres/iteration_callback.h>

namespace cushion::calibration {

/// Stops Levenberg-Marquardt after `iteration` iterations when chi2 (twice Ceres' cost, at the current point) is still
/// above `chi2_above`: a pair whose second effect explains too little by then (DiagnoseOptions::pair_stop_share).
struct EarlyStop {
  int iteration = 0;
  double chi2_above = std::numeric_limits<double>::infinity();
  std::string why;  ///< the end of the warning of a fit stopped so: "stopped after N iterations: <why>"
  bool active() const { return iteration > 0 && std::isfinite(chi2_above); }
};

/// The Ceres callback of an EarlyStop (the solver it stops reports USER_SUCCESS).
class EarlyStopCallback final : public ceres::IterationCallback {
 public:
  explicit EarlyStopCallback(EarlyStop stop) : stop_(stop) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    if (it.iteration == 0 || it.step_is_successful) chi2_ = std::min(chi2_, 2.0 * it.cost);  // the current point's
    if (static_cast<int>(it.iteration) < stop_.iteration || chi2_ <= stop_.chi2_above) return ceres::SOLVER_CONTINUE;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }

 private:
  EarlyStop stop_;
  double chi2_ = std::numeric_limits<double>::infinity();
};

}  // namespace cushion::calibration
