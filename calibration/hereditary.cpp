#include "calibration/hereditary.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cushion::calibration {

namespace {
/// e^{-z} - 1 without cancellation for small |z|.
cplx exp_neg_minus_one(cplx z) {
  const double x = z.real(), y = z.imag(), s = std::sin(0.5 * y);
  return cplx(std::expm1(-x) * std::cos(y) - 2.0 * s * s, -std::exp(-x) * std::sin(y));
}
}  // namespace

cplx phi(cplx z) {
  if (std::abs(z) < 0.1) {
    // sum_{n>=0} (-z)^n / (n+1)!
    cplx term = 1.0, sum = 1.0;
    for (int n = 1; n < 14; ++n) {
      term *= -z / double(n + 1);
      sum += term;
    }
    return sum;
  }
  return -exp_neg_minus_one(z) / z;
}

cplx phi_prime(cplx z) {
  if (std::abs(z) < 0.1) {
    // d/dz sum (-1)^n z^n/(n+1)! = sum_{n>=1} (-1)^n n z^{n-1}/(n+1)!
    cplx sum = 0.0, zpow = 1.0;
    double fact = 2.0;  // (n+1)! for n = 1
    for (int n = 1; n < 15; ++n) {
      sum += (n % 2 ? -1.0 : 1.0) * double(n) * zpow / fact;
      zpow *= z;
      fact *= double(n + 2);
    }
    return sum;
  }
  return (exp_neg_minus_one(z) + z * std::exp(-z)) / (z * z);
}

HereditaryKernel hereditary_kernel(const std::vector<double>& time, const std::vector<double>& strain,
                                   cplx beta, const std::vector<double>& query_times) {
  const std::size_t n = time.size();
  if (n < 2 || strain.size() != n) throw std::invalid_argument("hereditary_kernel: need >= 2 samples of time and strain");
  // J and dJ/dbeta at the samples by the exact one-piece recursion.
  std::vector<cplx> Jk(n), dJk(n);
  Jk[0] = dJk[0] = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double h = time[k + 1] - time[k];
    if (!(h > 0.0)) throw std::invalid_argument("hereditary_kernel: time must be strictly increasing");
    const double de = strain[k + 1] - strain[k];
    const cplx z = beta * h, E = std::exp(-z);
    Jk[k + 1] = E * Jk[k] + de * phi(z);
    dJk[k + 1] = E * dJk[k] - h * E * Jk[k] + de * h * phi_prime(z);
  }
  HereditaryKernel out;
  out.J.resize(query_times.size());
  out.dJ_dbeta.resize(query_times.size());
  for (std::size_t q = 0; q < query_times.size(); ++q) {
    const double t = std::clamp(query_times[q], time.front(), time.back());
    std::size_t k = std::upper_bound(time.begin(), time.end(), t) - time.begin();
    k = k == 0 ? 0 : std::min(k - 1, n - 2);
    const double s = t - time[k];
    const double rate = (strain[k + 1] - strain[k]) / (time[k + 1] - time[k]);
    const cplx z = beta * s, E = std::exp(-z);
    out.J[q] = E * Jk[k] + rate * s * phi(z);
    out.dJ_dbeta[q] = E * dJk[k] - s * E * Jk[k] + rate * s * s * phi_prime(z);
  }
  return out;
}

std::vector<std::size_t> piecewise_linear_knots(const std::vector<double>& time, const std::vector<double>& strain,
                                                double tolerance) {
  const std::size_t n = time.size();
  std::vector<std::size_t> knots;
  if (n == 0) return knots;
  knots.push_back(0);
  std::size_t i = 0;
  while (i + 1 < n) {
    // Extend the chord from i to j while every sample between lies within the tolerance.
    std::size_t j = i + 1;
    while (j + 1 < n) {
      const std::size_t next = j + 1;
      const double slope = (strain[next] - strain[i]) / (time[next] - time[i]);
      bool fits = true;
      for (std::size_t k = i + 1; k < next && fits; ++k)
        fits = std::abs(strain[i] + slope * (time[k] - time[i]) - strain[k]) <= tolerance;
      if (!fits) break;
      j = next;
    }
    knots.push_back(j);
    i = j;
  }
  return knots;
}

std::vector<double> hereditary_stress(const std::vector<double>& time, const std::vector<double>& strain,
                                      const std::vector<HereditaryMode>& modes,
                                      const std::vector<double>& query_times) {
  std::vector<double> sigma(query_times.size(), 0.0);
  for (const auto& m : modes) {
    const auto K = hereditary_kernel(time, strain, m.beta, query_times);
    for (std::size_t q = 0; q < sigma.size(); ++q) sigma[q] -= (m.alpha * K.J[q]).real();
  }
  return sigma;
}

std::vector<HereditaryMode> paper_table2_modes() {
  const double kPa = 1e-3;  // MPa
  return {{cplx(-4.85e-3, 0.662) * kPa, cplx(5.25e-5, 3.45e-6)},
          {cplx(-3.01, 6.25) * kPa, cplx(1.32e-3, 2.01e-4)}};
}

std::vector<HereditaryMode> canonical(std::vector<HereditaryMode> modes) {
  for (auto& m : modes)
    if (m.beta.imag() < 0.0) {
      m.alpha = std::conj(m.alpha);
      m.beta = std::conj(m.beta);
    }
  std::sort(modes.begin(), modes.end(),
            [](const HereditaryMode& a, const HereditaryMode& b) { return a.beta.real() < b.beta.real(); });
  return modes;
}

}  // namespace cushion::calibration
