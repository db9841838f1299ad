#include "material/effect_stiffness_damping.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {
std::shared_ptr<const Hyperelastic> checked(std::shared_ptr<const Hyperelastic> base) {
  if (!base) throw std::invalid_argument("stiffness_damping: no elastic base");
  return base;
}
}  // namespace

StiffnessDampingEffect::StiffnessDampingEffect(std::shared_ptr<const Material> inner,
                                               std::shared_ptr<const Hyperelastic> elastic_base, double beta_s,
                                               double current_share)
    : EffectDecorator(std::move(inner), 0),
      base_(checked(std::move(elastic_base))),
      C0_(base_->evaluate(Mat3::Identity()).dS_dE),
      beta_(beta_s),
      share_(current_share) {
  if (!(beta_ >= 0.0) || !std::isfinite(beta_)) throw std::invalid_argument("stiffness_damping: beta_s must be >= 0");
  if (!(share_ >= 0.0 && share_ <= 1.0))
    throw std::invalid_argument("stiffness_damping: current_tangent_share must lie in [0, 1]");
}

Mat6 StiffnessDampingEffect::damping_tangent(const Mat3& F) const {
  if (share_ == 0.0) return C0_;
  return (1.0 - share_) * C0_ + share_ * base_->evaluate(F).dS_dE;
}

PointResponse StiffnessDampingEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                                std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed || dt == 0.0) return r;
  const Vec6 E_rate = (to_voigt_strain(green_lagrange(F_new)) - to_voigt_strain(green_lagrange(F_old))) / dt;
  const Mat6 C_d = damping_tangent(F_old);
  r.S += beta_ * C_d * E_rate;
  r.dS_dE += (beta_ / dt) * C_d;
  return r;
}

Mat6c StiffnessDampingEffect::complex_tangent(const Mat3& F_base, double omega) const {
  return inner_->complex_tangent(F_base, omega) +
         std::complex<double>(0.0, omega * beta_) * damping_tangent(F_base).cast<std::complex<double>>();
}

std::string StiffnessDampingEffect::describe() const {
  std::ostringstream o;
  o << "stiffness-proportional damping (beta_s = " << beta_ << " s";
  if (share_ > 0.0) o << ", current-tangent share " << share_;
  o << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
