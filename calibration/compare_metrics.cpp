#include "calibration/compare_metrics.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace cushion::calibration {

namespace {

double median_abs(std::vector<double> v) {
  if (v.empty()) return 0.0;
  for (double& x : v) x = std::abs(x);
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

int scatter_degree(std::size_t n) { return n >= 8 ? 3 : n >= 5 ? 2 : -1; }

}  // namespace

double third_difference_noise(const std::vector<double>& y) {
  if (y.size() < 8) return 0.0;
  std::vector<double> d3;
  for (std::size_t i = 0; i + 3 < y.size(); ++i) d3.push_back(y[i + 3] - 3.0 * y[i + 2] + 3.0 * y[i + 1] - y[i]);
  return 1.4826 * median_abs(d3) / std::sqrt(20.0);
}

double polynomial_scatter(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  const int n = static_cast<int>(x.size());
  if (degree < 0 || n <= degree + 1) return 0.0;
  const double x0 = (x.front() + x.back()) / 2.0, h = std::max(1e-12, (x.back() - x.front()) / 2.0);
  Eigen::MatrixXd A(n, degree + 1);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double u = (x[i] - x0) / h;
    for (int k = 0; k <= degree; ++k) A(i, k) = std::pow(u, k);
    b(i) = y[i];
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  return std::sqrt((A * c - b).squaredNorm() / (n - degree - 1));
}

std::vector<double> local_branch_noise(const std::vector<double>& y,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& branches) {
  const std::size_t N = y.size();
  std::vector<double> local(N, -1.0);
  for (const auto& [a, b] : branches) {
    if (b >= N || b < a + 8) continue;
    std::vector<double> d3;
    for (std::size_t i = a; i + 3 <= b; ++i) d3.push_back(y[i + 3] - 3.0 * y[i + 2] + 3.0 * y[i + 1] - y[i]);
    const std::size_t m = d3.size(), w = 15;
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t lo = k > w ? k - w : 0, hi = std::min(m - 1, k + w);
      double s2 = 0.0;
      for (std::size_t q = lo; q <= hi; ++q) s2 += d3[q] * d3[q];
      const double sigma = std::sqrt(s2 / (hi - lo + 1) / 20.0);
      for (std::size_t q = a + k; q <= std::min(b, a + k + 3); ++q)
        local[q] = local[q] < 0.0 ? sigma : std::min(local[q], sigma);
    }
  }
  // Samples not covered (before loading, hold, after unloading) take the nearest covered value.
  double last = -1.0;
  for (std::size_t i = 0; i < N; ++i) (local[i] >= 0.0 ? last = local[i] : local[i] = last);
  last = -1.0;
  for (std::size_t i = N; i-- > 0;) (local[i] >= 0.0 ? last = local[i] : local[i] = last);
  if (N == 0 || local.front() < 0.0) return {};
  return local;
}

double rms_of(const std::vector<double>& v) {
  double s2 = 0.0;
  for (double x : v) s2 += x * x;
  return v.empty() ? 0.0 : std::sqrt(s2 / v.size());
}

RegionError region_error(const std::string& name, const std::string& unit, const std::vector<double>& model,
                         const std::vector<double>& measured, const std::vector<std::size_t>& index, double scale,
                         double noise, double factor, const std::vector<double>* local) {
  RegionError r{name, unit};
  if (local && !local->empty() && !index.empty()) {  // RMS of the local noise over the region
    double n2 = 0.0;
    for (std::size_t i : index) n2 += (*local)[i] * (*local)[i];
    noise = std::sqrt(n2 / index.size());
  }
  double s2 = 0.0, s1 = 0.0;
  for (std::size_t i : index) {
    const double e = (model[i] - measured[i]) * factor;
    s2 += e * e;
    s1 += e;
  }
  r.points = index.size();
  if (!index.empty()) {
    r.rms = std::sqrt(s2 / index.size());
    r.bias = s1 / index.size();
  }
  r.nrmse = scale > 0.0 ? r.rms / (scale * factor) : 0.0;
  r.noise = noise * factor;
  return r;
}

double loop_area(const std::vector<double>& x, const std::vector<double>& y) {
  double a = 0.0;
  for (std::size_t i = 1; i < x.size(); ++i) a += 0.5 * (y[i] + y[i - 1]) * (x[i] - x[i - 1]);
  return a;
}

