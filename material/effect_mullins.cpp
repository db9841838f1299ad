#include "material/effect_mullins.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "material/principal_stretch.hpp"

namespace cushion::material {

MullinsEffect::MullinsEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> energy_base,
                             MullinsParameters parameters)
    : EffectDecorator(inner, parameters.damage_limit > 0.0 ? 2 : 1),
      energy_base_(std::move(energy_base)),
      memory_(parameters.relaxation_share > 0.0 ? std::dynamic_pointer_cast<const PronyMemory>(inner) : nullptr),
      p_(parameters) {
  if (!energy_base_) throw std::invalid_argument("mullins: no elastic base for the energy");
  if (!(p_.relaxation_share >= 0.0 && p_.relaxation_share <= 1.0))
    throw std::invalid_argument("mullins: relaxation_share must lie in [0, 1]");
  if (p_.relaxation_share > 0.0 && !memory_)
    throw std::invalid_argument(
        "mullins: relaxation_share > 0 needs a Prony memory beneath: a viscoelastic (Prony) material with mullins as "
        "the first effect, or directly over strain_dependent_prony");
  if (!(p_.r > 1.0) || !std::isfinite(p_.r)) throw std::invalid_argument("mullins: r must be > 1");
  if (!(p_.m > 0.0) || !std::isfinite(p_.m)) throw std::invalid_argument("mullins: m must be > 0");
  if (!(p_.beta >= 0.0) || !std::isfinite(p_.beta)) throw std::invalid_argument("mullins: beta must be >= 0");
  if (!(p_.strain_scale >= 0.0) || !std::isfinite(p_.strain_scale))
    throw std::invalid_argument("mullins: strain_scale must be >= 0");
  if (!(p_.damage_limit >= 0.0 && p_.damage_limit < 1.0))
    throw std::invalid_argument("mullins: damage_limit must lie in [0, 1)");
  if (!(p_.damage_strain > 0.0) || !std::isfinite(p_.damage_strain))
    throw std::invalid_argument("mullins: damage_strain must be > 0");
}

double MullinsEffect::scale(double D_max) const {
  return (p_.strain_scale > 0.0 ? p_.strain_scale : p_.m) + p_.beta * D_max;
}

double MullinsEffect::eta(double D, double D_max) const { return 1.0 - std::erf((D_max - D) / scale(D_max)) / p_.r; }

MullinsEffect::Driver MullinsEffect::driver(const Mat3& F, const ElasticEval& e) const {
  return p_.strain_scale == 0.0 ? Driver{e.W, e.S} : biot_norm(F);
}

MullinsEffect::Driver MullinsEffect::biot_norm(const Mat3& F) {
  // D^2 = tr((U - I)^2) = tr C - 2 tr U + 3, d tr U/dC = U^-1 / 2: dD/dE = (I - U^-1) / D.
  const principal::Stretches st = principal::decompose(F);  // F valid (the base evaluated it): st has no failure
  const Vec3 l = st.s.array().exp();
  const double D = (l.array() - 1.0).matrix().norm();
  if (D == 0.0) return {0.0, Vec6::Zero()};
  const Mat3 U_inv = st.N * l.cwiseInverse().asDiagonal() * st.N.transpose();
  return {D, to_voigt_stress((Mat3::Identity() - U_inv) / D)};
}

PointResponse MullinsEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                       std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  const ElasticEval e = energy_base_->evaluate(F_new);
  combine_status(r, e.status, e.message);
  if (r.status == Status::failed) return r;
  // the Biot strain norm, once: the strain driver's and the damage's
  const std::optional<Driver> n =
      p_.strain_scale > 0.0 || p_.damage_limit > 0.0 ? std::optional<Driver>(biot_norm(F_new)) : std::nullopt;
  Softening f = ogden_roxburgh(p_.strain_scale > 0.0 ? *n : Driver{e.W, e.S}, own(state_old)[0], state_new);
  if (p_.damage_limit > 0.0) damage(f, *n, own(state_old)[1], state_new);
  if (f.first_loading_unchanged) return r;  // eta = 1 identically, no damage
  if (memory_) drive_memory_with_softened_stress(r, F_new, e, f.value, f.d_dE, dt, state_new);
  // The softening left outside the memory: eta^(1-w) (w = 0: eta, the same operations as without a share).
  const double w = p_.relaxation_share, outer = w == 0.0 ? f.value : std::pow(f.value, 1.0 - w);
  const double douter_deta = w == 0.0 ? 1.0 : (1.0 - w) * std::pow(f.value, -w);
  r.dS_dE = outer * r.dS_dE + douter_deta * r.S * f.d_dE.transpose();
  r.S *= outer;
  return r;
}

