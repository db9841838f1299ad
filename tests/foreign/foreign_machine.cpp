// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/:
// the 1D foam step, the quasi-static and dynamic protocols, the sine fit and the machine's noise.
#include "foreign_machine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

namespace foreign_bench {

namespace {

constexpr double max_substep_mm = 0.02;

double relaxation_average(double x) { return x < 1e-12 ? 1.0 : -std::expm1(-x) / x; }

/// Sub-steps needed to move `distance_mm` in steps of at most max_substep_mm.
int substeps_for(double distance_mm) {
  return std::max(1, static_cast<int>(std::ceil(std::abs(distance_mm) / max_substep_mm - 1e-9)));
}

}  // namespace

FoamSpecimen::FoamSpecimen(const BaseFoam& foam, const std::vector<EffectSpec>& effects)
    : foam_(foam), prony_pk2_kPa_(foam.prony.size(), 0.0) {
  for (const auto& e : effects) effects_.push_back(make_effect(e, foam));
}

double FoamSpecimen::step(double strain_new, double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("FoamSpecimen::step: dt must be > 0");
  const Increment inc{dt_s, strain_, strain_new};
  double elastic_kPa = foam_.elastic_stress_kPa(strain_new);
  for (auto& e : effects_) elastic_kPa = e->soften_kPa(inc, elastic_kPa);
  // Decorator on the second Piola-Kirchhoff stress S = s/l (F = diag(l, 1, 1)); nominal s = l S.
  const double stretch = 1.0 - strain_new;
  const double elastic_pk2_kPa = elastic_kPa / stretch;
  double viscous_pk2_kPa = 0.0;
  for (std::size_t j = 0; j < prony_pk2_kPa_.size(); ++j) {
    double a = foam_.decorator_weight(j);
    for (const auto& e : effects_) a *= e->prony_factor(j, inc);
    const double x = dt_s / foam_.prony[j].tau_s;
    prony_pk2_kPa_[j] = std::exp(-x) * prony_pk2_kPa_[j] + a * relaxation_average(x) * (elastic_pk2_kPa - elastic_pk2_kPa_);
    viscous_pk2_kPa += prony_pk2_kPa_[j];
  }
  double stress_kPa = elastic_kPa + stretch * viscous_pk2_kPa;
  for (auto& e : effects_) stress_kPa += e->extra_stress_kPa(inc);
  strain_ = strain_new;
  elastic_pk2_kPa_ = elastic_pk2_kPa;
  return stress_kPa;
}

double DynamicRecord::modulus_sd_kPa(std::size_t i) const {
  return dynamic_modulus_kPa[i] * force_noise_sd_N[i] * std::sqrt(2.0 / fit_samples) / force_amplitude_N[i];
}

double DynamicRecord::phase_sd_deg(std::size_t i) const {
  return force_noise_sd_N[i] * std::sqrt(2.0 / fit_samples) / force_amplitude_N[i] * 180.0 / std::numbers::pi;
}

double displacement_amplitude_mm(double acceleration_peak_to_peak_m_s2, double frequency_Hz) {
  const double omega = 2.0 * std::numbers::pi * frequency_Hz;
  return 0.5 * acceleration_peak_to_peak_m_s2 / (omega * omega) * 1000.0;
}

SineFit fit_sine(const std::vector<double>& time_s, const std::vector<double>& y, double frequency_Hz) {
  const Eigen::Index n = static_cast<Eigen::Index>(time_s.size());
  if (n < 4 || y.size() != time_s.size()) throw std::invalid_argument("fit_sine: need >= 4 samples of t and y");
  const double omega = 2.0 * std::numbers::pi * frequency_Hz;
  const double t0 = time_s.front();
  Eigen::MatrixXd basis(n, 4);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = time_s[k];
    basis.row(k) << std::sin(omega * t), std::cos(omega * t), 1.0, t - t0;
    rhs(k) = y[k];
  }
  const Eigen::Vector4d c = basis.colPivHouseholderQr().solve(rhs);
  return {c(0), c(1), c(2) - c(3) * t0, c(3)};
}

