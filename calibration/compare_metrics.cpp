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

namespace {

/// Residuals y - p(x) of the least-squares polynomial of `degree` in x weighted by w (x scaled to [-1, 1]).
std::vector<double> polynomial_residuals(const std::vector<double>& x, const std::vector<double>& y, int degree,
                                         const std::vector<double>& w) {
  const int n = static_cast<int>(x.size());
  const double x0 = (x.front() + x.back()) / 2.0, h = std::max(1e-12, (x.back() - x.front()) / 2.0);
  Eigen::MatrixXd A(n, degree + 1);
  Eigen::VectorXd b(n), sw(n);
  for (int i = 0; i < n; ++i) {
    const double u = (x[i] - x0) / h;
    sw(i) = std::sqrt(w[i]);
    for (int k = 0; k <= degree; ++k) A(i, k) = std::pow(u, k);
    b(i) = y[i];
  }
  const Eigen::VectorXd c = (sw.asDiagonal() * A).colPivHouseholderQr().solve(sw.asDiagonal() * b);
  const Eigen::VectorXd r = b - A * c;
  return {r.data(), r.data() + n};
}

}  // namespace

double polynomial_scatter(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  const int n = static_cast<int>(x.size());
  if (degree < 0 || n <= degree + 1) return 0.0;
  double ssr = 0.0;
  for (double r : polynomial_residuals(x, y, degree, std::vector<double>(x.size(), 1.0))) ssr += r * r;
  return std::sqrt(ssr / (n - degree - 1));
}

namespace {

/// Differences of reading_noise: order 5, d_k = sum_j c_j y[k+j], c = (-1, 5, -10, 10, -5, 1) (binomial, alternating),
/// sum c_j^2 = 252; a polynomial of degree 4 gives d = 0, a smooth curve h^5 y^(5).
constexpr int kOrder = 5;
constexpr double kCoefficient[kOrder + 1] = {-1.0, 5.0, -10.0, 10.0, -5.0, 1.0};
constexpr double kSumSquares = 252.0;

/// Noise variance model sigma^2 = A y^2 + B of reading_noise.
struct ReadingVariance {
  double A = 0.0, B = 0.0;
  double at(double x) const { return A * x + kSumSquares * B; }  ///< E[d^2] for x = sum c_j^2 y_j^2
};

/// Two non-negative variance parts: weighted least squares of r2_k ~ A u_k + B v_k with A, B >= 0 over the
/// samples `use` marks, weights w (the better one-part fit when the two-part one has a negative part).
std::pair<double, double> two_part_variance(const std::vector<double>& r2, const std::vector<double>& u,
                                            const std::vector<double>& v, const std::vector<double>& w,
                                            const std::vector<char>& use) {
  double suu = 0.0, svv = 0.0, suv = 0.0, sur = 0.0, svr = 0.0, srr = 0.0;
  for (std::size_t k = 0; k < r2.size(); ++k) {
    if (!use[k]) continue;
    suu += w[k] * u[k] * u[k], svv += w[k] * v[k] * v[k], suv += w[k] * u[k] * v[k];
    sur += w[k] * u[k] * r2[k], svr += w[k] * v[k] * r2[k], srr += w[k] * r2[k] * r2[k];
  }
  const double det = suu * svv - suv * suv;
  if (det > 1e-12 * suu * svv) {
    const double A = (svv * sur - suv * svr) / det, B = (suu * svr - suv * sur) / det;
    if (A >= 0.0 && B >= 0.0) return {A, B};
  }
  const double A = suu > 0.0 ? std::max(0.0, sur / suu) : 0.0, B = svv > 0.0 ? std::max(0.0, svr / svv) : 0.0;
  const double cost_A = srr - A * sur, cost_B = srr - B * svr;  // weighted SSR of each one-part fit
  return cost_A < cost_B ? std::pair{A, 0.0} : std::pair{0.0, B};
}

/// Weighted least squares of d2 ~ A x + 252 B with A, B >= 0 over the samples `use` marks, weights w.
ReadingVariance weighted_variance_fit(const std::vector<double>& d2, const std::vector<double>& x,
                                      const std::vector<double>& w, const std::vector<char>& use) {
  const auto [A, B] = two_part_variance(d2, x, std::vector<double>(d2.size(), kSumSquares), w, use);
  return {A, B};
}

}  // namespace

