#include "solver/case/case_spec.hpp"

#include <algorithm>
#include <cmath>

namespace cushion::solver {

double Amplitude::at(double t) const {
  if (kind == Kind::sine) return t < start ? 0.0 : std::sin(2.0 * M_PI * frequency * (t - start));
  if (t <= time.front()) return value.front();
  if (t >= time.back()) return value.back();
  const auto upper = std::upper_bound(time.begin(), time.end(), t);  // first time > t
  const std::size_t i = static_cast<std::size_t>(upper - time.begin());
  const double w = (t - time[i - 1]) / (time[i] - time[i - 1]);
  return (1.0 - w) * value[i - 1] + w * value[i];
}

double Amplitude::rate(double t) const {
  const double w = 2.0 * M_PI * frequency;
  if (kind == Kind::sine) return t < start ? 0.0 : w * std::cos(w * (t - start));
  if (t <= time.front() || t > time.back()) return 0.0;
  const auto upper = std::lower_bound(time.begin(), time.end(), t);  // first time >= t: segment ending at t
  const std::size_t i = static_cast<std::size_t>(upper - time.begin());
  return (value[i] - value[i - 1]) / (time[i] - time[i - 1]);
}

double Amplitude::second_rate(double t) const {
  const double w = 2.0 * M_PI * frequency;
  if (kind == Kind::sine) return t < start ? 0.0 : -w * w * std::sin(w * (t - start));
  return 0.0;
}

double ramped_value(double value, const std::optional<std::string>& amplitude,
                    const std::map<std::string, Amplitude>& amplitudes, double start_value, double t_step,
                    double period, double t_start) {
  if (amplitude) {
    const Amplitude& a = amplitudes.at(*amplitude);
    return value * a.at(a.total_time ? t_start + t_step : t_step);
  }
  return start_value + (value - start_value) * std::clamp(t_step / period, 0.0, 1.0);
}

PrescribedMotion prescribed_motion(const BoundarySpec& bc, const std::map<std::string, Amplitude>& amplitudes,
                                   double start_value, double t_step, double period, double t_start) {
  if (bc.kind != BoundarySpec::Kind::displacement) return {};
  if (bc.amplitude) {
    const Amplitude& a = amplitudes.at(*bc.amplitude);
    const double t = a.total_time ? t_start + t_step : t_step;
    return {bc.value * a.at(t), bc.value * a.rate(t), bc.value * a.second_rate(t)};
  }
  const bool ramping = t_step > 0.0 && t_step <= period;
  return {ramped_value(bc.value, std::nullopt, amplitudes, start_value, t_step, period, t_start),
          ramping ? (bc.value - start_value) / period : 0.0, 0.0};
}

double prescribed_value(const BoundarySpec& bc, const std::map<std::string, Amplitude>& amplitudes,
                        double start_value, double t_step, double period, double t_start) {
  return prescribed_motion(bc, amplitudes, start_value, t_step, period, t_start).u;
}

std::string to_string(HistoryQuantity q) {
  static const char* names[] = {"U1", "U2", "U3", "RF1", "RF2", "RF3"};
  return names[static_cast<int>(q)];
}

std::string history_column(const std::string& set, HistoryQuantity q) {
  const bool force = static_cast<int>(q) >= 3;
  return set + "." + to_string(q) + (force ? "_N" : "_mm");
}

std::vector<std::string> history_columns(const CaseSpec& spec) {
  std::vector<std::string> columns;
  for (const StepSpec& step : spec.steps)
    for (const HistoryRequest& request : step.output.history)
      for (HistoryQuantity q : request.quantities) {
        const std::string name = history_column(request.set, q);
        if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
      }
  return columns;
}

}  // namespace cushion::solver
