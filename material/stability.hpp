#pragma once
/// Drucker stability check in the ABAQUS sense: d(tau):d(eps_log) > 0, i.e. the tangent of the
/// Kirchhoff stress with respect to the logarithmic strain is positive definite, checked along the
/// uniaxial, equibiaxial, planar and volumetric deformation modes over a range of nominal strain.
///
/// Criterion used (isotropic models, principal frame, eps_a = ln l_a): the quadratic form
///   d(tau):d(eps) = sum_ab M_ab d(eps_a) d(eps_b) + sum_{a<b} 2 K_ab d(eps_ab)^2,
///   M_ab = d(tau_a)/d(eps_b),  K_ab = (tau_a - tau_b)/(eps_a - eps_b) (limit at equal stretches),
/// is positive definite iff M is positive definite and every K_ab > 0. Both are computed from the
/// material tangent dS/dE by push-forward at F = diag(l), so any Hyperelastic works:
///   M_ab = 2 tau_a delta_ab + l_a^2 l_b^2 D_aabb,
///   K_ab = (2 l_a^2 l_b^2 D_abab + tau_a + tau_b) tanh(d)/d,  d = eps_a - eps_b  (tanh(d)/d -> 1),
/// the latter from l_a^2 l_b^2 D_abab = (tau_a l_b^2 - tau_b l_a^2)/(l_a^2 - l_b^2).
#include <optional>
#include <string>
#include <vector>

#include "material/hyperelastic.hpp"

namespace cushion::material {

enum class StabilityMode { uniaxial, equibiaxial, planar, volumetric };
std::string to_string(StabilityMode mode);

struct StabilityModeResult {
  StabilityMode mode;
  /// First nominal strain (stretch - 1) in compression (searching from 0 towards min_strain) and in
  /// tension (from 0 towards max_strain) at which the material is unstable; empty when stable.
  std::optional<double> first_unstable_compression;
  std::optional<double> first_unstable_tension;
};

struct StabilityReport {
  std::vector<StabilityModeResult> modes;
  double min_strain = -0.9;  ///< nominal strain range that was checked [-]
  double max_strain = 10.0;
  bool stable() const;
  std::string summary() const;  ///< one line per mode, e.g. "uniaxial: stable over [-0.9, 10]"
};

/// Log-strain tangent of the Kirchhoff stress at F = diag(l) [MPa], principal frame: entries (0..2, 0..2)
/// hold M_ab = dtau_a/d ln l_b, diagonal entries 3, 4, 5 hold K_12, K_23, K_13 (see above), the rest
/// is zero. NaN entries when the model fails at that stretch.
Mat6 kirchhoff_log_tangent(const Hyperelastic& model, const Vec3& l);

/// Checks stability over nominal strain [min_strain, max_strain] (defaults as ABAQUS: -0.9 .. 10)
/// in `steps` steps per side (stretch l = 1 + strain on the loading axes; volumetric: all three axes).
/// For a mode the lateral stretches follow the zero-lateral-stress condition of that mode, solved
/// numerically by Newton in ln l with continuation along the path, so it works for any Hyperelastic;
/// a state where the model fails or the lateral condition has no solution counts as unstable.
StabilityReport check_stability(const Hyperelastic& model, double min_strain = -0.9, double max_strain = 10.0,
                                int steps = 400);

}  // namespace cushion::material