std::vector<double> reading_noise(const std::vector<double>& y,
                                  const std::vector<std::pair<std::size_t, std::size_t>>& branches) {
  std::vector<double> d2, x;  // squared differences, sum c_j^2 y_j^2
  for (const auto& [a, b] : branches)
    for (std::size_t i = a; i + kOrder <= b && b < y.size(); ++i) {
      double d = 0.0, s = 0.0;
      for (int j = 0; j <= kOrder; ++j) {
        d += kCoefficient[j] * y[i + j];
        s += kCoefficient[j] * kCoefficient[j] * y[i + j] * y[i + j];
      }
      d2.push_back(d * d);
      x.push_back(s);
    }
  if (d2.size() < 8) return {};
  // Start: a floor from the median (median of chi2_1 = 0.4549), then iterate weights 1/E[d^2]^2 and the 4-sigma
  // rejection until the model settles.
  std::vector<double> sorted = d2;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  ReadingVariance m{0.0, sorted[sorted.size() / 2] / 0.4549 / kSumSquares};
  std::vector<double> w(d2.size());
  std::vector<char> use(d2.size());
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double floor = 1e-30 + 1e-12 * m.at(*std::max_element(x.begin(), x.end()));
    for (std::size_t k = 0; k < d2.size(); ++k) {
      const double v = std::max(m.at(x[k]), floor);
      w[k] = 1.0 / (v * v);
      use[k] = d2[k] <= 16.0 * v;
    }
    const ReadingVariance next = weighted_variance_fit(d2, x, w, use);
    const bool settled = std::abs(next.A - m.A) <= 1e-6 * std::abs(m.A) + 1e-300 &&
                         std::abs(next.B - m.B) <= 1e-6 * std::abs(m.B) + 1e-300;
    m = next;
    if (settled) break;
  }
  std::vector<double> sigma;
  for (double v : y) sigma.push_back(std::sqrt(m.A * v * v + m.B));
  // A relative-only fit (B = 0) would give zero noise at zero force, and infinite normalised residuals there: no
  // sample is credited with less than 10 % of the record's RMS noise.
  const double lowest = 0.1 * rms_of(sigma);
  for (double& x : sigma) x = std::max(x, lowest);
  return sigma;
}

double rms_of(const std::vector<double>& v) {
  double s2 = 0.0;
  for (double x : v) s2 += x * x;
  return v.empty() ? 0.0 : std::sqrt(s2 / v.size());
}

