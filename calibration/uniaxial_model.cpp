#include "calibration/uniaxial_model.hpp"

#include <stdexcept>

#include "material/viscoelastic.hpp"

namespace cushion::calibration {

UniaxialPath make_uniaxial_path(const std::vector<double>& time, const std::vector<double>& strain,
                                const std::vector<double>& tau) {
  if (time.size() != strain.size() || time.empty())
    throw std::invalid_argument("make_uniaxial_path: time and strain must be non-empty and of equal length");
  UniaxialPath p;
  p.time = time;
  p.modes = tau.size();
  for (double e : strain) p.stretch.push_back(1.0 - e);
  for (std::size_t n = 1; n < time.size(); ++n) {
    const double dt = time[n] - time[n - 1];
    if (!(dt > 0.0)) throw std::invalid_argument("make_uniaxial_path: time must be strictly increasing");
    for (double t : tau) {
      const material::PronyRecursion q = material::prony_recursion(dt, t);  // the solver's recursion
      p.decay.push_back(q.decay);
      p.weight.push_back(q.weight);
    }
  }
  return p;
}

}  // namespace cushion::calibration
