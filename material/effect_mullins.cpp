#include "material/effect_mullins.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

MullinsEffect::MullinsEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> energy_base,
                             MullinsParameters parameters)
    : EffectDecorator(inner, 1),
      energy_base_(std::move(energy_base)),
      memory_(parameters.relaxation_share > 0.0 ? std::dynamic_pointer_cast<const Viscoelastic>(inner) : nullptr),
      p_(parameters) {
  if (!energy_base_) throw std::invalid_argument("mullins: no elastic base for the energy");
  if (!(p_.relaxation_share >= 0.0 && p_.relaxation_share <= 1.0))
    throw std::invalid_argument("mullins: relaxation_share must lie in [0, 1]");
  if (p_.relaxation_share > 0.0 && !memory_)
    throw std::invalid_argument(
        "mullins: relaxation_share > 0 needs a viscoelastic (Prony) material with mullins as the first effect");
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
  if (memory_) drive_memory_with_softened_stress(r, e, eta_value, deta_dW * e.S, dt, state_new);
  // The softening left outside the memory: eta^(1-w) (w = 0: eta, the same operations as without a share).
  const double w = p_.relaxation_share, outer = w == 0.0 ? eta_value : std::pow(eta_value, 1.0 - w);
  const double douter_deta = w == 0.0 ? 1.0 : (1.0 - w) * std::pow(eta_value, -w);
  r.dS_dE = outer * r.dS_dE + (douter_deta * deta_dW) * r.S * e.S.transpose();
  r.S *= outer;
  return r;
}

void MullinsEffect::drive_memory_with_softened_stress(PointResponse& r, const ElasticEval& e, double eta_value,
                                                      const Vec6& deta_dE, double dt,
                                                      std::span<double> state_new) const {
  const double w = p_.relaxation_share, zeta = std::pow(eta_value, w);
  const Vec6 dzeta_dE = w * std::pow(eta_value, w - 1.0) * deta_dE;
  // The Viscoelastic's state starts with the long-term stress it stored (S_e): store zeta S_e there, and let the
  // memory take the difference as if the long-term stress had risen by (zeta - 1) S_e more.
  Eigen::Map<Vec6>(state_new.data()) = zeta * e.S;
  const double k = 1.0 + memory_->add_to_memory(state_new, dt, (zeta - 1.0) * e.S);  // 1 + sum a_i q_i
  r.dS_dE += k * ((zeta - 1.0) * e.dS_dE + e.S * dzeta_dE.transpose());
  r.S += (zeta - 1.0) * k * e.S;
}

Vec6 MullinsEffect::viscous_stress(const Mat3& F, std::span<const double> state) const {
  const double eta_value = eta(energy_base_->evaluate(F).W, own(state)[0]);
  return std::pow(eta_value, 1.0 - p_.relaxation_share) * EffectDecorator::viscous_stress(F, state);
}

Mat6c MullinsEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const ElasticEval e = energy_base_->evaluate(F_base);
  const double deta_dW = 2.0 / (p_.r * std::sqrt(std::numbers::pi) * (p_.m + p_.beta * e.W));
  const Mat6 softening = deta_dW * e.S * e.S.transpose();
  const double w = p_.relaxation_share;
  const std::complex<double> share = memory_ ? w * prony_complex_factor(memory_->terms(), omega) + (1.0 - w) : 1.0;
  return inner_->complex_tangent(F_base, omega) + share * softening.cast<std::complex<double>>();
}

std::string MullinsEffect::describe() const {
  std::ostringstream o;
  o << "Mullins softening (r = " << p_.r << ", m = " << p_.m * 1e3 << " kPa, beta = " << p_.beta;
  if (p_.relaxation_share > 0.0) o << ", relaxation share " << p_.relaxation_share;
  o << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
