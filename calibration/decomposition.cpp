#include "calibration/decomposition.hpp"

#include <algorithm>
#include <cmath>

#include "calibration/segments.hpp"

namespace cushion::calibration {

Decomposition decompose(const StressStrainRecord& r, const Segments& s, const std::vector<HereditaryMode>& modes,
                        int pairs_per_branch, int curve_points) {
  Decomposition d;
  for (std::size_t i = s.load_begin; i <= s.unload_end; ++i) {
    d.time.push_back(r.time[i]);
    d.strain.push_back(r.strain[i]);
    d.sigma.push_back(r.stress[i]);
    d.loading.push_back(i <= s.load_end);
  }
  d.sigma_v = hereditary_stress(r.time, r.strain, modes, d.time);
  d.sigma_e.resize(d.time.size());
  for (std::size_t i = 0; i < d.time.size(); ++i) d.sigma_e[i] = d.sigma[i] - d.sigma_v[i];

  // Branch comparison at equal strain.
  const double dt = (r.time[s.load_end] - r.time[s.load_begin]) / std::max(1, pairs_per_branch);
  const StrainPairs p = pair_loading_unloading(r, s, dt);
  std::vector<double> q = p.t1;
  q.insert(q.end(), p.t2.begin(), p.t2.end());
  const auto sv = hereditary_stress(r.time, r.strain, modes, q);
  const std::size_t n = p.t1.size();
  std::vector<double> e_pair(n), se_pair(n);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double se1 = interpolate(r.time, r.stress, p.t1[i]) - sv[i];
    const double se2 = interpolate(r.time, r.stress, p.t2[i]) - sv[n + i];
    sum2 += (se1 - se2) * (se1 - se2);
    e_pair[i] = p.strain[i];
    se_pair[i] = 0.5 * (se1 + se2);
  }
  if (n > 0) {
    d.branch_mismatch = std::sqrt(sum2 / double(n)) / s.peak_stress;
    d.paired_strain_min = *std::min_element(e_pair.begin(), e_pair.end());
    d.paired_strain_max = *std::max_element(e_pair.begin(), e_pair.end());
  }

  // Elastic curve: branch average where paired, loading branch below the paired range.
  std::size_t loaded = 0;  // the leading loading samples
  while (loaded < d.time.size() && d.loading[loaded]) ++loaded;
  const MonotoneBranch load =  // kept increasing through noise
      loaded > 0 ? monotone_branch(d.strain, d.sigma_e, 0, loaded - 1, true) : MonotoneBranch{};
  for (int k = 0; k <= curve_points; ++k) {
    const double e = s.peak_strain * double(k) / curve_points;
    double se = interpolate(load.x, load.y, e);
    if (n > 1 && e >= d.paired_strain_min && e <= d.paired_strain_max) se = interpolate(e_pair, se_pair, e);
    d.elastic.strain.push_back(e);
    d.elastic.stress.push_back(se);
  }
  return d;
}

}  // namespace cushion::calibration