QuasiStaticRecord run_quasi_static(const BaseFoam& foam, const std::vector<EffectSpec>& effects,
                                   const Specimen& specimen, const QuasiStaticProtocol& p) {
  FoamSpecimen foam_specimen(foam, effects);
  const double H = specimen.thickness_mm;
  const double peak_mm = p.max_strain * H, speed_mm_s = p.rate_mm_min / 60.0;
  const double ramp_s = peak_mm / speed_mm_s;
  const int ramp_samples = static_cast<int>(std::ceil(ramp_s * p.sample_hz - 1e-9));
  const int hold_samples = static_cast<int>(std::ceil(p.hold_s * p.sample_hz - 1e-9));
  const double ramp_dt = ramp_s / ramp_samples;
  const int ramp_sub = substeps_for(peak_mm / ramp_samples);

  QuasiStaticRecord rec;
  double t = 0.0, u = 0.0;
  rec.time_s.push_back(0.0);
  rec.displacement_mm.push_back(0.0);
  rec.force_N.push_back(0.0);
  // One sample interval of `substeps` steps from u to u_end; false when the platen lifts off on the way.
  auto advance = [&](double u_end, double interval_s, int substeps, bool unloading) {
    const double u_start = u;
    for (int k = 1; k <= substeps; ++k) {
      const double u_k = u_start + (u_end - u_start) * k / substeps;
      const double stress_kPa = foam_specimen.step(u_k / H, interval_s / substeps);
      if (unloading && u_k > 1e-9 && stress_kPa <= 0.0) return false;
      u = u_k;
      if (k == substeps) {
        t += interval_s;
        rec.time_s.push_back(t);
        rec.displacement_mm.push_back(u);
        rec.force_N.push_back(specimen.force_N(stress_kPa));
      }
    }
    return true;
  };
  for (int i = 1; i <= ramp_samples; ++i) advance(peak_mm * i / ramp_samples, ramp_dt, ramp_sub, false);
  if (hold_samples > 0) {
    const double hold_dt = p.hold_s / hold_samples;
    for (int i = 1; i <= hold_samples; ++i) advance(peak_mm, hold_dt, std::max(1, ramp_sub), false);
  }
  for (int i = ramp_samples - 1; i >= 0; --i)
    if (!advance(peak_mm * i / ramp_samples, ramp_dt, ramp_sub, true)) {
      rec.lifted_off = true;
      break;
    }
  return rec;
}

void add_quasi_static_noise(QuasiStaticRecord& record, const NoiseModel& noise, Random& random) {
  for (double& f : record.force_N) f += noise.force_sd_N(f) * random.normal();
}

DynamicRecord run_dynamic(const BaseFoam& foam, const std::vector<EffectSpec>& effects, const Specimen& specimen,
                          const DynamicProtocol& p, const NoiseModel& noise, Random* random) {
  FoamSpecimen foam_specimen(foam, effects);
  const double H = specimen.thickness_mm, area = specimen.area_mm2();
  const double preload_mm = p.preload_strain * H;
  // Preload ramp and dwell.
  const int ramp_steps = substeps_for(preload_mm);
  const double ramp_dt = preload_mm / (p.preload_rate_mm_min / 60.0) / ramp_steps;
  for (int k = 1; k <= ramp_steps; ++k) foam_specimen.step(preload_mm * k / ramp_steps / H, ramp_dt);
  const int dwell_steps = static_cast<int>(std::ceil(p.dwell_s / 0.05));  // none without a dwell
  for (int k = 0; k < dwell_steps; ++k) foam_specimen.step(p.preload_strain, p.dwell_s / dwell_steps);

  DynamicRecord rec;
  const int steps = p.cycles * p.steps_per_cycle, fit_from = (p.cycles - p.fit_cycles) * p.steps_per_cycle;
  rec.fit_samples = steps - fit_from;
  for (double f : p.frequencies_Hz) {
    const double omega = 2.0 * std::numbers::pi * f, dt = 1.0 / (f * p.steps_per_cycle);
    const double U = displacement_amplitude_mm(p.acceleration_peak_to_peak_m_s2, f);
    std::vector<double> time_s, displacement_mm, force_N;
    const int sub = std::max(1, p.integration_substeps);
    for (int k = 1; k <= steps; ++k) {
      const double t = k * dt, u = preload_mm + U * std::sin(omega * t);
      double stress_kPa = 0.0;
      for (int j = 1; j <= sub; ++j) {  // sub = 1: t_j = t, u_j = u
        const double t_j = ((k - 1) + static_cast<double>(j) / sub) * dt;
        stress_kPa = foam_specimen.step((preload_mm + U * std::sin(omega * t_j)) / H, dt / sub);
      }
      if (k <= fit_from) continue;
      time_s.push_back(t);
      displacement_mm.push_back(u);
      force_N.push_back(specimen.force_N(stress_kPa));
    }
    const double amplitude_N = std::abs(fit_sine(time_s, force_N, f).phasor());
    double sum_variance = 0.0;
    for (double& F : force_N) {
      const double sd = noise.dynamic_relative_to_reading ? noise.force_sd_N(F) : noise.force_sd_N(amplitude_N);
      sum_variance += sd * sd;
      if (random) F += sd * random->normal();
    }
    const std::complex<double> stress_phasor = fit_sine(time_s, force_N, f).phasor() / area;
    const std::complex<double> strain_phasor = fit_sine(time_s, displacement_mm, f).phasor() / H;
    const std::complex<double> modulus_kPa = stress_phasor / strain_phasor * 1000.0;
    rec.frequency_Hz.push_back(f);
    rec.dynamic_modulus_kPa.push_back(std::abs(modulus_kPa));
    rec.phase_deg.push_back(std::arg(modulus_kPa) * 180.0 / std::numbers::pi);
    rec.force_amplitude_N.push_back(amplitude_N);
    rec.force_noise_sd_N.push_back(std::sqrt(sum_variance / force_N.size()));
  }
  return rec;
}

}  // namespace foreign_bench
