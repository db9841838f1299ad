#include "calibration/separating_test.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>

#include "calibration/fit_model.hpp"
#include "calibration/lab.hpp"
#include "io/text_support.hpp"

namespace cushion::calibration {

namespace {

/// v with 3 (or 4) significant digits, for the names of the proposals.
std::string fmt(double v) { return io::format_with("%.3g", v); }
std::string fmt4(double v) { return io::format_with("%.4g", v); }

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The campaign's noise scales: quasi-static RMS stress noise [MPa], dynamic |E*| noise relative to |E*| [-] and
/// phase noise [deg], medians over the tests with an estimate (NaN: no such test).
struct NoiseScales {
  double stress = std::numeric_limits<double>::quiet_NaN();
  double modulus_relative = std::numeric_limits<double>::quiet_NaN();
  double phase = std::numeric_limits<double>::quiet_NaN();
};

NoiseScales noise_scales(const Campaign& c, const std::vector<TestNoise>& noise) {
  std::vector<double> stress, modulus, phase;
  for (std::size_t i = 0; i < c.quasi_static.size() && i < noise.size(); ++i)
    if (noise[i].known) stress.push_back(noise[i].stress);
  for (std::size_t j = 0; j < c.dynamic.size(); ++j) {
    const std::size_t i = c.quasi_static.size() + j;
    if (i >= noise.size() || !noise[i].known) continue;
    const DynamicModuli& m = c.dynamic[j].moduli;
    double mean = 0.0;
    for (std::size_t k = 0; k < m.frequency.size(); ++k)
      mean += std::abs(std::complex<double>(m.storage[k], m.loss[k]));
    mean /= std::max<std::size_t>(1, m.frequency.size());
    if (mean > 0.0) modulus.push_back(noise[i].modulus / mean);
    phase.push_back(noise[i].phase);
  }
  return {median(stress), median(modulus), median(phase)};
}

/// One proposal: its name and how to run it with a model (the separation from the two runs).
struct Proposal {
  std::string name;
  int residuals = 0;  ///< noise-normalised residuals of such a test in diagnose's chi2
  std::function<double(const material::Material&, const material::Material&)> separation;
};

/// Quasi-static separation: RMS stress difference [MPa] over the campaign's stress noise.
double quasi_static_separation(const material::Material& a, const material::Material& b, const LabSpecimen& lab,
                               const QuasiStaticProtocol& p, double stress_noise) {
  const QuasiStaticRecord ra = run_quasi_static(a, lab, p), rb = run_quasi_static(b, lab, p);
  if (ra.force_N.size() != rb.force_N.size()) throw std::runtime_error("the two runs differ in length");
  std::vector<double> d;
  for (std::size_t k = 0; k < ra.force_N.size(); ++k) d.push_back((ra.force_N[k] - rb.force_N[k]) / lab.area());
  return rms_of(d) / stress_noise;
}

/// Dynamic separation: sqrt((m^2 + p^2)/2), m and p the RMS |E*| and phase differences in noise units.
double dynamic_separation(const material::Material& a, const material::Material& b, const LabSpecimen& lab,
                          const DynamicProtocol& p, const NoiseScales& n, double noise_factor) {
  const DynamicRecord ra = run_dynamic(a, lab, p, LabNoise{}, 0), rb = run_dynamic(b, lab, p, LabNoise{}, 0);
  std::vector<double> m, ph;
  for (std::size_t k = 0; k < ra.frequency_Hz.size(); ++k) {
    const double mean = 0.5 * (ra.dynamic_modulus_kPa[k] + rb.dynamic_modulus_kPa[k]);
    m.push_back((ra.dynamic_modulus_kPa[k] - rb.dynamic_modulus_kPa[k]) / (noise_factor * n.modulus_relative * mean));
    ph.push_back((ra.phase_deg[k] - rb.phase_deg[k]) / (noise_factor * n.phase));
  }
  const double x = rms_of(m), y = rms_of(ph);
  return std::sqrt((x * x + y * y) / 2.0);
}

void quasi_static_proposals(const Campaign& c, const NoiseScales& n, const CompareOptions& o, int points,
                            const LabSpecimen& lab, std::vector<Proposal>& out) {
  if (c.quasi_static.empty() || !std::isfinite(n.stress) || n.stress <= 0.0) return;
  std::vector<const QuasiStaticTest*> by_rate;
  for (const auto& t : c.quasi_static) by_rate.push_back(&t);
  std::sort(by_rate.begin(), by_rate.end(), [](auto x, auto y) { return x->rate < y->rate; });
  const QuasiStaticTest& mid = *by_rate[by_rate.size() / 2];
  const Segments seg = detect_segments(mid.record);
  const double H = c.specimen.thickness;
  // compare's sampling: the record's rate, at most quasi_static_steps per loading ramp
  auto protocol_at = [&](double rate_mm_s, double max_strain) {
    const double ramp_s = max_strain * H / rate_mm_s;
    QuasiStaticProtocol p = protocol_of(mid, seg, std::min(sampling_rate(mid.record), o.quasi_static_steps / ramp_s));
    p.rate_mm_min = rate_mm_s * 60.0;
    p.max_strain = max_strain;
    p.name = "proposal";
    return p;
  };
  auto add = [&](std::string name, QuasiStaticProtocol p) {
    out.push_back(
        {std::move(name), points, [p, &lab, s = n.stress](const material::Material& a, const material::Material& b) {
           return quasi_static_separation(a, b, lab, p, s);
         }});
  };
  const double peak = seg.peak_strain, slow = by_rate.front()->rate, fast = by_rate.back()->rate;
  const std::string at = " to " + fmt(100 * peak) + " % compression";
  add("quasi-static at " + fmt4(slow * 6.0) + " mm/min (a tenth of the slowest rate)" + at,
      protocol_at(slow / 10.0, peak));
  add("quasi-static at " + fmt4(fast * 300.0) + " mm/min (five times the fastest rate)" + at,
      protocol_at(fast * 5.0, peak));
  QuasiStaticProtocol again = protocol_at(mid.rate, peak);
  again.prior.preflex_cycles += 1;
  again.prior.preflex_strain = peak;
  again.prior.rest_s = 0.0;
  add(mid.name + " repeated at once on the same specimen (a second loading: preflex_cycles " +
          std::to_string(again.prior.preflex_cycles) + ", rest_between_tests_s 0)",
      again);
  QuasiStaticProtocol hold = protocol_at(mid.rate, peak);
  hold.hold_s = 300.0;
  add(mid.name + " with a 300 s hold at " + fmt(100 * peak) + " % compression (relaxation)", hold);
  add(mid.name + " to half its peak, " + fmt(50 * peak) + " % compression", protocol_at(mid.rate, 0.5 * peak));
}

void dynamic_proposals(const Campaign& c, const NoiseScales& n, const CompareOptions& o, const LabSpecimen& lab,
                       std::vector<Proposal>& out) {
  if (c.dynamic.empty() || !std::isfinite(n.modulus_relative) || !(n.modulus_relative > 0.0) || !(n.phase > 0.0))
    return;
  double lo = 1.0, hi = 0.0;
  for (const auto& t : c.dynamic) lo = std::min(lo, t.preload_strain), hi = std::max(hi, t.preload_strain);
  const DynamicTest& first = c.dynamic.front();
  const DynamicProtocol base =
      protocol_of(first, o.dynamic_steps_per_cycle, o.dynamic_transient_steps_per_cycle, o.preload_rate_mm_min);
  auto add = [&](std::string name, DynamicProtocol p, double noise_factor) {
    out.push_back({std::move(name), 2 * static_cast<int>(p.frequencies_Hz.size()),
                   [p, &lab, n, noise_factor](const material::Material& a, const material::Material& b) {
                     return dynamic_separation(a, b, lab, p, n, noise_factor);
                   }});
  };
  for (double preload : {0.5 * lo, std::min(0.7, hi + 0.15)}) {
    if (preload < 0.02 || std::any_of(c.dynamic.begin(), c.dynamic.end(), [&](const DynamicTest& t) {
          return std::abs(t.preload_strain - preload) < 0.02;
        }))
      continue;
    DynamicProtocol p = base;
    p.preload_strain = preload;
    add("dynamic sweep at " + fmt(100 * preload) + " % preload (preload_strain " + fmt(preload) + ")", p, 1.0);
  }
  const double amplitude = first.acceleration_amplitude * 1e-3;  // m/s^2
  for (double factor : {0.25, 4.0}) {
    DynamicProtocol p = base;
    p.acceleration_amplitude *= factor;
    add(first.name + " at " + (factor < 1 ? "a quarter of" : "four times") +
            " its excitation (acceleration_amplitude_m_s2 " + fmt(amplitude * factor) + ")",
        p, std::max(1.0, 1.0 / factor));
  }
}

}  // namespace

std::vector<SeparatingTest> separating_tests(const material::Material& a, const material::Material& b,
                                             const Campaign& campaign, const std::vector<TestNoise>& noise,
                                             const CompareOptions& options, int quasi_static_points) {
  const LabSpecimen lab{campaign.specimen.length, campaign.specimen.width, campaign.specimen.thickness, 65.0};
  const NoiseScales n = noise_scales(campaign, noise);
  std::vector<Proposal> proposals;
  quasi_static_proposals(campaign, n, options, quasi_static_points, lab, proposals);
  dynamic_proposals(campaign, n, options, lab, proposals);
  std::vector<SeparatingTest> out;
  for (const auto& p : proposals) {
    SeparatingTest t{p.name, std::numeric_limits<double>::quiet_NaN(), p.residuals, ""};
    try {
      t.separation = p.separation(a, b);
      if (!std::isfinite(t.separation)) t.failure = "a model run gave no finite prediction";
    } catch (const std::exception& e) {
      t.failure = e.what();
    }
    if (!t.failure.empty()) t.separation = std::numeric_limits<double>::quiet_NaN();
    out.push_back(std::move(t));
  }
  std::stable_sort(out.begin(), out.end(), [](const SeparatingTest& x, const SeparatingTest& y) {
    if (std::isfinite(x.separation) != std::isfinite(y.separation)) return std::isfinite(x.separation);
    return x.delta_chi2() > y.delta_chi2();
  });
  return out;
}

}  // namespace cushion::calibration
