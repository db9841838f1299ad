#pragma once
/// Drucker stability check in the ABAQUS sense: d(tau):d(eps_log) > 0, i.e. the tangent of the
/// Kirchhoff stress with respect to the logarithmic strain is positive definite, checked along the
/// uniaxial, equibiaxial, planar and volumetric deformation modes over a range of nominal strain.
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
  bool stable() const;
  std::string summary() const;  ///< one line per mode, e.g. "uniaxial: stable over [-0.9, 10]"
};

/// Checks stability over nominal strain [min_strain, max_strain] (defaults as ABAQUS: -0.9 .. 10)
/// in `steps` steps per side. For a mode the lateral stretches follow the zero-lateral-stress
/// condition of that mode, solved numerically, so it works for any Hyperelastic.
StabilityReport check_stability(const Hyperelastic& model, double min_strain = -0.9, double max_strain = 10.0,
                                int steps = 400);

}  // namespace cushion::material