MullinsEffect::Softening MullinsEffect::ogden_roxburgh(const Driver& d, double D_max_old,
                                                       std::span<double> state_new) const {
  if (d.D >= D_max_old) {  // first loading: eta = 1 identically, D_max follows D
    own(state_new)[0] = d.D;
    return {};
  }
  own(state_new)[0] = D_max_old;
  const double scale_value = scale(D_max_old), z = (D_max_old - d.D) / scale_value;
  // d eta / dE = (2 / (r sqrt(pi) scale)) e^{-z^2} dD/dE (energy: dW/dE = S_base).
  return {1.0 - std::erf(z) / p_.r,
          2.0 * std::exp(-z * z) / (p_.r * std::sqrt(std::numbers::pi) * scale_value) * d.dD_dE, false};
}

void MullinsEffect::damage(Softening& f, const Driver& n, double N_max_old, std::span<double> state_new) const {
  const double N_max = std::max(N_max_old, n.D), factor = damage_factor(N_max);
  own(state_new)[1] = N_max;
  f.d_dE *= factor;
  if (n.D >= N_max_old)  // the damage grows: eta (-dd/dE), dd/dE = (d_inf/e_d) exp(-N/e_d) dN/dE
    f.d_dE -= f.value * (p_.damage_limit / p_.damage_strain) * std::exp(-n.D / p_.damage_strain) * n.dD_dE;
  f.value *= factor;
  f.first_loading_unchanged = false;
}

void MullinsEffect::drive_memory_with_softened_stress(PointResponse& r, const Mat3& F_new, const ElasticEval& e,
                                                      double eta_value, const Vec6& deta_dE, double dt,
                                                      std::span<double> state_new) const {
  const double w = p_.relaxation_share, zeta = std::pow(eta_value, w);
  const Vec6 dzeta_dE = w * std::pow(eta_value, w - 1.0) * deta_dE;
  // The memory's state starts with the long-term stress the Viscoelastic stored (S_e): store zeta S_e there, and let
  // the memory take the difference as if the long-term stress had risen by (zeta - 1) S_e more.
  Eigen::Map<Vec6>(state_new.data()) = zeta * e.S;
  const MemoryGain gain = memory_->drive_memory(F_new, state_new, dt, (zeta - 1.0) * e.S);
  const double k = 1.0 + gain.k;  // Viscoelastic: 1 + sum a_i q_i
  r.dS_dE += k * ((zeta - 1.0) * e.dS_dE + e.S * dzeta_dE.transpose()) + (zeta - 1.0) * e.S * gain.dk_dE.transpose();
  r.S += (zeta - 1.0) * k * e.S;
}

Vec6 MullinsEffect::viscous_stress(const Mat3& F, std::span<const double> state) const {
  const double eta_value = eta(driver(F, energy_base_->evaluate(F)).D, own(state)[0]);
  const double softening = eta_value * (p_.damage_limit > 0.0 ? damage_factor(own(state)[1]) : 1.0);
  return std::pow(softening, 1.0 - p_.relaxation_share) * EffectDecorator::viscous_stress(F, state);
}

Mat6c MullinsEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const ElasticEval e = energy_base_->evaluate(F_base);
  const Driver d = driver(F_base, e);
  const double deta_dD = 2.0 / (p_.r * std::sqrt(std::numbers::pi) * scale(d.D));
  const Mat6 softening = deta_dD * e.S * d.dD_dE.transpose();
  const double w = p_.relaxation_share;
  const std::complex<double> share = memory_ ? w * memory_->memory_complex_factor(F_base, omega) + (1.0 - w) : 1.0;
  const double damage = p_.damage_limit > 0.0 ? damage_factor(biot_norm(F_base).D) : 1.0;
  return damage * (inner_->complex_tangent(F_base, omega) + share * softening.cast<std::complex<double>>());
}

std::string MullinsEffect::describe() const {
  std::ostringstream o;
  o << "Mullins softening (r = " << p_.r;
  if (p_.strain_scale > 0.0)
    o << ", driven by the Biot strain norm, m_e = " << p_.strain_scale;
  else
    o << ", m = " << p_.m * 1e3 << " kPa";
  o << ", beta = " << p_.beta;
  if (p_.relaxation_share > 0.0) o << ", relaxation share " << p_.relaxation_share;
  if (p_.damage_limit > 0.0) o << ", damage d_inf = " << p_.damage_limit << " over e_d = " << p_.damage_strain;
  o << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
