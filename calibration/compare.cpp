#include "calibration/compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "calibration/fit_model.hpp"
#include "calibration/lab.hpp"

namespace cushion::calibration {

namespace {

constexpr double kPa = 1000.0;  // kPa per MPa

/// Quasi-static noise: the reading-dependent noise fitted on the loading, the hold and the unloading branch.
void quasi_static_noise(const QuasiStaticTest& test, const Segments& s, TestNoise& n) {
  const std::vector<double> local = reading_noise(
      test.record.stress, {{s.load_begin, s.load_end}, {s.load_end, s.unload_begin}, {s.unload_begin, s.unload_end}});
  n.stress = rms_of(local);
  n.known = n.stress > 0.0;
  if (n.known) n.stress_local = local;
}

std::vector<double> modulus_amplitude(const DynamicModuli& m) {
  std::vector<double> a;
  for (std::size_t i = 0; i < m.frequency.size(); ++i) a.push_back(std::abs(std::complex<double>(m.storage[i], m.loss[i])));
  return a;
}

std::vector<double> modulus_phase(const DynamicModuli& m) {
  std::vector<double> p;
  for (std::size_t i = 0; i < m.frequency.size(); ++i)
    p.push_back(std::arg(std::complex<double>(m.storage[i], m.loss[i])) * 180.0 / std::numbers::pi);
  return p;
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
  const double sn = noise.known ? noise.stress : 0.0;
  // Local noise at the prediction's samples (the prediction starts at the record's load_begin).
  if (noise.known)
    for (std::size_t i = 0; i < c.x.size(); ++i) c.noise_local.push_back(noise.stress_local[seg.load_begin + i]);
  c.regions = curve_regions({c.x, c.measured, c.model, c.noise_local, c.unload_begin, seg.peak_strain, seg.peak_stress},
                            "strain", "kPa", "kPa", sn, kPa);
  c.hysteresis_measured = loop_area(c.x, c.measured);
  c.hysteresis_model = loop_area(c.x, c.model);
  return c;
}

/// The specimen of a campaign as the dynamic forward model (lab.hpp run_dynamic) takes it.
LabSpecimen lab_of(const Campaign& campaign) {
  return {campaign.specimen.length, campaign.specimen.width, campaign.specimen.thickness, 65.0};
}

/// The protocol of dynamic test `test` at the options' steps per cycle and preload rate.
DynamicProtocol dynamic_protocol(const DynamicTest& test, const CompareOptions& o) {
  return protocol_of(test, o.dynamic_steps_per_cycle, o.dynamic_transient_steps_per_cycle, o.preload_rate_mm_min);
}

/// TestCompare::step_error of the dynamic test `c` (compared at o's steps): `test` at half the steps per cycle, the
/// change of |E*| and phase in noise units at each frequency, combined as noise_ratio; -1 when that run fails.
double sweep_step_error(const material::Material& model, const Campaign& campaign, const DynamicTest& test,
                        const CompareOptions& o, const TestCompare& c) {
  DynamicProtocol coarse = dynamic_protocol(test, o);
  coarse.steps_per_cycle = std::max(1, coarse.steps_per_cycle / 2);
  coarse.transient_steps_per_cycle = std::max(1, coarse.transient_steps_per_cycle / 2);
  DynamicRecord r;
  try {
    r = run_dynamic(model, lab_of(campaign), coarse, LabNoise{}, 0);
  } catch (const std::exception&) {
    return -1.0;  // not checked (step_warnings says so)
  }
  std::vector<double> modulus, phase;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    modulus.push_back(r.dynamic_modulus_kPa[i] / kPa);
    phase.push_back(r.phase_deg[i]);
  }
  TestCompare change = c;  // the coarse run in place of the measurement: its error is the change
  change.regions = spectrum_regions(modulus, c.model, phase, c.model_phase, c.noise.spectrum(), "modulus", "kPa", kPa);
  return change.noise_ratio();
}

TestCompare compare_dynamic(const material::Material& model, const Campaign& campaign, const DynamicTest& test,
                            const TestNoise& noise, const CompareOptions& o) {
  TestCompare c;
  c.name = test.name;
  c.kind = "dynamic";
  c.use = use_name(test.use);
  c.preload = test.preload_strain;
  c.noise = noise;
  const DynamicRecord r = run_dynamic(model, lab_of(campaign), dynamic_protocol(test, o), LabNoise{}, 0);
  c.x = test.moduli.frequency;
  c.measured = modulus_amplitude(test.moduli);
  c.measured_phase = modulus_phase(test.moduli);
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    c.model.push_back(r.dynamic_modulus_kPa[i] / kPa);
    c.model_phase.push_back(r.phase_deg[i]);
  }
  c.regions = spectrum_regions(c.measured, c.model, c.measured_phase, c.model_phase, noise.spectrum(), "modulus",
                               "kPa", kPa);
  c.steps_per_cycle = o.dynamic_steps_per_cycle;
  return c;
}

}  // namespace

std::vector<TestNoise> estimate_noise(const Campaign& campaign) {
  std::vector<TestNoise> out;
  for (const auto& t : campaign.quasi_static) {
    TestNoise n;
    quasi_static_noise(t, detect_segments(t.record), n);
    out.push_back(n);
  }
  for (const auto& t : campaign.dynamic) {
    std::vector<double> inverse_excitation;  // 1 / strain amplitude (none without an acceleration amplitude)
    if (t.acceleration_amplitude > 0.0)
      for (double e : strain_amplitudes(t, campaign.specimen.thickness)) inverse_excitation.push_back(1.0 / e);
    out.push_back(TestNoise::of(
        spectrum_noise(t.moduli.frequency, modulus_amplitude(t.moduli), modulus_phase(t.moduli), inverse_excitation)));
  }
  return out;
}

