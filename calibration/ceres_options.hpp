#pragma once
/// One place for the Ceres settings the calibration fits share: a silent dense-QR trust-region
/// solve of a small bounded least-squares problem (a few to a few dozen parameters).
#include <ceres/ceres.h>

namespace cushion::calibration {

/// Stopping tolerances of a fit (Ceres' relative tests, dimensionless) and its iteration limit.
struct FitTolerances {
  double function = 1e-12;   ///< |d cost| / cost
  double gradient = 1e-12;   ///< max |projected gradient|
  double parameter = 1e-10;  ///< |d x| / (|x| + tolerance)
  int max_iterations = 200;
};

/// Trust-region options with the given strategy (Levenberg-Marquardt or dogleg), DENSE_QR, silent,
/// single-threaded (fits run inside multi-start loops and must be deterministic).
inline ceres::Solver::Options dense_fit_options(const FitTolerances& t,
                                                ceres::TrustRegionStrategyType strategy = ceres::LEVENBERG_MARQUARDT) {
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = strategy;
  so.linear_solver_type = ceres::DENSE_QR;
  so.function_tolerance = t.function;
  so.gradient_tolerance = t.gradient;
  so.parameter_tolerance = t.parameter;
  so.max_num_iterations = t.max_iterations;
  so.logging_type = ceres::SILENT;
  so.num_threads = 1;
  return so;
}

}  // namespace cushion::calibration
