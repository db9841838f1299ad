#include "material/effect_stiffness_damping.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

StiffnessDampingEffect::StiffnessDampingEffect(std::shared_ptr<const Material> inner, const Hyperelastic& elastic_base,
                                               double beta_s)
    : EffectDecorator(std::move(inner), 0), C0_(elastic_base.evaluate(Mat3::Identity()).dS_dE), beta_(beta_s) {
  if (!(beta_ >= 0.0) || !std::isfinite(beta_)) throw std::invalid_argument("stiffness_damping: beta_s must be >= 0");
}

PointResponse StiffnessDampingEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                                std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed || dt == 0.0) return r;
  const Vec6 E_rate = (to_voigt_strain(green_lagrange(F_new)) - to_voigt_strain(green_lagrange(F_old))) / dt;
  r.S += beta_ * C0_ * E_rate;
  r.dS_dE += (beta_ / dt) * C0_;
  return r;
}

Mat6c StiffnessDampingEffect::complex_tangent(const Mat3& F_base, double omega) const {
  return inner_->complex_tangent(F_base, omega) + std::complex<double>(0.0, omega * beta_) * C0_.cast<std::complex<double>>();
}

std::string StiffnessDampingEffect::describe() const {
  std::ostringstream o;
  o << "stiffness-proportional damping (beta_s = " << beta_ << " s) over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
