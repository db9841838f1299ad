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
/// Samples the segments in order from t = 0, control = 0: ramps linear in time, holds constant, sines
/// control = c + amplitude sin(2 pi f t') (c: value where the sine starts, t' from its start). Default
/// steps: 100 per ramp or hold, 64 per sine cycle. Throws InputError naming the segment on durations,
/// frequencies or cycles <= 0, negative amplitudes or steps, or non-finite values.
History build_history(const std::vector<Segment>& segments, AxisControl axis_control = AxisControl::displacement);

/// Results at every sampled time.
struct PointResult {
  std::vector<double> time;          ///< [s]
  std::vector<double> control;       ///< the control value reached (differs from the input after lift-off)
  std::vector<Mat3> F;               ///< deformation gradient
  std::vector<Mat3> P;               ///< nominal (first Piola-Kirchhoff) stress [MPa]
  std::vector<Mat3> sigma;           ///< Cauchy stress [MPa]
  std::vector<bool> in_contact;      ///< platen control: whether the platen touches (always true otherwise)
  std::vector<std::string> warnings; ///< distinct messages of increments the material flagged `unreliable`
};

/// Runs the history from the virgin state (F = I at t[0]; a non-zero control[0] is reached with dt = 0).
/// Each increment integrates from the committed state and commits on success. uniaxial_free solves the
/// lateral stretches from S22 = S33 = 0 (equivalently P22 = P33 = 0) by Newton on dS/dE to 1e-12.
/// Platen control (uniaxial modes only): the foam is first let free on axis 1 too (S = 0 from the
/// committed state); if its free l1 is below the platen stretch 1 + control it is clear (P11 = 0,
/// in_contact false), else the platen stretch is imposed. Throws std::runtime_error with the time and
/// reason if the material fails or the lateral Newton does not converge; InputError for platen
/// control in a volumetric or shear mode or for time/control arrays of different lengths.
PointResult run_point(const Material& material, LoadMode mode, const History& history);

}  // namespace cushion::material
