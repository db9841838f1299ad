#include "material/calibration/compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "material/calibration/fit_model.hpp"
#include "material/calibration/lab.hpp"

namespace cushion::calibration {

namespace {

constexpr double kPa = 1000.0;  // kPa per MPa

double median_abs(std::vector<double> v) {
  if (v.empty()) return 0.0;
  for (double& x : v) x = std::abs(x);
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// Quasi-static noise: third differences of the loading and of the unloading branch; local RMS over
/// +-15 differences, assigned to the record samples (hold samples take the nearest branch value).
void quasi_static_noise(const QuasiStaticTest& test, const Segments& s, TestNoise& n) {
  const auto& y = test.record.stress;
  const std::size_t N = y.size();
  std::vector<double> local(N, -1.0);
  auto branch = [&](std::size_t a, std::size_t b) {
    if (b < a + 8) return;
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
  };
  branch(s.load_begin, s.load_end);
  branch(s.unload_begin, s.unload_end);
  // Fill samples not covered (before loading, hold, after unloading) from the nearest covered one.
  double last = -1.0;
  for (std::size_t i = 0; i < N; ++i) (local[i] >= 0.0 ? last = local[i] : local[i] = last);
  last = -1.0;
  for (std::size_t i = N; i-- > 0;) (local[i] >= 0.0 ? last = local[i] : local[i] = last);
  double s2 = 0.0;
  for (double v : local) s2 += v * v;
  n.stress = N > 0 && local.front() >= 0.0 ? std::sqrt(s2 / N) : 0.0;
  n.known = n.stress > 0.0;
  if (n.known) n.stress_local = local;
}

std::vector<double> log_frequency(const DynamicModuli& m) {
  std::vector<double> x;
  for (double f : m.frequency) x.push_back(std::log(f));
  return x;
}

int scatter_degree(std::size_t n) { return n >= 8 ? 3 : n >= 5 ? 2 : -1; }

RegionError region_of(const std::string& name, const std::string& unit, const std::vector<double>& model,
                      const std::vector<double>& measured, const std::vector<std::size_t>& index, double scale,
                      double noise, double factor, const std::vector<double>* local = nullptr) {
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

/// Loop area of a closed-ish load/unload curve: integral of stress d strain (loading minus unloading) [MPa].
double loop_area(const std::vector<double>& strain, const std::vector<double>& stress) {
  double a = 0.0;
  for (std::size_t i = 1; i < strain.size(); ++i) a += 0.5 * (stress[i] + stress[i - 1]) * (strain[i] - strain[i - 1]);
  return a;
}

std::string use_name(TestUse u) { return u == TestUse::calibration ? "calibration" : "validation"; }

TestCompare compare_quasi_static(const material::Material& model, const Campaign& campaign, const QuasiStaticTest& test,
                                 const TestNoise& noise, const CompareOptions& o) {
  TestCompare c;
  c.name = test.name;
  c.kind = "quasi_static";
  c.use = use_name(test.use);
  c.rate_mm_min = test.rate * 60.0;
  c.noise = noise;
  const Segments seg = detect_segments(test.record);
  const double ramp_s = seg.peak_strain * campaign.specimen.thickness / test.rate;
  const double hz = std::min(sampling_rate(test.record), o.quasi_static_steps / ramp_s);
  const QuasiStaticPrediction p = predict_quasi_static(model, campaign.specimen, test, seg, hz);
  c.x = p.strain;
  c.measured = p.measured;
  c.model = p.model;
  // Unloading starts at the record's unload_begin (prediction starts at load_begin).
  c.unload_begin = std::min(seg.unload_begin - seg.load_begin, c.x.size());
  const double peak = seg.peak_stress;
  std::vector<std::size_t> all, load, unload, low, mid, high;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    all.push_back(i);
    (i < c.unload_begin ? load : unload).push_back(i);
    const double u = c.x[i] / seg.peak_strain;
    (u < 1.0 / 3.0 ? low : u < 2.0 / 3.0 ? mid : high).push_back(i);
  }
  const double sn = noise.known ? noise.stress : 0.0;
  // Local noise at the prediction's samples (the prediction starts at the record's load_begin).
  std::vector<double> ln;
  if (noise.known)
    for (std::size_t i = 0; i < c.x.size(); ++i) ln.push_back(noise.stress_local[seg.load_begin + i]);
  c.noise_local = ln;
  const std::vector<double>* L = &c.noise_local;
  c.regions.push_back(region_of("all", "kPa", c.model, c.measured, all, peak, sn, kPa, L));
  c.regions.push_back(region_of("loading", "kPa", c.model, c.measured, load, peak, sn, kPa, L));
  c.regions.push_back(region_of("unloading", "kPa", c.model, c.measured, unload, peak, sn, kPa, L));
  c.regions.push_back(region_of("low_strain", "kPa", c.model, c.measured, low, peak, sn, kPa, L));
  c.regions.push_back(region_of("mid_strain", "kPa", c.model, c.measured, mid, peak, sn, kPa, L));
  c.regions.push_back(region_of("high_strain", "kPa", c.model, c.measured, high, peak, sn, kPa, L));
  c.hysteresis_measured = loop_area(c.x, c.measured);
  c.hysteresis_model = loop_area(c.x, c.model);
  RegionError h{"hysteresis_area", "kPa"};
  h.rms = std::abs(c.hysteresis_model - c.hysteresis_measured) * kPa;
  h.bias = (c.hysteresis_model - c.hysteresis_measured) * kPa;
  h.nrmse = std::abs(c.hysteresis_measured) > 0.0 ? h.rms / (std::abs(c.hysteresis_measured) * kPa) : 0.0;
  // Noise of the trapezoid sum: sigma sqrt(sum of squared strain steps).
  double ds2 = 0.0;
  for (std::size_t i = 1; i < c.x.size(); ++i) ds2 += std::pow(c.x[i] - c.x[i - 1], 2) * (ln.empty() ? 1.0 : ln[i] * ln[i] / (sn * sn));
  h.noise = sn * std::sqrt(ds2) * kPa;
  h.points = c.x.size();
  c.regions.push_back(h);
  return c;
}

TestCompare compare_dynamic(const material::Material& model, const Campaign& campaign, const DynamicTest& test,
                            const TestNoise& noise, const CompareOptions& o) {
  TestCompare c;
  c.name = test.name;
  c.kind = "dynamic";
  c.use = use_name(test.use);
  c.preload = test.preload_strain;
  c.noise = noise;
  DynamicProtocol p;
  p.name = test.name;
  p.preload_strain = test.preload_strain;
  p.preload_rate_mm_min = o.preload_rate_mm_min;
  p.acceleration_amplitude = test.acceleration_amplitude / 1000.0;  // mm/s^2 -> m/s^2
  p.amplitude_peak_to_peak = true;
  p.frequencies_Hz = test.moduli.frequency;
  p.cycles = o.dynamic_cycles;
  p.fit_cycles = o.dynamic_fit_cycles;
  p.steps_per_cycle = o.dynamic_steps_per_cycle;
  const LabSpecimen lab{campaign.specimen.length, campaign.specimen.width, campaign.specimen.thickness, 65.0};
  const DynamicRecord r = run_dynamic(model, lab, p, LabNoise{}, 0);
  c.x = test.moduli.frequency;
  const std::size_t n = c.x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::complex<double> E(test.moduli.storage[i], test.moduli.loss[i]);
    c.measured.push_back(std::abs(E));
    c.measured_phase.push_back(std::arg(E) * 180.0 / std::numbers::pi);
    c.model.push_back(r.dynamic_modulus_kPa[i] / kPa);
    c.model_phase.push_back(r.phase_deg[i]);
  }
  double mean = 0.0;
  for (double e : c.measured) mean += e / n;
  std::vector<std::size_t> all, band[3];
  for (std::size_t i = 0; i < n; ++i) {
    all.push_back(i);
    band[std::min<std::size_t>(2, 3 * i / n)].push_back(i);
  }
  const double em = noise.known ? noise.modulus : 0.0, ep = noise.known ? noise.phase : 0.0;
  c.regions.push_back(region_of("all_modulus", "kPa", c.model, c.measured, all, mean, em, kPa));
  c.regions.push_back(region_of("all_phase", "deg", c.model_phase, c.measured_phase, all, 90.0, ep, 1.0));
  const char* names[3] = {"band_low", "band_mid", "band_high"};
  for (int b = 0; b < 3; ++b) {
    c.regions.push_back(region_of(std::string(names[b]) + "_modulus", "kPa", c.model, c.measured, band[b], mean, em, kPa));
    c.regions.push_back(region_of(std::string(names[b]) + "_phase", "deg", c.model_phase, c.measured_phase, band[b], 90.0, ep, 1.0));
  }
  return c;
}

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

std::vector<TestNoise> estimate_noise(const Campaign& campaign) {
  std::vector<TestNoise> out;
  for (const auto& t : campaign.quasi_static) {
    TestNoise n;
    quasi_static_noise(t, detect_segments(t.record), n);
    out.push_back(n);
  }
  for (const auto& t : campaign.dynamic) {
    TestNoise n;
    const int degree = scatter_degree(t.moduli.frequency.size());
    if (degree >= 0) {
      std::vector<double> E, phase;
      for (std::size_t i = 0; i < t.moduli.frequency.size(); ++i) {
        const std::complex<double> e(t.moduli.storage[i], t.moduli.loss[i]);
        E.push_back(std::abs(e));
        phase.push_back(std::arg(e) * 180.0 / std::numbers::pi);
      }
      const auto x = log_frequency(t.moduli);
      n.modulus = polynomial_scatter(x, E, degree);
      n.phase = polynomial_scatter(x, phase, degree);
      // A noise-free record still has floating-point scatter: floor at 1e-6 of the level.
      double mean = 0.0;
      for (double e : E) mean += e / E.size();
      n.modulus = std::max(n.modulus, 1e-6 * mean);
      n.phase = std::max(n.phase, 1e-6);
      n.known = true;
    }
    out.push_back(n);
  }
  return out;
}

double TestCompare::noise_ratio() const {
  if (!failure.empty() || regions.empty()) return 0.0;
  if (kind == "quasi_static") return regions.front().ratio();
  const double a = regions[0].ratio(), b = regions[1].ratio();
  return std::sqrt((a * a + b * b) / 2.0);
}

const RegionError* TestCompare::region(const std::string& name) const {
  for (const auto& r : regions)
    if (r.region == name) return &r;
  return nullptr;
}

bool CompareResult::at_noise_level(double ratio) const {
  for (const auto& t : tests)
    if (!t.failure.empty() || (t.noise.known && t.noise_ratio() > ratio)) return false;
  return true;
}

CompareResult compare_campaign(const material::Material& model, const Campaign& campaign, const CompareOptions& options,
                               const std::vector<TestNoise>& given_noise) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<TestNoise> noise = given_noise.empty() ? estimate_noise(campaign) : given_noise;
  CompareResult result;
  std::size_t k = 0;
  auto guarded = [&](auto&& run, const std::string& name, const std::string& kind) {
    try {
      result.tests.push_back(run());
    } catch (const std::exception& e) {
      TestCompare c;
      c.name = name;
      c.kind = kind;
      c.noise = noise[k];
      c.failure = e.what();
      result.warnings.push_back(name + ": model run failed: " + e.what());
      result.tests.push_back(c);
    }
    ++k;
  };
  for (const auto& t : campaign.quasi_static)
    guarded([&] { return compare_quasi_static(model, campaign, t, noise[k], options); }, t.name, "quasi_static");
  for (const auto& t : campaign.dynamic)
    guarded([&] { return compare_dynamic(model, campaign, t, noise[k], options); }, t.name, "dynamic");
  for (const auto& t : result.tests)
    if (t.failure.empty() && !t.noise.known)
      result.warnings.push_back(t.name + ": too few samples to estimate the measurement noise");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<std::string> specimen_warnings(double material_density, const Campaign& campaign) {
  const double c = campaign.specimen.density;
  if (material_density <= 0.0 || c <= 0.0 || std::abs(material_density / c - 1.0) <= 0.05) return {};
  return {"specimen mismatch: the material file gives density " + std::to_string(material_density * 1e12) +
          " kg/m^3, the campaign's specimen " + std::to_string(c * 1e12) +
          " kg/m^3: the material was calibrated on another foam; errors below include that difference"};
}

std::vector<double> normalised_residuals(const CompareResult& result, int quasi_static_points) {
  std::vector<double> r;
  for (const auto& t : result.tests) {
    if (!t.noise.known) continue;
    if (t.kind == "quasi_static") {
      const std::size_t n = t.x.size();
      const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(quasi_static_points));
      for (std::size_t j = 0; j < m; ++j) {
        if (!t.failure.empty()) {
          r.push_back(1e3);
          continue;
        }
        const std::size_t i = m > 1 ? j * (n - 1) / (m - 1) : 0;
        r.push_back((t.model[i] - t.measured[i]) / t.noise_local[i]);
      }
    } else {
      for (std::size_t i = 0; i < t.x.size(); ++i) {
        if (!t.failure.empty()) {
          r.push_back(1e3);
          r.push_back(1e3);
          continue;
        }
        r.push_back((t.model[i] - t.measured[i]) / t.noise.modulus);
        r.push_back((t.model_phase[i] - t.measured_phase[i]) / t.noise.phase);
      }
    }
  }
  return r;
}

}  // namespace cushion::calibration
