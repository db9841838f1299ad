#pragma once
/// Method step 8 (beyond the paper): consistency refit. The paper identifies the hyperfoam from a
/// decomposition made with a LINEAR hereditary model, and the Prony series from small-amplitude
/// dynamic moduli; the solver runs hyperfoam + finite-strain Prony, so the two need not agree.
/// Starting from the paper's result, the hyperfoam (mu_i [MPa], alpha_i; nu kept) and the Prony
/// moduli a_i = g_i/(1 - sum g) (tau_i kept) are refitted jointly so that the SOLVER's model matches
/// both calibration tests at once:
///   quasi-static: the material-point driver under platen control (calibration::run_quasi_static, the
///     lab's protocol rebuilt from the record: rate, peak strain, hold), residuals
///     (sigma_model(t_k) - sigma_k) / sigma_peak / sqrt(K) at K record samples;
///   dynamic: model_dynamic_moduli (complex tangent about the preload, along the test's schedule, fit_model.hpp),
///     residuals (E'_model/E' - 1, E''_model/E'' - 1) / sqrt(2 F) at the F frequencies.
/// Cost = (RMS_qs^2 + RMS_dyn^2)/2, each test normalised on its own. Ceres bounded trust region
/// (Levenberg-Marquardt, bounds: a_i >= 0, alpha_i keeps its sign with 0.2 <= |alpha_i| <= 50),
/// forward-difference Jacobian with its columns evaluated on `threads` threads.
#include <optional>
#include <string>
#include <vector>

#include "material/calibration/fit_model.hpp"

namespace cushion::calibration {

struct RefitOptions {
  double max_sample_hz = 4.0;   ///< driver steps per second of test (the record's rate if lower)
  int max_quasi_static_points = 160;  ///< record samples used as residuals (evenly spread)
  int max_iterations = 40;
  double function_tolerance = 1e-9, gradient_tolerance = 1e-12, parameter_tolerance = 1e-9;
  int threads = 2;
  double stability_tension = 0.5;  ///< required Drucker-stable nominal strain range [-peak, this]
  std::optional<DynamicSchedule> schedule;  ///< dynamic test timing (empty: about a relaxed preload)
};

struct RefitResult {
  ViscoHyperfoam start, material;     ///< the paper's material and the refitted one
  double quasi_static_rms_start = 0.0, quasi_static_rms = 0.0;  ///< RMS error / peak stress [-] (RMS over the tests)
  double dynamic_rms_start = 0.0, dynamic_rms = 0.0;            ///< RMS relative error of E', E'' [-]
  double cost_start = 0.0, cost = 0.0;
  bool converged = false;  ///< Ceres reported a usable solution
  bool stable = false;     ///< refitted hyperfoam Drucker-stable over the required range
  bool improved = false;   ///< cost decreased
  bool started_stable = false;  ///< the paper's hyperfoam was unstable: started from a stable approximation of it
  int iterations = 0, evaluations = 0;
  double seconds = 0.0;
  std::string stability;   ///< check_stability summary of the refitted hyperfoam
  std::string report;      ///< Ceres brief report
  bool accepted() const { return converged && stable && improved; }
};

/// A quasi-static test with its segments, as a refit target.
struct QuasiStaticTarget {
  const QuasiStaticTest* test = nullptr;
  Segments segments;
};

/// Refits `start` (hyperfoam + Prony with the dynamic test's tau) to the quasi-static tests (normally
/// the calibration one; several rates separate the long-term curve from the slow Prony terms, which one
/// rate cannot) and the dynamic test. Each quasi-static test weighs as one test.
RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const DynamicTest& dynamic, const RefitOptions& options = {});

}  // namespace cushion::calibration
