#pragma once
/// `cushion compare`: a material model against EVERY test of a campaign (calibration and validation),
/// with the TIME-DOMAIN forward model of each test protocol (calibration::run_quasi_static and
/// run_dynamic of lab.hpp: platen control, preload ramp, sines, sine-fit measurement), and error
/// figures that locate the failure, next to the measurement noise estimated from the data itself.
///
/// Quasi-static test: the record's protocol (rate, peak strain, hold) after the campaign's preflex cycles and
/// rest (protocol keys; default: none, a virgin relaxed specimen), with a platen that only pushes when the test's
/// lift_off is true (default), at min(record rate, quasi_static_steps / ramp time) steps per second,
/// interpolated to the record's samples. Regions: loading, unloading, low/mid/high thirds of the peak strain
/// (both branches), and the hysteresis area (loop integral of stress d strain).
/// Dynamic test: the whole protocol as the campaign describes it, by THE dynamic forward model
/// (lab.hpp run_dynamic, also the virtual lab's): preflex and rest, preload ramp at preload_rate_mm_min
/// (default CompareOptions::preload_rate_mm_min), dwell_before_sweep_s, then at each frequency the test's
/// `cycles` (default 20) sines, |E*| and phase fitted on the last `fit_cycles` (default 10) run at
/// `dynamic_steps_per_cycle` steps a cycle (the cycles before them at `dynamic_transient_steps_per_cycle`),
/// amplitude read as the test's amplitude_convention (default peak-to-peak, paper 2.3). compare and diagnose run
/// the same schedule, so they report the same figures for the same material and campaign. Regions: low/mid/high
/// thirds of the frequency list, each for |E*| [kPa] and phase [deg].
///
/// Noise estimates (data only, never the model):
///   quasi-static: a noise that depends on the reading, sigma^2 = A stress^2 + B, fitted to the fifth
///     differences on the loading, hold and unloading branches (compare_metrics.hpp reading_noise): the noise
///     at each sample, so each region is judged against the noise at its own stress, the hold included;
///   dynamic: scatter of |E*| and of the phase about a smooth least-squares polynomial in log f
///     (cubic from 8 frequencies, quadratic from 5, else none), a noise PER FREQUENCY: the force channel's
///     percent of reading and floor, the floor weighing 1/(strain amplitude) of the test's excitation (constant
///     acceleration: the displacement falls as 1/f^2, so the floor dominates at high frequency;
///     compare_metrics.hpp spectrum_noise). A dynamic region's error/noise is the RMS of the error in units of
///     the noise at each frequency.
/// NRMSE: quasi-static RMS / peak measured stress; |E*|: RMS / mean measured |E*|; phase: RMS / 90 deg.
/// Units: internal mm, N, s, MPa; reported stresses/moduli in kPa, phases in degrees, strains nominal
/// compression positive. The error and noise helpers are shared with the structure level (compare_metrics.hpp).
/// Structure-level tests (kinds "indentation" and "dynamic_stiffness", compare_structure.hpp) are reported
/// as TestCompare too, in N, mm, N/mm and degrees.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/compare_metrics.hpp"
#include "material/material.hpp"

