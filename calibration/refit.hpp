#pragma once
/// Method step 8 (beyond the paper): consistency refit. The paper identifies the hyperfoam from a
/// decomposition made with a LINEAR hereditary model, and the Prony series from small-amplitude
/// dynamic moduli; the solver runs hyperfoam + finite-strain Prony, so the two need not agree.
/// Seeded by the paper's result (its exponents and Prony ratios), the hyperfoam (mu_i [MPa], alpha_i; nu kept) and the Prony
/// moduli a_i = g_i/(1 - sum g) (tau_i kept) are refitted jointly so that the SOLVER's model matches
/// both calibration tests at once:
///   quasi-static: the solver's model under platen control, evaluated EXACTLY and explicitly by the fast
///     uniaxial model (uniaxial_model.hpp; equal to the material-point driver while the platen touches), at
///     every in-contact record sample k of each test (contact_samples), residuals
///     (sigma_model(t_k) - sigma_k) / sigma_peak / sqrt(K T) (K samples, T tests);
///   dynamic: the complex modulus about the preload along the test's schedule at the test's finite sine
///     amplitude (uniaxial_dynamic_moduli, same fast model), residuals (E'_model/E' - 1, E''_model/E'' - 1) / sqrt(2 F) at the F frequencies.
/// Cost = (RMS_qs^2 + RMS_dyn^2)/2. The model is linear in mu for fixed (alpha, a) and linear in a for fixed
/// (alpha, mu), so the search is:
///   1. global: for every N-subset of `alpha_grid` (and the start's alphas) the inner problem in (mu, a >= 0)
///      is solved by alternating linear least squares (non-negative for a), from the start's a;
///   2. polish: the best `polished_starts` of them, all parameters jointly, Ceres bounded trust region
///      (dogleg) with automatic derivatives (ceres::Jet), bounds a_i >= 0, alpha_i keeps its
///      sign with 0.2 <= |alpha_i| <= 50;
///   Each subset is solved twice: mu free and mu_i >= 0 (NNLS; with nu >= 0 sufficient for Drucker stability);
///   3. the lowest-cost polished result whose hyperfoam is Drucker-stable over the tested range is returned;
///      the free-mu starts are polished first, the mu >= 0 ones (bounded polish) when none of those ends stable.
#include <optional>
#include <string>
#include <vector>

#include "calibration/fit_model.hpp"

namespace cushion::calibration {

struct RefitOptions {
  std::vector<double> alpha_grid = {-4.0, -2.0, -1.0, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0, 30.0};  ///< start exponents
  int alternating_iterations = 8;   ///< inner (mu, a) sweeps per grid start
  int polished_starts = 2;          ///< best grid starts polished jointly (two at a time on two threads)
  int max_iterations = 200;         ///< Ceres iterations per polish
  double function_tolerance = 1e-14, gradient_tolerance = 1e-16, parameter_tolerance = 1e-12;
  double stability_tension = 0.5;   ///< required Drucker-stable nominal strain range [-peak, this]
  std::optional<DynamicSchedule> schedule;  ///< dynamic test timing (empty: about a relaxed preload)
  bool finite_amplitude = true;     ///< dynamic model at the test's sine amplitude (else the small-amplitude limit)
};

struct RefitResult {
  ViscoHyperfoam start, material;     ///< the paper's material and the refitted one
  double quasi_static_rms_start = 0.0, quasi_static_rms = 0.0;  ///< RMS error / peak stress [-] (RMS over the tests)
  double dynamic_rms_start = 0.0, dynamic_rms = 0.0;            ///< RMS relative error of E', E'' [-]
  double cost_start = 0.0, cost = 0.0;
  bool converged = false;  ///< Ceres reported a usable solution
  bool stable = false;     ///< refitted hyperfoam Drucker-stable over the required range
  bool improved = false;   ///< cost decreased
  int starts = 0;          ///< grid starts solved (step 1)
  int iterations = 0;      ///< Ceres iterations of the polishes (step 2)
  int evaluations = 0;     ///< model evaluations (residual vectors; a Jacobian counts once)
  double seconds = 0.0;
  std::string stability;   ///< check_stability summary of the refitted hyperfoam
  std::string report;      ///< Ceres brief report
  std::string rejection;   ///< why not accepted: never empty when !accepted(), empty when accepted()
  bool accepted() const { return converged && stable && improved; }
};

/// A quasi-static test with its segments, as a refit target.
struct QuasiStaticTarget {
  const QuasiStaticTest* test = nullptr;
  Segments segments;
};

/// Refits `start` (hyperfoam with one common nu + Prony with the dynamic test's tau) to the quasi-static
/// tests (the calibration ones; several rates separate the long-term curve from the slow Prony terms) and
/// the dynamic test. Each quasi-static test weighs as one test. Throws std::invalid_argument without a
/// quasi-static test or when the start's terms do not share one nu.
RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const DynamicTest& dynamic, const RefitOptions& options = {});

}  // namespace cushion::calibration
