#include "calibration/fit_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "material/viscoelastic.hpp"

namespace cushion::calibration {

namespace {

using cplx = std::complex<double>;

/// Base equilibrium at the preload: F_b and the elastic evaluation there.
struct BaseState {
  cushion::Mat3 F;
  material::ElasticEval e;
};

BaseState base_state(const material::Hyperelastic& base, double preload, Lateral lateral) {
  material::History h;
  const int steps = 20;  // continuation for the lateral Newton; the result is the equilibrium at the end
  for (int k = 0; k <= steps; ++k) {
    h.time.push_back(k);
    h.control.push_back(-preload * k / steps);
  }
  const material::PointResult r = material::run_point(base, load_mode(lateral), h);
  BaseState s{r.F.back(), base.evaluate(r.F.back())};
  if (s.e.status == material::Status::failed)
    throw std::runtime_error("fit model: the hyperfoam fails at the preload " + std::to_string(preload) + ": " + s.e.message);
  return s;
}

/// Uniaxial condensation of a 6x6 tangent (Voigt [11,22,33,12,23,13]) to dS11/dE11.
template <class M>
typename M::Scalar condensed(const M& C, Lateral lateral) {
  using T = typename M::Scalar;
  if (lateral == Lateral::constrained) return C(0, 0);
  Eigen::Matrix<T, 2, 2> CLL;
  CLL << C(1, 1), C(1, 2), C(2, 1), C(2, 2);
  Eigen::Matrix<T, 1, 2> C0L;
  C0L << C(0, 1), C(0, 2);
  Eigen::Matrix<T, 2, 1> CL0;
  CL0 << C(1, 0), C(2, 0);
  return C(0, 0) - (C0L * CLL.inverse() * CL0)(0, 0);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

material::MaterialSpec to_spec(const ViscoHyperfoam& m, const std::string& name, const std::string& description,
                               double density) {
  material::MaterialSpec spec;
  spec.name = name;
  spec.description = description;
  spec.density = density;
  spec.base = material::MaterialSpec::Base::hyperfoam;
  spec.hyperfoam = m.terms;
  spec.prony = m.prony;
  spec.moduli = material::ModuliConvention::long_term;
  return spec;
}

std::shared_ptr<const material::Material> build_model(const ViscoHyperfoam& m) {
  auto base = std::make_shared<const material::Hyperfoam>(m.terms);
  if (m.prony.empty()) return base;
  return std::make_shared<const material::Viscoelastic>(base, m.prony, material::ModuliConvention::long_term);
}

std::string material_problem(const ViscoHyperfoam& m) {
  double sum_mu = 0.0;  // the material-file rule (io/material_file.hpp): sum mu > 0
  for (const auto& t : m.terms) sum_mu += t.mu;
  if (!(sum_mu > 0.0)) return "hyperfoam: the initial shear modulus sum(mu) must be > 0";
  try {
    material::build_material(to_spec(m, "check", "", 0.0), "material");
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::vector<material::PronyTerm> prony_from_long_term_ratios(const std::vector<double>& a, const std::vector<double>& tau) {
  if (a.size() != tau.size()) throw std::invalid_argument("prony_from_long_term_ratios: a and tau differ in length");
  double sum = 0.0;
  for (double x : a) sum += x;
  std::vector<material::PronyTerm> terms;
  for (std::size_t i = 0; i < a.size(); ++i) terms.push_back({a[i] / (1.0 + sum), tau[i]});
  return terms;
}

std::vector<double> long_term_ratios(const std::vector<material::PronyTerm>& prony) {
  double sum_g = 0.0;
  for (const auto& t : prony) sum_g += t.g;
  std::vector<double> a;
  for (const auto& t : prony) a.push_back(t.g / (1.0 - sum_g));
  return a;
}

material::LoadMode load_mode(Lateral lateral) {
  return lateral == Lateral::free ? material::LoadMode::uniaxial_free : material::LoadMode::uniaxial_constrained;
}

PreloadTangent preload_tangent(const material::Hyperelastic& base, double preload, Lateral lateral) {
  const BaseState s = base_state(base, preload, lateral);
  PreloadTangent p;
  p.preload = preload;
  p.stretch = s.F(0, 0);
  p.lateral_stretch = s.F(1, 1);
  p.S11 = s.e.S(0);
  p.stress = -p.stretch * p.S11;
  p.K_v = p.stretch * p.stretch * condensed(s.e.dS_dE, lateral);
  p.K_hf = p.S11 + p.K_v;
  return p;
}

DynamicModuli model_dynamic_moduli(const material::Material& model, const material::Hyperelastic& base,
                                   double preload, const std::vector<double>& frequency, Lateral lateral,
                                   const DynamicSchedule* schedule) {
  // Base state per frequency: F and the total PK2 S11 (relaxed: the long-term equilibrium).
  std::vector<cushion::Mat3> F(frequency.size());
  std::vector<double> S11(frequency.size());
  if (!schedule) {
    const BaseState s = base_state(base, preload, lateral);
    std::fill(F.begin(), F.end(), s.F);
    std::fill(S11.begin(), S11.end(), s.e.S(0));
  } else {
    const DynamicPath path = dynamic_path(preload, frequency, schedule, {});
    material::History h;
    h.time = path.path.time;
    for (double l : path.path.stretch) h.control.push_back(l - 1.0);
    const material::PointResult r = material::run_point(model, load_mode(lateral), h);
    for (std::size_t i = 0; i < frequency.size(); ++i) {
      const std::size_t k = path.window[i];
      F[i] = r.F[k];
      S11[i] = r.P[k](0, 0) / r.F[k](0, 0);
    }
  }
  DynamicModuli d;
  for (std::size_t i = 0; i < frequency.size(); ++i) {
    const double f = frequency[i];
    const double l = F[i](0, 0);
    const cushion::Mat6c C = model.complex_tangent(F[i], 2.0 * std::numbers::pi * f);
    const cplx E = S11[i] + l * l * condensed(C, lateral);
    d.frequency.push_back(f);
    d.storage.push_back(E.real());
    d.loss.push_back(E.imag());
  }
  return d;
}

std::vector<double> strain_amplitudes(const DynamicTest& test, double thickness) {
  std::vector<double> delta;
  for (double f : test.moduli.frequency) {
    const double w = 2.0 * std::numbers::pi * f;
    const double peak = test.amplitude_peak_to_peak ? 0.5 : 1.0;  // campaign key amplitude_is
    delta.push_back(peak * test.acceleration_amplitude / (w * w) / thickness);
  }
  return delta;
}

DynamicPath dynamic_path(double preload, const std::vector<double>& frequency, const DynamicSchedule* schedule,
                         const std::vector<double>& tau, const std::vector<double>& amplitude) {
  std::vector<double> time, strain;
  DynamicPath d;
  d.relaxed = schedule == nullptr;
  d.preload_stretch = 1.0 - preload;
  d.frequency = frequency;
  d.amplitude = amplitude;
  if (d.relaxed) {
    time = {0.0};
    strain = {preload};
    d.window.assign(frequency.size(), 0);
  } else {
    const double ramp_s = preload * schedule->thickness / (schedule->preload_rate_mm_min / 60.0);
    const int ramp_steps = std::max(1, static_cast<int>(std::ceil(ramp_s * 5.0)));
    for (int k = 0; k <= ramp_steps; ++k) {
      time.push_back(ramp_s * k / ramp_steps);
      strain.push_back(preload * k / ramp_steps);
    }
    double t = ramp_s + schedule->dwell_s;
    for (double f : frequency) {  // hold at the preload to each window centre (the sines are small)
      d.window.push_back(time.size());
      time.push_back(t + (schedule->cycles - 0.5 * schedule->fit_cycles) / f);
      strain.push_back(preload);
      t += schedule->cycles / f;
    }
  }
  d.path = make_uniaxial_path(time, strain, tau);
  for (double f : frequency)
    for (int h = 1; h <= 2; ++h) {
      const double w = 2.0 * std::numbers::pi * f * h;
      std::vector<cplx> weights;
      for (double t : tau) weights.push_back(cplx(0.0, w * t) / cplx(1.0, w * t));
      d.prony_weight.push_back(weights);
    }
  return d;
}

ContactSamples contact_samples(const QuasiStaticTest& test, const Segments& segments, const Specimen& specimen) {
  const StressStrainRecord& rec = test.record;
  const double strain_rate = test.rate / specimen.thickness;
  const double t0 = rec.time[segments.load_begin] - rec.strain[segments.load_begin] / strain_rate;
  ContactSamples c;
  if (rec.strain[segments.load_begin] > 0.0) {
    c.time.push_back(0.0);
    c.strain.push_back(0.0);
    c.stress.push_back(std::nan(""));
  }
  // A truncated unloading ends at its first ~zero-force sample: the platen may have left the foam there.
  const std::size_t last = segments.unload_end + 1 < rec.time.size() ? segments.unload_end - 1 : segments.unload_end;
  for (std::size_t i = segments.load_begin; i <= last; ++i) {
    c.time.push_back(rec.time[i] - t0);
    c.strain.push_back(rec.strain[i]);
    c.stress.push_back(rec.stress[i]);
  }
  return c;
}

QuasiStaticProtocol protocol_of(const QuasiStaticTest& test, const Segments& segments, double sample_hz) {
  QuasiStaticProtocol p;
  p.name = test.name;
  p.rate_mm_min = test.rate * 60.0;
  p.max_strain = segments.peak_strain;
  p.hold_s = segments.hold_duration;
  p.sample_hz = sample_hz;
  p.prior = test.prior;
  p.lift_off = test.lift_off;
  p.lateral = load_mode(test.lateral);
  return p;
}

DynamicProtocol protocol_of(const DynamicTest& test, int steps_per_cycle, int transient_steps_per_cycle,
                            double default_preload_rate_mm_min) {
  DynamicProtocol p;
  p.name = test.name;
  p.preload_strain = test.preload_strain;
  p.preload_rate_mm_min = test.preload_rate_mm_min > 0.0 ? test.preload_rate_mm_min : default_preload_rate_mm_min;
  p.dwell_s = test.dwell_s;
  p.prior = test.prior;
  p.lift_off = test.lift_off;
  p.acceleration_amplitude = test.acceleration_amplitude / 1000.0;  // mm/s^2 -> m/s^2
  p.amplitude_peak_to_peak = test.amplitude_peak_to_peak;
  p.frequencies_Hz = test.moduli.frequency;
  p.cycles = test.cycles;
  p.fit_cycles = test.fit_cycles;
  p.steps_per_cycle = steps_per_cycle;
  p.transient_steps_per_cycle = transient_steps_per_cycle;
  return p;
}

double sampling_rate(const StressStrainRecord& record) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < record.time.size(); ++i) dt.push_back(record.time[i] - record.time[i - 1]);
  const double m = median(dt);
  return m > 0.0 ? 1.0 / m : 1.0;
}

QuasiStaticPrediction predict_quasi_static(const material::Material& model, const Specimen& specimen,
                                           const QuasiStaticTest& test, const Segments& segments, double sample_hz) {
  const LabSpecimen lab{specimen.length, specimen.width, specimen.thickness, 65.0};
  const QuasiStaticRecord run = run_quasi_static(model, lab, protocol_of(test, segments, sample_hz));
  const StressStrainRecord& rec = test.record;
  // The model starts loading at t = 0; the record's loading starts where its strain leaves zero.
  const double strain_rate = test.rate / specimen.thickness;
  const double t0 = rec.time[segments.load_begin] - rec.strain[segments.load_begin] / strain_rate;
  std::vector<double> model_stress;
  for (double f : run.force_N) model_stress.push_back(f / specimen.area());
  QuasiStaticPrediction p;
  double peak = 0.0, sum2 = 0.0;
  for (std::size_t i = segments.load_begin; i < rec.time.size(); ++i) {
    const double t = rec.time[i] - t0;
    if (t > run.time_s.back() + 1e-9) break;
    p.time.push_back(rec.time[i]);
    p.strain.push_back(rec.strain[i]);
    p.measured.push_back(rec.stress[i]);
    p.model.push_back(interpolate(run.time_s, model_stress, t));
    peak = std::max(peak, rec.stress[i]);
  }
  for (std::size_t i = 0; i < p.model.size(); ++i) {
    const double e = std::abs(p.model[i] - p.measured[i]);
    sum2 += e * e;
    p.max_error = std::max(p.max_error, e);
  }
  if (peak > 0.0 && !p.model.empty()) {
    p.rms_error = std::sqrt(sum2 / p.model.size()) / peak;
    p.max_error /= peak;
  }
  return p;
}

DynamicPrediction predict_dynamic(const material::Material& model, const material::Hyperelastic& base,
                                  const DynamicTest& test, const DynamicSchedule* schedule) {
  DynamicPrediction p;
  p.measured = test.moduli;
  p.model = model_dynamic_moduli(model, base, test.preload_strain, test.moduli.frequency, Lateral::free, schedule);
  const std::size_t n = p.measured.frequency.size();
  for (std::size_t i = 0; i < n; ++i) {
    const cplx m(p.model.storage[i], p.model.loss[i]), d(p.measured.storage[i], p.measured.loss[i]);
    const double em = std::abs(m) / std::abs(d) - 1.0;
    const double ep = (std::arg(m) - std::arg(d)) * 180.0 / std::numbers::pi;
    const double es = p.model.storage[i] / p.measured.storage[i] - 1.0;
    const double el = p.model.loss[i] / p.measured.loss[i] - 1.0;
    p.magnitude_rms += em * em;
    p.phase_rms += ep * ep;
    p.storage_rms += es * es;
    p.loss_rms += el * el;
  }
  if (n > 0) {
    p.magnitude_rms = std::sqrt(p.magnitude_rms / n);
    p.phase_rms = std::sqrt(p.phase_rms / n);
    p.storage_rms = std::sqrt(p.storage_rms / n);
    p.loss_rms = std::sqrt(p.loss_rms / n);
  }
  return p;
}

}  // namespace cushion::calibration
