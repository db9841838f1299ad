#include "material/calibration/uniaxial_model.hpp"

#include <stdexcept>

namespace cushion::calibration {

void prony_recursion(double dt, double tau, double& decay, double& weight) {
  // Same factors as material/viscoelastic.cpp (expm1 form; both 1 at x = 0, the instantaneous jump).
  const double x = dt / tau;
  if (x == 0.0) {
    decay = weight = 1.0;
    return;
  }
  decay = std::exp(-x);
  weight = -std::expm1(-x) / x;
}

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
      double decay = 0.0, weight = 0.0;
      prony_recursion(dt, t, decay, weight);
      p.decay.push_back(decay);
      p.weight.push_back(weight);
    }
  }
  return p;
}

}  // namespace cushion::calibration
