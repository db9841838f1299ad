#include "calibration/sine_fit.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

namespace cushion::calibration {

SineFit fit_sine(const std::vector<double>& t, const std::vector<double>& y, double frequency_Hz) {
  const std::size_t n = t.size();
  if (n != y.size() || n < 4) throw std::invalid_argument("fit_sine: need at least 4 (t, y) samples");
  if (!(frequency_Hz > 0.0)) throw std::invalid_argument("fit_sine: frequency must be positive");
  if ((t.back() - t.front()) * frequency_Hz < 1.0 - 1e-9)
    throw std::invalid_argument("fit_sine: samples must span at least one cycle");
  const double w = 2.0 * std::numbers::pi * frequency_Hz;
  const double t0 = 0.5 * (t.front() + t.back());  // centre the drift column for conditioning
  Eigen::MatrixXd A(n, 4);
  Eigen::VectorXd b(n);
  for (std::size_t k = 0; k < n; ++k) {
    A(k, 0) = std::sin(w * t[k]);
    A(k, 1) = std::cos(w * t[k]);
    A(k, 2) = 1.0;
    A(k, 3) = t[k] - t0;
    b(k) = y[k];
  }
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
  SineFit fit;
  fit.phasor = {x(0), x(1)};
  fit.drift = x(3);
  fit.offset = x(2) - x(3) * t0;
  fit.rms_residual = std::sqrt((A * x - b).squaredNorm() / static_cast<double>(n));
  return fit;
}

}  // namespace cushion::calibration
