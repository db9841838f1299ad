#include "material/effect_mullins.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

MullinsEffect::MullinsEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> energy_base,
                             MullinsParameters parameters)
    : EffectDecorator(std::move(inner), 1), energy_base_(std::move(energy_base)), p_(parameters) {
  if (!energy_base_) throw std::invalid_argument("mullins: no elastic base for the energy");
  if (!(p_.r > 1.0) || !std::isfinite(p_.r)) throw std::invalid_argument("mullins: r must be > 1");
  if (!(p_.m > 0.0) || !std::isfinite(p_.m)) throw std::invalid_argument("mullins: m must be > 0");
  if (!(p_.beta >= 0.0) || !std::isfinite(p_.beta)) throw std::invalid_argument("mullins: beta must be >= 0");
}

double MullinsEffect::eta(double W, double W_max) const {
  return 1.0 - std::erf((W_max - W) / (p_.m + p_.beta * W_max)) / p_.r;
}

PointResponse MullinsEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                       std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  const ElasticEval e = energy_base_->evaluate(F_new);
  combine_status(r, e.status, e.message);
  if (r.status == Status::failed) return r;
  const double W_max_old = own(state_old)[0];
  if (e.W >= W_max_old) {  // first loading: eta = 1 identically, W_max follows W
    own(state_new)[0] = e.W;
    return r;
  }
  own(state_new)[0] = W_max_old;
  const double scale = p_.m + p_.beta * W_max_old, z = (W_max_old - e.W) / scale;
  const double eta_value = 1.0 - std::erf(z) / p_.r;
  // d eta / dW = (2 / (r sqrt(pi) scale)) e^{-z^2}, dW/dE = S_base.
  const double deta_dW = 2.0 * std::exp(-z * z) / (p_.r * std::sqrt(std::numbers::pi) * scale);
  r.dS_dE = eta_value * r.dS_dE + deta_dW * r.S * e.S.transpose();
  r.S *= eta_value;
  return r;
}

Vec6 MullinsEffect::viscous_stress(const Mat3& F, std::span<const double> state) const {
  return eta(energy_base_->evaluate(F).W, own(state)[0]) * EffectDecorator::viscous_stress(F, state);
}

Mat6c MullinsEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const ElasticEval e = energy_base_->evaluate(F_base);
  const double deta_dW = 2.0 / (p_.r * std::sqrt(std::numbers::pi) * (p_.m + p_.beta * e.W));
  const Mat6 softening = deta_dW * e.S * e.S.transpose();
  return inner_->complex_tangent(F_base, omega) + softening.cast<std::complex<double>>();
}

std::string MullinsEffect::describe() const {
  std::ostringstream o;
  o << "Mullins softening (r = " << p_.r << ", m = " << p_.m * 1e3 << " kPa, beta = " << p_.beta << ") over "
    << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
