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

/// For a bounded problem with NUMERIC derivatives: Ceres' trust-region minimiser runs a projected Armijo line search
/// on every step of a bounded problem, and with the default cubic interpolation every trial point also evaluates the
/// gradient, i.e. a whole forward-difference Jacobian (k + 1 model runs for k parameters) even when the full step is
/// accepted. Bisection needs the cost only (one run per trial). Measured (session 14): diagnose's candidate fits on
/// foreign campaign c052 took 2-4x fewer runs for the same or lower chi2; the refit's time polish 6.46 -> 4.62 s.
/// (With automatic derivatives the gradient is cheap; every calibration fit with bisection left one of 200 random
/// foams at 1.00 % of peak: not used there.)
inline void use_cost_only_line_search(ceres::Solver::Options& so) {
  so.line_search_interpolation_type = ceres::BISECTION;
}

}  // namespace cushion::calibration
