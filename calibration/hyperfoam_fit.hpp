#pragma once
/// Hyperfoam fit (ABAQUS *HYPERFOAM, N = 1..6 terms, one common nu) to the elastic curve
/// sigma_e(eps) from the decomposition: nominal stress, nominal strain, compression positive.
/// Closed forms used (stretch l = 1 - eps, tension-positive nominal stress T):
///   free lateral faces:  T_U = sum (2 mu_i/alpha_i) (l^(alpha_i - 1) - l^(-alpha_i nu - 1))
///   laterally constrained (l2 = l3 = 1, J = l): T_C = sum (2 mu_i/alpha_i) (l^(alpha_i - 1) - l^(-alpha_i b - 1)),
///   b = nu/(1 - 2 nu); the compression-positive model stress is -T.
/// Objective: sum ((model - data)/peak)^2, the ABSOLUTE error normalised by the peak stress (ABAQUS uses
/// the relative error (1 - model/data)^2, which over-weights the near-zero stresses at small strain).
/// Search, Drucker stability as a constraint (never an unstable answer):
///   1. global: for every N-subset of an exponent grid of both signs (0.5 .. alpha_max and -0.5 .. -20; coarser
///      for N >= 4) and each nu of the screen (the given nu; 0, 0.1, .., 0.4 when fitted) the stress is linear
///      in mu: solved by non-negative least squares (mu_i >= 0, with nu >= 0 sufficient for stability) and by
///      free least squares (a negative mu_i may fit better; kept only if stable);
///   2. polish: the best `polished` subsets of each kind, all parameters jointly (Ceres bounded trust region,
///      mu scaled by the peak stress; mu_i >= 0 kept for the non-negative ones, alpha_i keeps its sign with
///      0.2 <= |alpha_i| <= alpha_max);
///   3. the lowest-cost fit that is Drucker-stable over nominal strain [-peak strain, stability_tension]
///      (material/stability.hpp) is returned; an unstable polish falls back to its (checked) start. If no
///      candidate is stable, std::runtime_error says what was tried.
#include <string>
#include <vector>

#include "calibration/decomposition.hpp"
#include "material/hyperfoam.hpp"

namespace cushion::calibration {

enum class Lateral { free, constrained };

/// Model nominal stress [MPa] (compression positive) at compression-positive nominal strains.
std::vector<double> hyperfoam_uniaxial_stress(const std::vector<material::HyperfoamTerm>& terms, double nu,
                                              Lateral lateral, const std::vector<double>& strain);

struct HyperfoamFitOptions {
  int terms = 3;                    ///< N, 1..6 (paper: 3)
  double nu = 0.0;                  ///< fixed Poisson ratio (when !fit_nu)
  bool fit_nu = false;              ///< fit one common nu in [0, 0.45]
  Lateral lateral = Lateral::free;  ///< test kinematics
  double alpha_max = 50.0;          ///< bounds 0.2 <= |alpha_i| <= alpha_max (sign fixed per start)
  int polished = 4;                 ///< best grid subsets polished, of each kind (mu >= 0; free mu)
  double stability_tension = 0.5;   ///< required Drucker-stable range: nominal strain [-peak strain, this]
  double function_tolerance = 1e-12, gradient_tolerance = 1e-12, parameter_tolerance = 1e-10;
  int max_iterations = 500;
};

struct HyperfoamFit {
  std::vector<material::HyperfoamTerm> terms;  ///< mu [MPa], alpha [-], nu [-] (common)
  double nu = 0.0;
  double rms_error = 0.0;   ///< RMS(model - data)/peak [-]
  double max_error = 0.0;   ///< max|model - data|/peak [-]
  bool stable = false;      ///< Drucker-stable over the required range (always true: else fit_hyperfoam throws)
  std::string stability;    ///< check_stability summary over the ABAQUS range (-0.9 .. 10)
  int starts = 0;            ///< exponent subsets screened (step 1) times nu values
  int polishes = 0;          ///< Ceres polishes (step 2)
  int rejected_unstable = 0; ///< better (lower cost) candidates rejected as Drucker-unstable
  std::vector<std::string> warnings;
};

/// Fits to the curve (points with strain in [0, 0.99)); throws std::invalid_argument on fewer points
/// than parameters or N outside 1..6, std::runtime_error when no Drucker-stable fit was found.
HyperfoamFit fit_hyperfoam(const ElasticCurve& curve, const HyperfoamFitOptions& options = {});

}  // namespace cushion::calibration
