// Sine fit used by the virtual lab to "measure" dynamic tests.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "calibration/sine_fit.hpp"

using cushion::calibration::fit_sine;

TEST(SineFit, RecoversPhasorOffsetAndDriftExactly) {
  const double f = 3.7, w = 2.0 * std::numbers::pi * f;
  const std::complex<double> Y{0.8, -0.35};
  std::vector<double> t, y;
  for (int k = 0; k <= 640; ++k) {
    const double tk = 10.0 + k / (64.0 * f);
    t.push_back(tk);
    y.push_back(Y.real() * std::sin(w * tk) + Y.imag() * std::cos(w * tk) + 2.5 - 0.04 * tk);
  }
  const auto fit = fit_sine(t, y, f);
  // Noise-free data of exactly the model's form: recovered to round-off (1e-12 absolute).
  EXPECT_NEAR(fit.phasor.real(), Y.real(), 1e-12);
  EXPECT_NEAR(fit.phasor.imag(), Y.imag(), 1e-12);
  EXPECT_NEAR(fit.offset, 2.5, 1e-10);
  EXPECT_NEAR(fit.drift, -0.04, 1e-12);
  EXPECT_LT(fit.rms_residual, 1e-12);
  // |Y| sin(w t + arg Y) form.
  EXPECT_NEAR(std::abs(fit.phasor) * std::sin(w * t[7] + std::arg(fit.phasor)) + 2.5 - 0.04 * t[7], y[7], 1e-10);
}

TEST(SineFit, RejectsTooShortRecords) {
  EXPECT_THROW(fit_sine({0.0, 0.1, 0.2}, {1.0, 2.0, 3.0}, 1.0), std::invalid_argument);
  EXPECT_THROW(fit_sine({0.0, 0.1, 0.2, 0.3, 0.4}, {1, 2, 3, 4, 5}, 1.0), std::invalid_argument);  // < 1 cycle
  EXPECT_THROW(fit_sine({0.0, 0.5, 1.0, 1.5}, {1, 2, 3, 4}, -1.0), std::invalid_argument);
}