namespace cushion::calibration {

/// The most time steps per sine cycle the command lines accept (--steps-per-cycle, --transient-steps-per-cycle).
inline constexpr int max_steps_per_cycle = 1000;

struct CompareOptions {
  int quasi_static_steps = 300;     ///< model steps per loading ramp at most (record rate if lower)
  int dynamic_steps_per_cycle = 64;  ///< model time steps per sine cycle (cycles per frequency: the campaign's)
  /// Model time steps per cycle of the cycles before the fitted ones (they only set the state the fitted cycles start
  /// from): 32 instead of 64 changed benchmark campaigns' |E*| and phase by at most 0.042 of their noise and a
  /// diagnosis' time by a factor 0.895 (median; the sweeps are about three quarters of a model run; physics.md 9.6).
  int dynamic_transient_steps_per_cycle = 32;
  double preload_rate_mm_min = 30.0;  ///< dynamic preload ramp (paper 2.3) of tests that give none
  double noise_level_ratio = 1.5;   ///< error/noise at or below this: "at the noise level"
  /// Also run each dynamic test at half the steps per cycle (fitted and transient cycles both halved) and report
  /// how far its |E*| and phase move (TestCompare::step_error): the time-discretisation error of the sweep at the
  /// model's step, where it is first order in the step (the dashpot effects' secant rate; docs/physics.md 9.38, 9.39).
  /// About 1.5x the dynamic tests' cost.
  bool step_check = false;
  /// A step_error above this many noise units (the step alone as large as the noise) is reported as a warning naming
  /// the test and the finer step.
  double step_error_warning = 1.0;
};

/// Data-only noise estimates of one test.
struct TestNoise {
  double stress = 0.0;   ///< quasi-static: RMS stress noise over the record [MPa]; indentation: force noise [N]
  std::vector<double> stress_local;  ///< quasi-static: local noise per record sample [MPa] (reading_noise)
  double modulus = 0.0;  ///< dynamic: |E*| noise [MPa]; dynamic_stiffness: |K*| noise [N/mm] (RMS over the frequencies)
  double phase = 0.0;    ///< dynamic, dynamic_stiffness: phase noise [deg] (RMS over the frequencies)
  std::vector<double> modulus_local, phase_local;  ///< dynamic, dynamic_stiffness: noise at each frequency [MPa or N/mm], [deg]
  bool known = false;    ///< estimate available (enough samples)
  /// The spectrum noise of a dynamic or dynamic_stiffness test (compare_metrics.hpp), and back.
  SpectrumNoise spectrum() const { return {modulus, phase, modulus_local, phase_local, known}; }
  /// The noise a quasi-static residual is divided by: the local noise `local`, but at least half the test's RMS noise
  /// (weights at most 4x the mean; the true noise of the lowest readings is tiny, and a fit would otherwise be steered
  /// by the model-form error there) [MPa].
  double stress_weighting(double local) const { return std::max(local, 0.5 * stress); }
  static TestNoise of(const SpectrumNoise& s);
};

struct TestCompare {
  std::string name, kind, use;  ///< kind "quasi_static" | "dynamic" | "indentation" | "dynamic_stiffness"; use "calibration" | "validation"
  double rate_mm_min = 0.0;     ///< quasi-static
  double preload = 0.0;         ///< dynamic: nominal preload [-]
  TestNoise noise;
  std::vector<RegionError> regions;  ///< "all" first
  /// Quasi-static curves: x = strain [-], measured/model stress [MPa] at the record's samples from the
  /// start of loading; dynamic: x = frequency [Hz], measured/model |E*| [MPa] and phase [deg];
  /// indentation: x = indentation [mm], force [N]; dynamic_stiffness: x = frequency [Hz], |K*| [N/mm], phase [deg].
  std::vector<double> x, measured, model, measured_phase, model_phase;
  std::vector<double> noise_local;    ///< quasi-static: local noise at each x [MPa] (indentation: [N])
  std::size_t unload_begin = 0;       ///< quasi-static, indentation: index in x where unloading starts
  double hysteresis_measured = 0.0, hysteresis_model = 0.0;  ///< loop area [MPa] (quasi-static), [N mm] (indentation)
  std::string failure;                ///< the model run failed (message); regions empty then
  /// Dynamic test with CompareOptions::step_check: RMS change of the model's |E*| and phase between the run at
  /// `steps_per_cycle` and at half of it, in noise units at each frequency, |E*| and phase combined as in
  /// noise_ratio [-]. For a scheme first order in the step this is about the error of the model's sweep at its own
  /// step (docs/physics.md 9.39); < 0: not computed.
  double step_error = -1.0;
  int steps_per_cycle = 0;  ///< dynamic: the model's time steps per fitted sine cycle
  /// RMS error over the whole test in noise units (dynamic: |E*| and phase combined) [-]; 0 if unknown.
  double noise_ratio() const;
  /// A load/unload curve (quasi_static, indentation) rather than a spectrum (dynamic, dynamic_stiffness).
  bool is_curve() const { return kind == "quasi_static" || kind == "indentation"; }
  const RegionError* region(const std::string& name) const;
};

struct CompareResult {
  std::vector<TestCompare> tests;  ///< quasi-static tests first, then dynamic, in campaign order
  std::vector<std::string> warnings;
  double seconds = 0.0;
  /// Every test with a known noise within options.noise_level_ratio of it.
  bool at_noise_level(double ratio) const;
};

/// Data-only noise of every test (same order as CompareResult::tests).
std::vector<TestNoise> estimate_noise(const Campaign& campaign);

/// Model vs every test. `noise`: from estimate_noise (computed when empty). A test whose model run throws
/// is reported with `failure` set; the others are still compared.
CompareResult compare_campaign(const material::Material& model, const Campaign& campaign, const CompareOptions& options = {},
                               const std::vector<TestNoise>& noise = {});

/// CompareOptions::step_check on a comparison made already: each dynamic test of `result` (compared with `model` at
/// o's steps, known noise, no failure) run again at half the steps per cycle, its TestCompare::step_error filled
/// (compare_campaign does this with step_check; diagnose on the model it names, whose comparison it has).
void add_step_errors(const material::Material& model, const Campaign& campaign, const CompareOptions& o,
                     CompareResult& result);

/// The warnings of CompareOptions::step_check (compare_campaign adds them): each dynamic test whose step_error
/// exceeds o.step_error_warning, with the finer step that halves it, and each whose run at half the steps failed.
std::vector<std::string> step_warnings(const CompareResult& result, const CompareOptions& o);

/// Warnings when the material and the campaign do not describe the same specimen (density of the material
/// file vs the campaign's specimen, more than 5% apart), empty when they agree or the material gives none.
std::vector<std::string> specimen_warnings(double material_density, const Campaign& campaign);

/// What the campaign's tests cannot tell apart, in words (empty when it has several rates and preloads):
/// a single material-level test; one quasi-static rate (rate-dependent hysteresis, viscous or pneumatic, vs
/// rate-independent, friction or Mullins); one dynamic preload (preload-dependent moduli); one indentation
/// test (the same for the structure's hysteresis).
std::vector<std::string> coverage_warnings(const Campaign& campaign);

/// Noise-normalised residuals for least squares (diagnose): quasi-static (model - measured)/sigma at up to
/// `quasi_static_points` evenly spread samples per test, sigma the local noise but at least half the test's RMS noise
/// (weights at most 4x the mean: at the lowest readings the true noise is tiny and model-form error would steer the
/// fit); dynamic (|E*| error)/sigma_E and (phase error)/sigma_phase
/// per frequency. Tests without a noise estimate or with a failed run contribute nothing (the latter: huge values).
std::vector<double> normalised_residuals(const CompareResult& result, int quasi_static_points = 100);

}  // namespace cushion::calibration
