#pragma once
/// Material-point driver: runs a strain history at one point with any Material and returns stress
/// histories. The fast forward model of calibration and diagnosis. Mechanics sign convention:
/// tension positive (a compression test has negative strain and negative stress here; the test
/// files' compression-positive convention is converted by their readers).
#include <string>
#include <vector>

#include "material/material.hpp"

namespace cushion::material {

/// Kinematic mode of the point. Axis 1 (x) is the loading axis.
enum class LoadMode {
  uniaxial_free,         ///< F = diag(l, l2, l3), lateral stretches solved from P22 = P33 = 0
  uniaxial_constrained,  ///< F = diag(l, 1, 1) (laterally confined)
  volumetric,            ///< F = l I
  simple_shear           ///< F = I + gamma e1 (x) e2; control is gamma
};
std::string to_string(LoadMode mode);
LoadMode load_mode_from_string(const std::string& name);  ///< throws InputError naming the value

/// How axis 1 is driven in an increment.
enum class AxisControl {
  displacement,  ///< the control value is imposed
  platen         ///< a platen that only pushes: the control is the platen position; where the foam
                 ///< recovers more slowly than the platen retracts it loses contact (P11 = 0, lift-off)
};

/// A sampled history: control value (nominal strain l - 1, or gamma for simple shear) at times t.
struct History {
  std::vector<double> time;     ///< [s], strictly increasing, starts at 0
  std::vector<double> control;  ///< [-], control[0] is usually 0
  AxisControl axis_control = AxisControl::displacement;
};

/// Segments from which a History is built (the `cushion point` protocol language).
struct Segment {
  enum class Kind { ramp, hold, sine } kind = Kind::ramp;
  double target = 0.0;     ///< ramp: control value at the end
  double duration = 0.0;   ///< ramp, hold: [s]
  double amplitude = 0.0;  ///< sine: control amplitude about the current value
  double frequency = 0.0;  ///< sine: [Hz]
  double cycles = 0.0;     ///< sine: number of cycles
  int steps = 0;           ///< increments in the segment (0: a sensible default)
};
History build_history(const std::vector<Segment>& segments, AxisControl axis_control = AxisControl::displacement);

/// Results at every sampled time.
struct PointResult {
  std::vector<double> time;          ///< [s]
  std::vector<double> control;       ///< the control value reached (differs from the input after lift-off)
  std::vector<Mat3> F;               ///< deformation gradient
  std::vector<Mat3> P;               ///< nominal (first Piola-Kirchhoff) stress [MPa]
  std::vector<Mat3> sigma;           ///< Cauchy stress [MPa]
  std::vector<bool> in_contact;      ///< platen control: whether the platen touches
};

/// Runs the history; throws std::runtime_error with time and reason if the material fails.
PointResult run_point(const Material& material, LoadMode mode, const History& history);

}  // namespace cushion::material
