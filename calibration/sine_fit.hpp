#pragma once
/// Least-squares sine fit, as a test machine's software measures a dynamic test:
///   y(t) ~ a sin(2 pi f t) + b cos(2 pi f t) + c + d t
/// (offset and linear drift absorb slow relaxation). The complex phasor is Y = a + i b, so that
/// y - c - d t = Im(Y e^{i w t}) = |Y| sin(w t + arg Y): ratios of phasors are transfer functions
/// in the e^{+i w t} convention (phase > 0: the output leads).
#include <complex>
#include <vector>

namespace cushion::calibration {

struct SineFit {
  std::complex<double> phasor;  ///< a + i b: amplitude |.|, phase arg(.) relative to sin(2 pi f t) [rad]
  double offset = 0.0;          ///< c
  double drift = 0.0;           ///< d [unit of y per s]
  double rms_residual = 0.0;    ///< RMS of y minus the fit
};

/// Fits samples (t [s], y) at frequency f [Hz]; needs at least 4 samples spanning >= 1 cycle.
/// Throws std::invalid_argument otherwise.
SineFit fit_sine(const std::vector<double>& t, const std::vector<double>& y, double frequency_Hz);

}  // namespace cushion::calibration