std::vector<RegionError> curve_regions(const CurveSamples& c, const std::string& x_name, const std::string& unit,
                                       const std::string& area_unit, double noise, double factor) {
  std::vector<std::size_t> all, load, unload, low, mid, high;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    all.push_back(i);
    (i < c.unload_begin ? load : unload).push_back(i);
    const double u = c.x[i] / c.x_peak;
    (u < 1.0 / 3.0 ? low : u < 2.0 / 3.0 ? mid : high).push_back(i);
  }
  const std::vector<double>* L = c.local_noise.empty() ? nullptr : &c.local_noise;
  std::vector<RegionError> out;
  out.push_back(region_error("all", unit, c.model, c.measured, all, c.y_peak, noise, factor, L));
  out.push_back(region_error("loading", unit, c.model, c.measured, load, c.y_peak, noise, factor, L));
  out.push_back(region_error("unloading", unit, c.model, c.measured, unload, c.y_peak, noise, factor, L));
  out.push_back(region_error("low_" + x_name, unit, c.model, c.measured, low, c.y_peak, noise, factor, L));
  out.push_back(region_error("mid_" + x_name, unit, c.model, c.measured, mid, c.y_peak, noise, factor, L));
  out.push_back(region_error("high_" + x_name, unit, c.model, c.measured, high, c.y_peak, noise, factor, L));
  const double measured_loop = loop_area(c.x, c.measured), model_loop = loop_area(c.x, c.model);
  RegionError h{"hysteresis_area", area_unit};
  h.rms = std::abs(model_loop - measured_loop) * factor;
  h.bias = (model_loop - measured_loop) * factor;
  h.nrmse = std::abs(measured_loop) > 0.0 ? h.rms / (std::abs(measured_loop) * factor) : 0.0;
  // Noise of the trapezoid sum: sqrt(sum of (strain step x local noise)^2).
  double ds2 = 0.0;
  for (std::size_t i = 1; i < c.x.size(); ++i)
    ds2 += std::pow(c.x[i] - c.x[i - 1], 2) * (L && noise > 0.0 ? c.local_noise[i] * c.local_noise[i] / (noise * noise) : 1.0);
  h.noise = noise * std::sqrt(ds2) * factor;
  h.points = c.x.size();
  out.push_back(h);
  return out;
}

SpectrumNoise spectrum_noise(const std::vector<double>& frequency, const std::vector<double>& amplitude,
                             const std::vector<double>& phase_deg) {
  SpectrumNoise n;
  const int degree = scatter_degree(frequency.size());
  if (degree < 0) return n;
  std::vector<double> x;
  for (double f : frequency) x.push_back(std::log(f));
  n.amplitude = polynomial_scatter(x, amplitude, degree);
  n.phase = polynomial_scatter(x, phase_deg, degree);
  double mean = 0.0;
  for (double a : amplitude) mean += a / amplitude.size();
  n.amplitude = std::max(n.amplitude, 1e-6 * mean);
  n.phase = std::max(n.phase, 1e-6);
  n.known = true;
  return n;
}

std::vector<RegionError> spectrum_regions(const std::vector<double>& measured, const std::vector<double>& model,
                                          const std::vector<double>& measured_phase, const std::vector<double>& model_phase,
                                          const SpectrumNoise& noise, const std::string& amplitude_name,
                                          const std::string& unit, double factor) {
  const std::size_t n = measured.size();
  double mean = 0.0;
  for (double e : measured) mean += e / n;
  std::vector<std::size_t> all, band[3];
  for (std::size_t i = 0; i < n; ++i) {
    all.push_back(i);
    band[std::min<std::size_t>(2, 3 * i / n)].push_back(i);
  }
  const double ea = noise.known ? noise.amplitude : 0.0, ep = noise.known ? noise.phase : 0.0;
  std::vector<RegionError> out;
  out.push_back(region_error("all_" + amplitude_name, unit, model, measured, all, mean, ea, factor));
  out.push_back(region_error("all_phase", "deg", model_phase, measured_phase, all, 90.0, ep, 1.0));
  const char* names[3] = {"band_low", "band_mid", "band_high"};
  for (int b = 0; b < 3; ++b) {
    out.push_back(region_error(std::string(names[b]) + "_" + amplitude_name, unit, model, measured, band[b], mean, ea, factor));
    out.push_back(region_error(std::string(names[b]) + "_phase", "deg", model_phase, measured_phase, band[b], 90.0, ep, 1.0));
  }
  return out;
}

}  // namespace cushion::calibration
