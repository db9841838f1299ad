#pragma once
// Synthetic quasi-static records for the calibration tests: sigma = f(eps) + sigma_v(t) along a
// strain-controlled triangle with hold, built with the closed-form hereditary stress.
#include <cmath>
#include <vector>

#include "calibration/difference_stress.hpp"

namespace cushion::calibration::testing {

/// Elastic curve used by the synthetic records [MPa], compression positive.
inline double elastic_f(double e) { return 0.005 * e + 0.02 * std::pow(e, 4); }

/// Two modes that are well identifiable over a 30 s test.
inline std::vector<HereditaryMode> known_modes() {
  return {{cplx(-0.0020, 0.0030), cplx(0.03, 0.02)}, {cplx(0.0040, -0.0010), cplx(0.30, 0.10)}};
}

/// eps: 0 -> 0.75 in 30 s, hold, back in 30 s, sampled every dt; sigma = f(eps) + sigma_v.
inline StressStrainRecord synthetic_record(const std::vector<HereditaryMode>& modes, double hold = 2.0,
                                           double dt = 0.05) {
  const ProtocolHistory h = triangle_history(0.75, 0.025, hold, dt);
  StressStrainRecord r;
  r.source = "synthetic.csv";
  r.time = h.time;
  r.strain = h.strain;
  const auto sv = hereditary_stress(h.time, h.strain, modes, h.time);
  for (std::size_t i = 0; i < h.time.size(); ++i) r.stress.push_back(elastic_f(h.strain[i]) + sv[i]);
  return r;
}

}  // namespace cushion::calibration::testing
