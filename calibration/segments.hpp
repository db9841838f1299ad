#pragma once
/// Quasi-static compression records: force-displacement -> nominal stress-strain (compression
/// positive), and detection of the loading, hold and unloading segments (paper section 2.2, Method E
/// of ISO 2439: load to the maximum, optional hold, unload).
#include <string>
#include <vector>

namespace cushion::calibration {

/// Block specimen of the campaign (paper Table 1: 80 x 80 x 80 mm, 65 kg/m^3).
struct Specimen {
  double length = 0.0;     ///< [mm]
  double width = 0.0;      ///< [mm]
  double thickness = 0.0;  ///< [mm], loading direction
  double density = 0.0;    ///< [t/mm^3] (65 kg/m^3 = 6.5e-11 t/mm^3)
  double area() const { return length * width; }  ///< [mm^2] loaded (reference) area
};

/// A uniaxial record in nominal measures, compression positive.
struct StressStrainRecord {
  std::string source;           ///< file name, for messages
  std::vector<double> time;     ///< [s], strictly increasing
  std::vector<double> strain;   ///< nominal strain displacement/thickness [-], compression positive
  std::vector<double> stress;   ///< nominal stress force/area [MPa], compression positive
  std::vector<int> line;        ///< file line of each sample (0 when synthetic), for messages
};

/// Nominal strain = displacement/thickness, nominal stress = force/area (reference area).
/// displacement [mm], force [N], compression positive. Throws InputError (naming `source` and the
/// line) if time is not strictly increasing.
StressStrainRecord to_nominal(const std::string& source, const std::vector<double>& time,
                              const std::vector<double>& displacement, const std::vector<double>& force,
                              const Specimen& specimen, const std::vector<int>& line = {});

/// Robust noise level (standard deviation) of a sampled signal from its second differences:
/// 1.4826 median|x[i+1] - 2x[i] + x[i-1]| / sqrt(6). Zero for a piecewise-linear clean signal.
double noise_level(const std::vector<double>& x);

struct SegmentOptions {
  double noise_factor = 6.0;        ///< monotonicity tolerance = noise_factor * noise level (at least 1e-6 eps_max)
  double hold_tolerance = 1e-4;     ///< strain within max(tol, hold_tolerance*eps_max) of eps_max is "at the peak"
  double lift_off_fraction = 1e-3;  ///< force ~ 0 means stress <= max(lift_off_fraction*peak, noise tolerance)
  double lift_off_strain = 0.05;    ///< force ~ 0 above this fraction of eps_max is a lift-off (warning);
                                    ///< below it the unloading simply ends there
  double min_unloading_drop = 0.1;  ///< unloading must return by at least this fraction of eps_max, unless:
  /// an unloading whose stress falls to at most this fraction of the peak stress by the record's end is a branch
  /// whatever its strain return: a platen that leaves a slowly recovering foam within a few percent of strain
  /// (a fast test of a foam with long relaxation times), recorded until the force was gone
  double unloaded_stress_fraction = 0.05;
  int min_points = 5;               ///< per branch
};

/// Sample indices (into the record) of the segments; ranges are inclusive.
struct Segments {
  std::size_t load_begin = 0, load_end = 0;      ///< loading: [load_begin, load_end], load_end = first peak sample
  std::size_t unload_begin = 0, unload_end = 0;  ///< unloading: [unload_begin, unload_end], unload_begin = last peak sample
  double peak_strain = 0.0;                      ///< [-]
  double peak_stress = 0.0;                      ///< [MPa] maximum stress of the record
  double hold_duration = 0.0;                    ///< [s] time between load_end and unload_begin
  bool lift_off = false;                         ///< unloading truncated where the force reached ~0
  double lift_off_strain = 0.0;                  ///< [-] strain at the truncation (lift_off only)
  double strain_noise = 0.0, stress_noise = 0.0; ///< estimated noise levels [-], [MPa]
  std::vector<std::string> warnings;             ///< e.g. the lift-off truncation
};

/// Detects loading (to the maximum strain), optional hold and unloading. Rejects with InputError
/// (naming the record's source and line): too few points, no unloading branch (the strain returns by less than
/// min_unloading_drop of the peak while the stress stays above unloaded_stress_fraction of its peak), non-monotonic
/// loading or unloading beyond the noise tolerance. An unloading branch whose force reaches ~0 before the
/// strain returns to 0 (the foam lifted off the platen) is truncated there with a warning.
Segments detect_segments(const StressStrainRecord& record, const SegmentOptions& options = {});

/// Linear interpolation of y(x) at xq for increasing x (clamped at the ends).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq);

/// A branch of a load/unload curve as a table with x strictly increasing (for interpolate).
struct MonotoneBranch {
  std::vector<double> x, y;
};
/// Samples [a, b] of (x, y) keeping the monotone part, the rest (noise, a hold) left out: loading, each x above all
/// before it; unloading, each x below all before it, returned in reverse (x increasing).
MonotoneBranch monotone_branch(const std::vector<double>& x, const std::vector<double>& y, std::size_t a, std::size_t b,
                               bool loading);

}  // namespace cushion::calibration
