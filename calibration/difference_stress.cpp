#include "calibration/difference_stress.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cushion::calibration {

StrainPairs pair_loading_unloading(const StressStrainRecord& r, const Segments& s, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("pair_loading_unloading: dt must be positive");
  StrainPairs p;
  const double t0 = r.time[s.load_begin], t_end = r.time[s.load_end];
  const double eps_unload_min = r.strain[s.unload_end];
  // Loading branch as a function of time (only its samples), unloading searched by strain.
  for (int i = 1;; ++i) {
    const double t1 = t0 + i * dt;
    if (t1 > t_end + 1e-9 * dt) break;
    // interpolate strain on the loading samples
    const auto lb = r.time.begin() + s.load_begin, le = r.time.begin() + s.load_end + 1;
    std::size_t k = std::upper_bound(lb, le, t1) - r.time.begin();
    k = std::clamp<std::size_t>(k == 0 ? 0 : k - 1, s.load_begin, s.load_end > s.load_begin ? s.load_end - 1 : s.load_begin);
    const double w = std::clamp((t1 - r.time[k]) / (r.time[k + 1] - r.time[k]), 0.0, 1.0);
    const double e1 = (1.0 - w) * r.strain[k] + w * r.strain[k + 1];
    if (e1 < eps_unload_min) continue;
    double t2 = r.time[s.unload_begin];
    if (e1 < r.strain[s.unload_begin]) {
      bool found = false;
      for (std::size_t j = s.unload_begin; j < s.unload_end; ++j) {
        const double a = r.strain[j], b = r.strain[j + 1];
        if (a >= e1 && e1 >= b && a > b) {
          t2 = r.time[j] + (a - e1) / (a - b) * (r.time[j + 1] - r.time[j]);
          found = true;
          break;
        }
      }
      if (!found) continue;
    }
    p.t1.push_back(t1);
    p.t2.push_back(t2);
    p.strain.push_back(e1);
  }
  return p;
}

std::vector<double> measured_difference_stress(const StressStrainRecord& r, const StrainPairs& p) {
  std::vector<double> d(p.t1.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = interpolate(r.time, r.stress, p.t1[i]) - interpolate(r.time, r.stress, p.t2[i]);
  return d;
}

std::vector<double> model_difference_stress(const StressStrainRecord& r, const StrainPairs& p,
                                            const std::vector<HereditaryMode>& modes) {
  std::vector<double> q = p.t1;
  q.insert(q.end(), p.t2.begin(), p.t2.end());
  const auto sv = hereditary_stress(r.time, r.strain, modes, q);
  const std::size_t n = p.t1.size();
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = sv[i] - sv[n + i];
  return d;
}

double rmse(const std::vector<double>& model, const std::vector<double>& measured) {
  if (model.size() != measured.size() || model.empty()) throw std::invalid_argument("rmse: size mismatch or empty");
  double s = 0.0;
  for (std::size_t i = 0; i < model.size(); ++i) s += (model[i] - measured[i]) * (model[i] - measured[i]);
  return std::sqrt(s / double(model.size()));
}

ProtocolHistory triangle_history(double peak_strain, double rate, double hold, double dt) {
  if (!(peak_strain > 0.0 && rate > 0.0 && hold >= 0.0 && dt > 0.0))
    throw std::invalid_argument("triangle_history: need peak_strain, rate, dt > 0 and hold >= 0");
  const double T = peak_strain / rate;
  ProtocolHistory h;
  auto add_segment = [&](double t_start, double duration, double e_start, double e_end) {
    const int n = std::max(1, int(std::ceil(duration / dt - 1e-9)));
    for (int i = 1; i <= n; ++i) {
      h.time.push_back(t_start + duration * i / n);
      h.strain.push_back(e_start + (e_end - e_start) * double(i) / n);
    }
  };
  h.time.push_back(0.0);
  h.strain.push_back(0.0);
  add_segment(0.0, T, 0.0, peak_strain);
  if (hold > 0.0) add_segment(T, hold, peak_strain, peak_strain);
  add_segment(T + hold, T, peak_strain, 0.0);
  return h;
}

ProtocolCurve protocol_curve(const std::vector<HereditaryMode>& modes, double thickness, double speed_mm_per_min,
                             double peak_strain, double hold, double dt) {
  ProtocolCurve c;
  const double rate = speed_mm_per_min / 60.0 / thickness;
  c.history = triangle_history(peak_strain, rate, hold, dt);
  c.sigma_v = hereditary_stress(c.history.time, c.history.strain, modes, c.history.time);
  StressStrainRecord r;
  r.source = "protocol";
  r.time = c.history.time;
  r.strain = c.history.strain;
  r.stress = c.sigma_v;
  Segments s;
  const double T = peak_strain / rate;
  s.load_begin = 0;
  s.load_end = std::lower_bound(r.time.begin(), r.time.end(), T - 1e-9) - r.time.begin();
  s.unload_begin = std::lower_bound(r.time.begin(), r.time.end(), T + hold - 1e-9) - r.time.begin();
  s.unload_end = r.time.size() - 1;
  c.pairs = pair_loading_unloading(r, s, 1.0);
  c.delta_sigma = model_difference_stress(r, c.pairs, modes);
  return c;
}

}  // namespace cushion::calibration
