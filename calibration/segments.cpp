#include "calibration/segments.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/input_error.hpp"

namespace cushion::calibration {
namespace {

std::string where(const StressStrainRecord& r, std::size_t i) {
  std::ostringstream s;
  s << r.source << ": ";
  if (i < r.line.size() && r.line[i] > 0) s << "line " << r.line[i] << ": ";
  else s << "sample " << i << " (t = " << r.time[i] << " s): ";
  return s.str();
}

}  // namespace

StressStrainRecord to_nominal(const std::string& source, const std::vector<double>& time,
                              const std::vector<double>& displacement, const std::vector<double>& force,
                              const Specimen& specimen, const std::vector<int>& line) {
  StressStrainRecord r;
  r.source = source;
  r.time = time;
  r.line = line;
  r.strain.resize(time.size());
  r.stress.resize(time.size());
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (i > 0 && !(time[i] > time[i - 1]))
      throw InputError(where(r, i) + "column time_s: time must be strictly increasing");
    r.strain[i] = displacement[i] / specimen.thickness;
    r.stress[i] = force[i] / specimen.area();
  }
  return r;
}

double noise_level(const std::vector<double>& x) {
  if (x.size() < 3) return 0.0;
  std::vector<double> d2(x.size() - 2);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) d2[i - 1] = std::abs(x[i + 1] - 2.0 * x[i] + x[i - 1]);
  auto mid = d2.begin() + d2.size() / 2;
  std::nth_element(d2.begin(), mid, d2.end());
  return 1.4826 * *mid / std::sqrt(6.0);
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  const std::size_t k = std::upper_bound(x.begin(), x.end(), xq) - x.begin() - 1;
  const double w = (xq - x[k]) / (x[k + 1] - x[k]);
  return (1.0 - w) * y[k] + w * y[k + 1];
}

MonotoneBranch monotone_branch(const std::vector<double>& x, const std::vector<double>& y, std::size_t a, std::size_t b,
                               bool loading) {
  MonotoneBranch t;
  for (std::size_t i = a; i <= b; ++i) {
    if (!t.x.empty() && (loading ? x[i] <= t.x.back() : x[i] >= t.x.back())) continue;
    t.x.push_back(x[i]);
    t.y.push_back(y[i]);
  }
  if (!loading) {
    std::reverse(t.x.begin(), t.x.end());
    std::reverse(t.y.begin(), t.y.end());
  }
  return t;
}

Segments detect_segments(const StressStrainRecord& r, const SegmentOptions& o) {
  const std::size_t n = r.time.size();
  if (n < std::size_t(2 * o.min_points + 1))
    throw InputError(r.source + ": too few points (" + std::to_string(n) + "): need at least " +
                     std::to_string(2 * o.min_points + 1) + " for loading and unloading branches");
  Segments s;
  const std::size_t i_max = std::max_element(r.strain.begin(), r.strain.end()) - r.strain.begin();
  s.peak_strain = r.strain[i_max];
  s.peak_stress = *std::max_element(r.stress.begin(), r.stress.end());
  if (!(s.peak_strain > 0.0)) throw InputError(r.source + ": no compression: the maximum displacement is not positive");
  s.strain_noise = noise_level(r.strain);
  s.stress_noise = noise_level(r.stress);
  const double mono_tol = std::max(o.noise_factor * s.strain_noise, 1e-6 * s.peak_strain);
  const double peak_tol = std::max(mono_tol, o.hold_tolerance * s.peak_strain);

  s.load_begin = 0;
  s.load_end = 0;
  while (r.strain[s.load_end] < s.peak_strain - peak_tol) ++s.load_end;
  s.unload_begin = n - 1;
  while (r.strain[s.unload_begin] < s.peak_strain - peak_tol) --s.unload_begin;
  s.hold_duration = r.time[s.unload_begin] - r.time[s.load_end];

  // Loading must be monotonic up to the noise tolerance.
  double running_max = r.strain[0];
  for (std::size_t i = 1; i <= s.load_end; ++i) {
    if (r.strain[i] < running_max - mono_tol) {
      std::ostringstream m;
      m << where(r, i) << "non-monotonic loading: strain drops by " << running_max - r.strain[i]
        << " below its running maximum (tolerance " << mono_tol << ", 6 x noise) before the peak strain "
        << s.peak_strain << " is reached";
      throw InputError(m.str());
    }
    running_max = std::max(running_max, r.strain[i]);
  }
  if (s.load_end - s.load_begin + 1 < std::size_t(o.min_points))
    throw InputError(r.source + ": too few points on the loading branch (" +
                     std::to_string(s.load_end - s.load_begin + 1) + ")");
  const double final_drop = s.peak_strain - *std::min_element(r.strain.begin() + s.unload_begin, r.strain.end());
  const bool unloaded = r.stress.back() <= o.unloaded_stress_fraction * s.peak_stress;
  if (s.unload_begin + 1 >= n || (final_drop < o.min_unloading_drop * s.peak_strain && !unloaded)) {
    std::ostringstream m;
    m << r.source << ": no unloading branch: after the peak strain " << s.peak_strain << " the strain returns by only "
      << final_drop << " (need " << o.min_unloading_drop * 100 << " % of the peak, or the stress down to "
      << o.unloaded_stress_fraction * 100 << " % of its peak by the end)";
    throw InputError(m.str());
  }

  // Unloading ends at the last sample, or where the force reaches ~0 (lift-off from the platen).
  const double zero_force = std::max(o.lift_off_fraction * s.peak_stress, o.noise_factor * s.stress_noise);
  s.unload_end = n - 1;
  for (std::size_t i = s.unload_begin + 1; i < n; ++i)
    if (r.stress[i] <= zero_force) {
      s.unload_end = i;
      break;
    }
  if (s.unload_end < n - 1 && r.strain[s.unload_end] > std::max(o.lift_off_strain * s.peak_strain, mono_tol)) {
    s.lift_off = true;
    s.lift_off_strain = r.strain[s.unload_end];
    std::ostringstream m;
    m << r.source << ": unloading truncated at strain " << s.lift_off_strain << " (t = " << r.time[s.unload_end]
      << " s): the force is ~0 there (foam lifted off the platen); later samples are ignored";
    s.warnings.push_back(m.str());
  }
  double running_min = r.strain[s.unload_begin];
  for (std::size_t i = s.unload_begin + 1; i <= s.unload_end; ++i) {
    if (r.strain[i] > running_min + mono_tol) {
      std::ostringstream m;
      m << where(r, i) << "non-monotonic unloading: strain rises by " << r.strain[i] - running_min
        << " above its running minimum (tolerance " << mono_tol << ")";
      throw InputError(m.str());
    }
    running_min = std::min(running_min, r.strain[i]);
  }
  if (s.unload_end - s.unload_begin + 1 < std::size_t(o.min_points))
    throw InputError(r.source + ": too few points on the unloading branch (" +
                     std::to_string(s.unload_end - s.unload_begin + 1) + ")");
  return s;
}

}  // namespace cushion::calibration
