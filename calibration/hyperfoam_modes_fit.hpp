#pragma once
/// Hyperfoam fit to homogeneous tests in the ABAQUS modes (hyperfoam-only campaigns), mu_i, alpha_i and
/// nu_i per term jointly, Drucker stability as a constraint (docs/physics.md 2.7).
/// Objective: 0.5 sum over tests and points of
///   ((P_model - P_data)/peak_t)^2                                       (stress; peak_t = max |P_data| of test t)
/// + (w (lf_model - lf_data)/range_t)^2   where a lateral stretch is given (range_t = max |lf_data - 1|, w =
///                                        lateral_weight), the stress and the stretch of a test weighing alike.
/// Search (never an unstable answer, no dependence on a lucky start):
///   1. global screen: with ONE common nu the free stretch does not depend on mu or alpha (lf = x^(-m b/(1 + k b)),
///      hyperfoam_modes.hpp) and every stress is linear in mu: for each nu of {0, 0.05, .., 0.45} and every
///      N-subset of an exponent grid of both signs (exponent_grid.hpp), mu by non-negative and by free least
///      squares; the lowest-cost `polished` subsets of each kind are kept;
///   2. polish: all parameters jointly from each kept start, nu_i per term starting from the common nu (Ceres
///      bounded trust region; mu scaled by the largest peak; alpha keeps its sign, 0.2 <= |alpha| <= alpha_max;
///      0 <= nu_i <= 0.49); the free stretch is solved per point (implicit derivative, hyperfoam_modes.hpp);
///   3. the lowest-cost candidate (polished or start) that is Drucker-stable (material/stability.hpp) in each of
///      the four modes over its stable stretch range (default_stable_stretch, or the campaign's one range for all)
///      and has sum mu > 0 is returned; std::runtime_error otherwise.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "calibration/hyperfoam_campaign.hpp"
#include "material/hyperfoam.hpp"

namespace cushion::calibration {

/// Required Drucker-stable stretch range [min, max] per mode, in material/stability.hpp's order: uniaxial,
/// equibiaxial, planar, volumetric.
using StableStretch = std::array<std::pair<double, double>, 4>;

/// Model vs one test.
struct HyperfoamTestFigures {
  std::vector<double> stress;   ///< model nominal stress [MPa] at the test's controls
  std::vector<double> lateral;  ///< model free-direction stretch [-] at the test's controls
  double r2 = 0.0;              ///< coefficient of determination of the stress: 1 - SS_res/SS_tot [-]
  double rms = 0.0, max = 0.0;  ///< RMS and max |P_model - P_data| / peak [-]
  double lateral_max = -1.0;    ///< max |lf_model/lf_data - 1| [-]; -1 when the test has no lateral data
  double lateral_rms = -1.0;    ///< RMS of lf_model/lf_data - 1 [-]; -1 likewise
  bool ok = true;               ///< false: the free stretch could not be solved at some point
};

struct HyperfoamModesFit {
  std::vector<material::HyperfoamTerm> terms;  ///< mu [MPa], alpha [-], nu [-] per term
  std::vector<HyperfoamTestFigures> tests;     ///< in campaign order
  double cost = 0.0;                           ///< objective at the answer (see top)
  StableStretch stable_stretch;                ///< stretch ranges over which Drucker stability was required
  std::string stability;                       ///< check_stability summary over the union of those ranges
  int starts = 0, polishes = 0, rejected_unstable = 0;
  std::vector<double> nu_screen;               ///< common nu values of the screen
  std::vector<std::string> warnings;
};

/// Model stress [MPa] and free stretch [-] of `terms` in `mode` at the controls (stretch, or gamma).
HyperfoamTestFigures evaluate_hyperfoam_test(const std::vector<material::HyperfoamTerm>& terms, const HyperfoamTest& test);

/// Default stable stretch ranges of a campaign, covering each mode's data and beyond: a mode with data
/// [0.8 min stretch, max(1.5, 1.2 max stretch)] of its tests (simple shear data count as planar, with their principal
/// stretches l and 1/l); a mode without data the narrowest of those ranges (largest min, smallest max).
StableStretch default_stable_stretch(const std::vector<HyperfoamTest>& tests);

/// "uniaxial [0.2, 1.5], equibiaxial [..], planar [..], volumetric [..]".
std::string describe(const StableStretch& ranges);

/// Drucker-stable over every mode's range (material/stability.hpp, run once over the union of the ranges).
bool stable_over(const material::Hyperelastic& model, const StableStretch& ranges);

/// The fit (see top). Throws std::runtime_error when no Drucker-stable candidate is found.
HyperfoamModesFit fit_hyperfoam_modes(const std::vector<HyperfoamTest>& tests, const HyperfoamFitSettings& settings);

}  // namespace cushion::calibration
