#pragma once
/// Error and noise figures shared by every `cushion compare` test kind (material level: compare.hpp;
/// structure level: compare_structure.hpp). Pure functions of sampled curves; the caller picks the
/// units: values are multiplied by `factor` into the reported physical unit (e.g. 1000: MPa -> kPa).
///
/// Curves (load/unload records: stress vs strain, force vs indentation): regions all, loading,
/// unloading, low/mid/high thirds of the peak x (both branches), and the hysteresis (loop) area.
/// Spectra (modulus or stiffness and phase vs frequency): regions all and low/mid/high thirds of the
/// frequency list, each for the amplitude and for the phase.
/// Noise estimates use the data only, never the model:
///   curves: fifth differences on each smooth branch (loading, hold, unloading; a high-pass that removes any
///     quartic trend) fitted by a noise that depends on the reading, sigma^2 = A y^2 + B (reading_noise):
///     each sample, and so each region, is judged against the noise at its own reading;
///   spectra: scatter about a least-squares polynomial in log f (cubic from 8 frequencies, quadratic
///     from 5, else unknown). Without the excitation amplitude, one sigma = sqrt(SSR / (n - p)) for every
///     frequency. With it (a dynamic test at constant acceleration, whose displacement falls as 1/f^2), a noise
///     per frequency from the force channel's two parts, a percent of the oscillating force and a floor
///     (docs/physics.md 9): amplitude sigma_i^2 = A a_i^2 + B x_i^2, phase sigma_i^2 = C + D (x_i/a_i)^2, x_i the
///     inverse excitation amplitude; A..D >= 0 fitted to the squared residuals about the polynomial, which is
///     refitted with weights 1/sigma_i^2 (iterated).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace cushion::calibration {

/// Error of one region of one test, in the physical unit named by `unit` (kPa, N, N/mm, deg; the
/// hysteresis area in kPa = kJ/m^3 or N mm = mJ).
struct RegionError {
  std::string region;        ///< e.g. "loading", "low_strain", "band_high_modulus", "hysteresis_area"
  std::string unit;          ///< "kPa", "N", "N/mm", "N mm" or "deg"
  double rms = 0.0;          ///< RMS(model - measured) [unit]; hysteresis_area: |model - measured|
  double bias = 0.0;         ///< mean(model - measured) [unit]
  double nrmse = 0.0;        ///< rms / scale [-] (scale: see the caller's documentation)
  double noise = 0.0;        ///< estimated noise standard deviation [unit] (0: unknown)
  std::size_t points = 0;
  /// RMS of the error in units of the noise AT EACH POINT [-] (0: not computed; spectra with a per-frequency noise,
  /// whose noise spans decades over a sweep, so that rms / noise would hide a misfit where the noise is small).
  double normalised_rms = 0.0;
  /// Error in noise units [-]: normalised_rms when computed, else rms / noise.
  double ratio() const { return normalised_rms > 0.0 ? normalised_rms : noise > 0.0 ? rms / noise : 0.0; }
};

/// Robust third-difference noise of a smooth sampled signal: 1.4826 median|d3| / sqrt(20) (0 for < 8 samples).
double third_difference_noise(const std::vector<double>& y);

/// Residual standard deviation of y about a least-squares polynomial of `degree` in x: sqrt(SSR/(n - degree - 1)).
double polynomial_scatter(const std::vector<double>& x, const std::vector<double>& y, int degree);

/// Noise standard deviation of each sample of a record `y` [unit of y] whose noise depends on the reading:
/// sigma(y)^2 = A y^2 + B (a load cell's "percent of reading" plus a floor; A, B >= 0; docs/physics.md 9).
/// A and B are fitted to the squared fifth differences d_k = sum_j c_j y[k+j], c = (-1, 5, -10, 10, -5, 1), inside
/// each branch [first, last] (inclusive sample indices: the smooth pieces of the record, e.g. loading, hold and
/// unloading; no difference spans a corner), whose expectation is sum_j c_j^2 sigma^2(y[k+j]), by least squares
/// weighted with the inverse variance of d_k^2 (iterated) and with differences beyond 4 standard deviations left
/// out (a corner, a fast relaxation: signal, not noise). Every sample gets sigma(y_i), those outside the branches
/// too, and at least 10 % of the record's RMS noise (a relative-only fit gives no zero noise at zero force); empty
/// when the branches hold fewer than 8 differences.
std::vector<double> reading_noise(const std::vector<double>& y,
                                  const std::vector<std::pair<std::size_t, std::size_t>>& branches);

