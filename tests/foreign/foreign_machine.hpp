#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: a 1D test machine written from the test standards' description, not from cushion's lab.
///
/// Specimen: a cube (80 mm), uniaxial compression with zero lateral contraction; nominal strain
/// e = u/H, nominal stress s = F/A, compression positive; force [N] = stress [kPa] x A [mm^2] x 1e-3.
/// Step of the foam (FoamSpecimen::step): s_e virgin -> softened by mullins forms -> Prony decorator (FEBio
/// form: on the second Piola-Kirchhoff stress S_e = s_e/l, s = l (S_e + sum h_j)) with weights
/// a_j = g_j/(1 - sum g) x the strain_dependent_prony factors at the increment's midpoint strain -> plus the
/// extra stresses (pneumatic, friction, stiffness_damping forms). Each test starts on a virgin, relaxed
/// specimen.
/// Quasi-static test: constant crosshead speed to max_strain, hold, back at the same speed; the platen
///   only pushes: when the (noise-free) force falls to zero on the way back the specimen has lifted off
///   and the record ends with the last sample before it. Sub-steps of at most 0.02 mm.
/// Dynamic test: preload ramp (preload_rate_mm_min, sub-steps of at most 0.02 mm), a dwell, then per
///   frequency `cycles` sines u = u_p + U sin(2 pi f t), U = a_pp/2/(2 pi f)^2, `steps_per_cycle` steps a
///   cycle, one continuous history over the frequencies; |E*| and phase from least-squares fits of
///   sine + cosine + offset + linear drift to the (noisy) force and the displacement over the last
///   `fit_cycles` cycles.
/// Noise (seeded Gaussian): quasi-static force sd = hypot(0.5 % x reading, 0.002 N) per sample; dynamic
///   force sd = hypot(0.5 % x the oscillating force amplitude, 0.002 N) per sample (a dynamic channel:
///   the static preload is not in its reading), or with `dynamic_relative_to_reading` 0.5 % of the whole
///   reading (preload included) per sample.
#include <complex>
#include <string>
#include <vector>

#include "foreign_effects.hpp"
#include "foreign_foam.hpp"
#include "foreign_random.hpp"

namespace foreign_bench {

struct Specimen {
  double length_mm = 80.0, width_mm = 80.0, thickness_mm = 80.0;
  double area_mm2() const { return length_mm * width_mm; }
  double force_N(double stress_kPa) const { return stress_kPa * area_mm2() * 1e-3; }
};

struct NoiseModel {
  double force_relative = 0.005;
  double force_floor_N = 0.002;
  bool dynamic_relative_to_reading = false;
  double force_sd_N(double reading_N) const { return std::hypot(force_relative * reading_N, force_floor_N); }
};

/// The foam of a truth, one test long: virgin and relaxed at e = 0 when built.
class FoamSpecimen {
 public:
  FoamSpecimen(const BaseFoam& foam, const std::vector<EffectSpec>& effects);
  /// Advances to strain_new over dt_s; returns the nominal compressive stress [kPa].
  double step(double strain_new, double dt_s);
  double strain() const { return strain_; }

 private:
  const BaseFoam& foam_;
  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<double> prony_pk2_kPa_;   ///< h_j on the second Piola-Kirchhoff stress
  double strain_ = 0.0, elastic_pk2_kPa_ = 0.0;
};

struct QuasiStaticProtocol {
  std::string name;
  double rate_mm_min = 120.0;
  double max_strain = 0.75;
  double hold_s = 2.0;
  double sample_hz = 10.0;
  std::string use = "validation";
};

struct DynamicProtocol {
  std::string name;
  double preload_strain = 0.25;
  double preload_rate_mm_min = 30.0;
  double dwell_s = 5.0;
  double acceleration_peak_to_peak_m_s2 = 0.25;
  std::vector<double> frequencies_Hz;
  int cycles = 20, fit_cycles = 10, steps_per_cycle = 64;
  /// Integration steps of the foam per sample of a sweep (along the sine). 1: one step a sample, whose secant rate
  /// lags the dashpots' stress by half a step, as cushion's 64-step model does (docs/physics.md 9.39); n > 1: that
  /// lag n times smaller, closer to a continuous specimen (the samples and the noise the same).
  int integration_substeps = 1;
  std::string use = "validation";
};

struct QuasiStaticRecord {
  std::vector<double> time_s, displacement_mm, force_N;
  bool lifted_off = false;   ///< the record ended before the crosshead came back
};

struct DynamicRecord {
  std::vector<double> frequency_Hz, dynamic_modulus_kPa, phase_deg;
  std::vector<double> force_amplitude_N;   ///< noise-free oscillating force amplitude
  std::vector<double> force_noise_sd_N;    ///< per-sample force noise (RMS over the fit window)
  int fit_samples = 0;
  /// Standard deviation of |E*| [kPa] and phase [deg] at frequency i from the force noise (least squares).
  double modulus_sd_kPa(std::size_t i) const;
  double phase_sd_deg(std::size_t i) const;
};

/// U = a_peak/(2 pi f)^2 with a_peak = a_pp/2 [mm].
double displacement_amplitude_mm(double acceleration_peak_to_peak_m_s2, double frequency_Hz);

struct SineFit {
  double sine = 0.0, cosine = 0.0, offset = 0.0, drift = 0.0;  ///< y ~ sine sin(wt) + cosine cos(wt) + offset + drift t
  /// Amplitude and phase as a phasor: A e^{i phi} for A sin(wt + phi).
  std::complex<double> phasor() const { return {sine, cosine}; }
};
SineFit fit_sine(const std::vector<double>& time_s, const std::vector<double>& y, double frequency_Hz);

/// Noise-free quasi-static test.
QuasiStaticRecord run_quasi_static(const BaseFoam& foam, const std::vector<EffectSpec>& effects,
                                   const Specimen& specimen, const QuasiStaticProtocol& protocol);
void add_quasi_static_noise(QuasiStaticRecord& record, const NoiseModel& noise, Random& random);

/// Dynamic test; noise-free when `random` is null.
DynamicRecord run_dynamic(const BaseFoam& foam, const std::vector<EffectSpec>& effects, const Specimen& specimen,
                          const DynamicProtocol& protocol, const NoiseModel& noise, Random* random);

}  // namespace foreign_bench
