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
///   1. global, on about 100 samples per quasi-static test and every dynamic row: for every N-subset of the exponent
///      grid (both signs, exponent_grid.hpp; and the start's exponents) a RELAXED linear least-squares problem in
///      (mu_j, b_ji = mu_j a_i), the rank-one structure b = mu a^T dropped: a lower bound of the subset's cost, zero
///      at the true exponents of noise-free data, one small dense solve per subset on the Gram matrix of the grid
///      columns; the best `relaxed_kept` subsets then solved for (mu, a >= 0) by alternating linear least squares
///      (from the relaxed ratios and from the start's), each twice: mu free and mu_i >= 0 (NNLS; with nu >= 0
///      sufficient for Drucker stability);
///   2. multi-start polish, all parameters jointly, Ceres bounded trust region (dogleg) with automatic derivatives
///      (ceres::Jet), bounds a_i >= 0, sum a_i <= a_sum_max (penalty), |mu_i| <= mu_bound peak stresses, alpha_i keeps its sign with
///      0.2 <= |alpha_i| <= 50: the best start of each kind (mu free, mu >= 0) and each sign pattern of the exponents
///      (a polish cannot change a sign, so each pattern is its own basin) within start_cost_ratio of the best, at
///      most polished_starts, on two threads; a parameter left at a bound is then held and the rest
///      polished again (Ceres' projected steps stall while a bound is active, typically a_i = 0);
///   3. the lowest-cost polished result whose hyperfoam is Drucker-stable over the tested range is returned (if
///      none is, the next mu >= 0 starts are polished).
#include <optional>
#include <string>
#include <vector>

#include "calibration/fit_model.hpp"

namespace cushion::calibration {

/// The half-range [decades] of the Prony times when they are freed (`cushion fit --free-tau`, diagnose's base fit).
inline constexpr double free_times_range = 0.5;

struct RefitOptions {
  std::vector<double> alpha_grid;   ///< start exponents; empty: alpha_grid(N, 50) of exponent_grid.hpp (both signs)
  int relaxed_kept = 32;            ///< best subsets of the relaxed screen solved by alternating least squares
  int alternating_iterations = 8;   ///< inner (mu, a) sweeps per grid start
  int polished_starts = 8;          ///< starts polished jointly (on two threads): the best of each kind
                                    ///< (mu free, mu >= 0) and sign pattern of the exponents, lowest cost first
  double start_cost_ratio = 100.0;  ///< polish starts: screen cost at most this times the best start's
  /// Ceres iterations per polish. 60: on six foreign campaigns (diagnose's base fit) every joint cost was the one of
  /// 200 iterations to 4 digits, and the refit took 3.0-5.3 s instead of 5.5-9.5 s (measured 2026-11-28): past ~60
  /// iterations the polishes crawl along a valley of the (mu, a) moduli without a visible gain.
  int max_iterations = 60;
  double a_sum_max = 9.0;           ///< polish bound sum a_i <= this (penalty): long-term modulus >= 10 % of the
                                    ///< instantaneous one (no vanishing long-term curve when one rate cannot separate them)
  double mu_bound = 100.0;          ///< polish bound |mu_i| <= this times the peak stress: no cancelling pair of huge
                                    ///< moduli (an ill-conditioned material on which the solver's Newton fails)
  double function_tolerance = 1e-14, gradient_tolerance = 1e-16, parameter_tolerance = 1e-12;
  double stability_tension = 0.5;   ///< required Drucker-stable nominal strain range [-peak, this]
  std::optional<DynamicSchedule> schedule;  ///< dynamic test timing (empty: about a relaxed preload)
  bool finite_amplitude = true;     ///< dynamic model at the test's sine amplitude (else the small-amplitude limit)
  /// Stage 4: each Prony time tau_i free within a factor 10^times_range of the start's (0: times kept, the default of
  /// `cushion fit`), jointly with every other parameter from the best stable polish; kept when the cost falls and the
  /// hyperfoam stays stable. diagnose's base fit uses 0.5. Not the default: on the lab-made round trip (times on the
  /// decade grid) it slid along the valley of the slow terms and the long-term curve (curve 5.3 % off, a_i 5 % off).
  double times_range = 0.0;
  int times_iterations = 50;        ///< Levenberg-Marquardt iterations of stage 4
  int rounds = 2;                   ///< stages 1-4 again from the result while stage 4 moved the times and the cost fell
  /// Residuals divided by the targets' noise estimates (chi2, as `compare`/`diagnose` weigh them: each quasi-static test
  /// as quasi_static_points samples, every frequency of E' and E'') instead of relative to the peak stress and moduli.
  bool noise_weighted = false;
  int quasi_static_points = 100;
};

struct RefitResult {
  ViscoHyperfoam start, material;     ///< the paper's material and the refitted one
  double quasi_static_rms_start = 0.0, quasi_static_rms = 0.0;  ///< RMS error / peak stress [-] (RMS over the tests)
  double dynamic_rms_start = 0.0, dynamic_rms = 0.0;            ///< RMS relative error of E', E'' [-]
  double cost_start = 0.0, cost = 0.0;
  bool converged = false;  ///< Ceres reported a usable solution
  bool stable = false;     ///< refitted hyperfoam Drucker-stable over the required range
  bool improved = false;   ///< cost decreased
  bool times_moved = false;  ///< stage 4 moved the Prony times (material.prony[i].tau differ from the start's)
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
  std::vector<double> stress_sigma;  ///< local stress noise [MPa] at each record sample (only for noise_weighted)
};

/// A dynamic test as a refit target.
struct DynamicTarget {
  const DynamicTest* test = nullptr;
  std::vector<double> modulus_sigma;  ///< |E*| noise [MPa] at each frequency (only for noise_weighted)
  std::vector<double> phase_sigma;    ///< phase noise [deg] at each frequency (only for noise_weighted)
};

/// Refits `start` (hyperfoam with one common nu + Prony with the dynamic test's tau) to the quasi-static
/// tests (the calibration ones; several rates separate the long-term curve from the slow Prony terms) and
/// the dynamic test. Each quasi-static test weighs as one test. `dynamic` may be empty: a refit on quasi-static records
/// alone (the damage start of calibration/damage_start.hpp). Throws std::invalid_argument without a quasi-static test or
/// when the start's terms do not share one nu.
RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const std::vector<DynamicTarget>& dynamic, const RefitOptions& options = {});

}  // namespace cushion::calibration