/// RMS of the local noise over all samples (0 for an empty vector).
double rms_of(const std::vector<double>& v);

/// Figures of region `name` over the samples `index`: rms, bias of (model - measured) x factor, nrmse = rms /
/// (scale x factor), noise = `noise` x factor, or the RMS of `local` over `index` x factor when `local` is given;
/// with `local` and `normalised`, also normalised_rms = RMS((model - measured)/local) over `index`.
RegionError region_error(const std::string& name, const std::string& unit, const std::vector<double>& model,
                         const std::vector<double>& measured, const std::vector<std::size_t>& index, double scale,
                         double noise, double factor, const std::vector<double>* local = nullptr,
                         bool normalised = false);

/// Loop area of a load/unload curve: trapezoid integral of y dx over the samples in order (loading minus
/// unloading) [unit of y x unit of x].
double loop_area(const std::vector<double>& x, const std::vector<double>& y);

/// A load/unload curve compared sample by sample: x increasing to its peak then decreasing (unloading
/// from index unload_begin), measured and model y at the same x, local noise of the measurement (may be empty).
struct CurveSamples {
  const std::vector<double>& x;
  const std::vector<double>& measured;
  const std::vector<double>& model;
  const std::vector<double>& local_noise;
  std::size_t unload_begin = 0;
  double x_peak = 0.0;  ///< peak x for the thirds [unit of x]
  double y_peak = 0.0;  ///< NRMSE scale: peak measured y [unit of y]
};

/// Regions of a curve: all (first), loading, unloading, low_/mid_/high_<x_name> (thirds of x_peak), and
/// hysteresis_area (|model loop - measured loop| x factor, unit `area_unit`, noise sigma sqrt(sum dx^2 (local/sigma)^2)
/// with sigma = `noise` the RMS noise, nrmse relative to the measured loop).
std::vector<RegionError> curve_regions(const CurveSamples& c, const std::string& x_name, const std::string& unit,
                                       const std::string& area_unit, double noise, double factor);

/// Amplitude and phase noise of a spectrum (scatter about a polynomial in log f; see the file comment), with
/// floors 1e-6 x mean amplitude and 1e-6 deg (floating-point scatter of noise-free data). known = false below 5
/// frequencies.
struct SpectrumNoise {
  double amplitude = 0.0;  ///< RMS over the frequencies of amplitude_local [unit of the amplitude]
  double phase = 0.0;      ///< RMS over the frequencies of phase_local [deg]
  std::vector<double> amplitude_local, phase_local;  ///< noise at each frequency (same order; empty when unknown)
  bool known = false;
};
/// `inverse_excitation`: a number proportional to 1 / (excitation amplitude) at each frequency (any scale, e.g.
/// 1 / strain amplitude); empty: the same noise at every frequency. A per-frequency noise is floored at 10 % of the
/// RMS noise (two variance parts fitted on n - p <= 6 residual degrees of freedom cannot resolve less).
SpectrumNoise spectrum_noise(const std::vector<double>& frequency, const std::vector<double>& amplitude,
                             const std::vector<double>& phase_deg, const std::vector<double>& inverse_excitation = {});

/// Regions of a spectrum: all_<a>, all_phase, then band_low/mid/high_<a> and _phase (thirds of the frequency
/// list), where <a> = `amplitude_name` (e.g. "modulus", "stiffness"). Amplitude NRMSE: RMS / mean measured
/// amplitude; phase NRMSE: RMS / 90 deg. Amplitudes x factor into `unit`.
std::vector<RegionError> spectrum_regions(const std::vector<double>& measured, const std::vector<double>& model,
                                          const std::vector<double>& measured_phase, const std::vector<double>& model_phase,
                                          const SpectrumNoise& noise, const std::string& amplitude_name,
                                          const std::string& unit, double factor);

}  // namespace cushion::calibration