RegionError region_error(const std::string& name, const std::string& unit, const std::vector<double>& model,
                         const std::vector<double>& measured, const std::vector<std::size_t>& index, double scale,
                         double noise, double factor, const std::vector<double>* local, bool normalised) {
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
  if (normalised && local && !index.empty()) {
    double z2 = 0.0;
    for (std::size_t i : index) z2 += std::pow((model[i] - measured[i]) / std::max((*local)[i], 1e-300), 2);
    r.normalised_rms = std::sqrt(z2 / index.size());
  }
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

namespace {

/// Noise at each frequency of one channel y whose variance is sigma_i^2 = A u_i + B v_i (A, B >= 0): the squared
/// residuals about the polynomial of `degree` in log f (weighted 1/sigma^2), scaled by n/(n - p) for the fitted
/// coefficients, fitted by two_part_variance with weights 1/sigma^4 (the variance of a squared residual), iterated.
std::vector<double> channel_noise(const std::vector<double>& logf, const std::vector<double>& y, int degree,
                                  const std::vector<double>& u, const std::vector<double>& v) {
  const std::size_t n = y.size();
  const double dof = static_cast<double>(n) / static_cast<double>(n - degree - 1);
  std::vector<double> var(n, 1.0), w(n), r2(n);
  const std::vector<char> use(n, 1);
  for (int iteration = 0; iteration < 30; ++iteration) {
    for (std::size_t i = 0; i < n; ++i) w[i] = 1.0 / var[i];
    const std::vector<double> r = polynomial_residuals(logf, y, degree, w);
    for (std::size_t i = 0; i < n; ++i) r2[i] = r[i] * r[i] * dof, w[i] = 1.0 / (var[i] * var[i]);
    const auto [A, B] = two_part_variance(r2, u, v, w, use);
    double change = 0.0, largest = 0.0;
    std::vector<double> next(n);
    for (std::size_t i = 0; i < n; ++i) next[i] = A * u[i] + B * v[i], largest = std::max(largest, next[i]);
    if (!(largest > 0.0)) return std::vector<double>(n, 0.0);  // noise-free data: the floors decide
    for (std::size_t i = 0; i < n; ++i) {
      next[i] = std::max(next[i], 1e-12 * largest);
      change = std::max(change, std::abs(next[i] - var[i]) / next[i]);
    }
    var = next;
    if (change < 1e-6) break;
  }
  std::vector<double> sigma;
  for (double x : var) sigma.push_back(std::sqrt(x));
  return sigma;
}

/// sigma floored at `least` and at 10 % of its RMS.
void floor_noise(std::vector<double>& sigma, double least) {
  const double lowest = std::max(least, 0.1 * rms_of(sigma));
  for (double& s : sigma) s = std::max(s, lowest);
}

}  // namespace

SpectrumNoise spectrum_noise(const std::vector<double>& frequency, const std::vector<double>& amplitude,
                             const std::vector<double>& phase_deg, const std::vector<double>& inverse_excitation) {
  SpectrumNoise n;
  const int degree = scatter_degree(frequency.size());
  if (degree < 0) return n;
  const std::size_t m = frequency.size();
  std::vector<double> x;
  for (double f : frequency) x.push_back(std::log(f));
  double mean = 0.0;
  for (double a : amplitude) mean += a / static_cast<double>(m);
  if (inverse_excitation.size() == m) {  // force channel: a percent of the force and a floor
    double top = 0.0;
    for (double e : inverse_excitation) top = std::max(top, std::abs(e));
    std::vector<double> a2, e2, one(m, 1.0), e2_over_a2;
    for (std::size_t i = 0; i < m; ++i) {
      const double e = inverse_excitation[i] / top;
      a2.push_back(amplitude[i] * amplitude[i]);
      e2.push_back(e * e);
      e2_over_a2.push_back(e * e * mean * mean / std::max(a2.back(), 1e-300));
    }
    n.amplitude_local = channel_noise(x, amplitude, degree, a2, e2);
    n.phase_local = channel_noise(x, phase_deg, degree, one, e2_over_a2);
  } else {
    n.amplitude_local.assign(m, polynomial_scatter(x, amplitude, degree));
    n.phase_local.assign(m, polynomial_scatter(x, phase_deg, degree));
  }
  floor_noise(n.amplitude_local, 1e-6 * mean);
  floor_noise(n.phase_local, 1e-6);
  n.amplitude = rms_of(n.amplitude_local);
  n.phase = rms_of(n.phase_local);
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
  const bool local = noise.known && noise.amplitude_local.size() == n && noise.phase_local.size() == n;
  const std::vector<double>* la = local ? &noise.amplitude_local : nullptr;
  const std::vector<double>* lp = local ? &noise.phase_local : nullptr;
  std::vector<RegionError> out;
  auto add = [&](const std::string& name, const std::vector<std::size_t>& index) {
    out.push_back(region_error(name + "_" + amplitude_name, unit, model, measured, index, mean, ea, factor, la, local));
    out.push_back(region_error(name + "_phase", "deg", model_phase, measured_phase, index, 90.0, ep, 1.0, lp, local));
  };
  add("all", all);
  const char* names[3] = {"band_low", "band_mid", "band_high"};
  for (int b = 0; b < 3; ++b) add(names[b], band[b]);
  return out;
}

}  // namespace cushion::calibration
