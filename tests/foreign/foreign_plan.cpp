// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/: noise-free
// records of a test plan and their distance in noise units.
#include "foreign_plan.hpp"

#include <algorithm>
#include <cmath>

namespace foreign_bench {

namespace {

double rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / v.size());
}

double quasi_static_ratio(const QuasiStaticRecord& base, const QuasiStaticRecord& with, const NoiseModel& noise) {
  const std::size_t n = std::min(base.force_N.size(), with.force_N.size());
  std::vector<double> difference_N(n), sd_N(n);
  for (std::size_t k = 0; k < n; ++k) {
    difference_N[k] = with.force_N[k] - base.force_N[k];
    sd_N[k] = noise.force_sd_N(base.force_N[k]);
  }
  return rms(difference_N) / rms(sd_N);
}

double dynamic_ratio(const DynamicRecord& base, const DynamicRecord& with) {
  const std::size_t n = base.frequency_Hz.size();
  std::vector<double> d_modulus(n), sd_modulus(n), d_phase(n), sd_phase(n);
  for (std::size_t i = 0; i < n; ++i) {
    d_modulus[i] = with.dynamic_modulus_kPa[i] - base.dynamic_modulus_kPa[i];
    d_phase[i] = with.phase_deg[i] - base.phase_deg[i];
    sd_modulus[i] = base.modulus_sd_kPa(i);
    sd_phase[i] = base.phase_sd_deg(i);
  }
  return std::max(rms(d_modulus) / rms(sd_modulus), rms(d_phase) / rms(sd_phase));
}

}  // namespace

PlanRecords simulate_noise_free(const BaseFoam& foam, const std::vector<EffectSpec>& effects, const TestPlan& plan) {
  PlanRecords r;
  for (const auto& p : plan.quasi_static) r.quasi_static.push_back(run_quasi_static(foam, effects, plan.specimen, p));
  for (const auto& p : plan.dynamic) r.dynamic.push_back(run_dynamic(foam, effects, plan.specimen, p, plan.noise, nullptr));
  return r;
}

std::map<std::string, double> ratios_between(const PlanRecords& base, const PlanRecords& with, const TestPlan& plan) {
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < plan.quasi_static.size(); ++i)
    out[plan.quasi_static[i].name] = quasi_static_ratio(base.quasi_static[i], with.quasi_static[i], plan.noise);
  for (std::size_t i = 0; i < plan.dynamic.size(); ++i)
    out[plan.dynamic[i].name] = dynamic_ratio(base.dynamic[i], with.dynamic[i]);
  return out;
}

Eigen::VectorXd normalised_differences(const PlanRecords& model, const PlanRecords& data, const TestPlan& plan) {
  std::vector<double> r;
  for (std::size_t i = 0; i < plan.quasi_static.size(); ++i) {
    const auto& m = model.quasi_static[i].force_N;
    const auto& d = data.quasi_static[i].force_N;
    for (std::size_t k = 0; k < d.size(); ++k)
      r.push_back(((k < m.size() ? m[k] : 0.0) - d[k]) / plan.noise.force_sd_N(d[k]));
  }
  for (std::size_t i = 0; i < plan.dynamic.size(); ++i) {
    const DynamicRecord& m = model.dynamic[i];
    const DynamicRecord& d = data.dynamic[i];
    for (std::size_t f = 0; f < d.frequency_Hz.size(); ++f) {
      r.push_back((m.dynamic_modulus_kPa[f] - d.dynamic_modulus_kPa[f]) / d.modulus_sd_kPa(f));
      r.push_back((m.phase_deg[f] - d.phase_deg[f]) / d.phase_sd_deg(f));
    }
  }
  return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

}  // namespace foreign_bench