TestNoise TestNoise::of(const SpectrumNoise& s) {
  TestNoise n;
  n.modulus = s.amplitude;
  n.phase = s.phase;
  n.modulus_local = s.amplitude_local;
  n.phase_local = s.phase_local;
  n.known = s.known;
  return n;
}

double TestCompare::noise_ratio() const {
  if (!failure.empty() || regions.empty()) return 0.0;
  if (is_curve()) return regions.front().ratio();
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
  if (options.step_check) {
    add_step_errors(model, campaign, options, result);
    for (const auto& w : step_warnings(result, options)) result.warnings.push_back(w);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void add_step_errors(const material::Material& model, const Campaign& campaign, const CompareOptions& o,
                     CompareResult& result) {
  for (const DynamicTest& test : campaign.dynamic)
    for (TestCompare& c : result.tests)
      if (c.kind == "dynamic" && c.name == test.name && c.failure.empty() && c.noise.known)
        c.step_error = sweep_step_error(model, campaign, test, o, c);
}

std::vector<std::string> step_warnings(const CompareResult& result, const CompareOptions& o) {
  std::vector<std::string> out;
  for (const auto& t : result.tests) {
    if (t.kind != "dynamic" || !t.failure.empty() || !t.noise.known) continue;
    if (t.step_error < 0.0) {
      out.push_back(t.name + ": time step not checked (the run at half the steps per cycle failed)");
    } else if (t.step_error > o.step_error_warning) {
      std::ostringstream w;
      w << t.name << ": the time step moves |E*| and phase by " << std::setprecision(3) << t.step_error
        << "x noise between " << t.steps_per_cycle << " and " << t.steps_per_cycle / 2
        << " steps a cycle (first order in the step for a dashpot effect: about the error at " << t.steps_per_cycle
        << "); rerun with --steps-per-cycle " << std::min(2 * t.steps_per_cycle, max_steps_per_cycle)
        << " --transient-steps-per-cycle " << std::min(2 * o.dynamic_transient_steps_per_cycle, max_steps_per_cycle)
        << " to halve it (docs/physics.md 9.39)";
      out.push_back(w.str());
    }
  }
  return out;
}

std::vector<std::string> specimen_warnings(double material_density, const Campaign& campaign) {
  const double c = campaign.specimen.density;
  if (material_density <= 0.0 || c <= 0.0 || std::abs(material_density / c - 1.0) <= 0.05) return {};
  return {"specimen mismatch: the material file gives density " + std::to_string(material_density * 1e12) +
          " kg/m^3, the campaign's specimen " + std::to_string(c * 1e12) +
          " kg/m^3: the material was calibrated on another foam; errors below include that difference"};
}

std::vector<std::string> coverage_warnings(const Campaign& campaign) {
  std::vector<std::string> w;
  const std::size_t material_tests = campaign.quasi_static.size() + campaign.dynamic.size();
  auto distinct = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return static_cast<std::size_t>(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); }) - v.begin());
  };
  std::vector<double> rates, preloads;
  for (const auto& t : campaign.quasi_static) rates.push_back(t.rate);
  for (const auto& t : campaign.dynamic) preloads.push_back(t.preload_strain);
  if (material_tests == 1)
    w.push_back("only one material-level test: its error alone cannot tell which effect is missing, and no held-out test "
                "checks the model outside the conditions it was fitted at");
  if (distinct(rates) == 1)
    w.push_back("one quasi-static rate: a rate-dependent hysteresis (viscous, pneumatic) cannot be told from a "
                "rate-independent one (friction, Mullins); add a test at another rate");
  if (distinct(preloads) == 1)
    w.push_back("one dynamic preload: preload-dependent moduli cannot be seen; add a sweep at another preload");
  if (campaign.indentation.size() == 1)
    w.push_back("one indentation test: the structure's hysteresis at one speed cannot tell viscous or pneumatic loss from "
                "friction; add a test at another speed");
  return w;
}

std::vector<double> normalised_residuals(const CompareResult& result, int quasi_static_points) {
  std::vector<double> r;
  for (const auto& t : result.tests) {
    if (!t.noise.known) continue;
    if (t.is_curve()) {
      const std::size_t n = t.x.size();
      const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(quasi_static_points));
      for (std::size_t j = 0; j < m; ++j) {
        if (!t.failure.empty()) {
          r.push_back(1e3);
          continue;
        }
        const std::size_t i = m > 1 ? j * (n - 1) / (m - 1) : 0;
        r.push_back((t.model[i] - t.measured[i]) / t.noise.stress_weighting(t.noise_local[i]));
      }
    } else {
      for (std::size_t i = 0; i < t.x.size(); ++i) {
        if (!t.failure.empty()) {
          r.push_back(1e3);
          r.push_back(1e3);
          continue;
        }
        const bool local = t.noise.modulus_local.size() == t.x.size() && t.noise.phase_local.size() == t.x.size();
        r.push_back((t.model[i] - t.measured[i]) / (local ? t.noise.modulus_local[i] : t.noise.modulus));
        r.push_back((t.model_phase[i] - t.measured_phase[i]) / (local ? t.noise.phase_local[i] : t.noise.phase));
      }
    }
  }
  return r;
}

}  // namespace cushion::calibration
