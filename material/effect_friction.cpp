#include "material/effect_friction.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

FrictionEffect::FrictionEffect(std::shared_ptr<const Material> inner, FrictionParameters parameters)
    : EffectDecorator(std::move(inner), 6), p_(parameters) {
  if (!(p_.stiffness > 0.0) || !std::isfinite(p_.stiffness)) throw std::invalid_argument("friction: stiffness must be > 0");
  if (!(p_.yield_stress > 0.0) || !std::isfinite(p_.yield_stress))
    throw std::invalid_argument("friction: yield stress must be > 0");
  if (!(p_.hardening >= 0.0) || !std::isfinite(p_.hardening)) throw std::invalid_argument("friction: hardening must be >= 0");
}

PointResponse FrictionEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                        std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  const double k = p_.stiffness, h = p_.hardening;
  // Tensor components in Voigt order (stress-like storage for E and E_p alike).
  const Vec6 E = to_voigt_stress(green_lagrange(F_new));
  const Vec6 Ep_old = Eigen::Map<const Vec6>(own(state_old).data());
  const Vec6 xi_trial = k * (E - Ep_old) - h * Ep_old;
  const double norm_trial = tensor_norm(xi_trial);
  const Mat6 I = symmetric_identity_voigt();
  Vec6 Ep = Ep_old;
  Mat6 tangent = k * I;
  if (norm_trial > p_.yield_stress) {
    // Radial return: the direction N is that of the trial stress; the tangent maps engineering dE.
    const Vec6 N = xi_trial / norm_trial;
    const double dgamma = (norm_trial - p_.yield_stress) / (k + h);
    Ep += dgamma * N;
    const Mat6 NN = N * N.transpose();
    tangent += -k * k / (k + h) * NN - k * k * dgamma / norm_trial * (I - NN);
  }
  Eigen::Map<Vec6>(own(state_new).data()) = Ep;
  r.S += k * (E - Ep);
  r.dS_dE += tangent;
  return r;
}

Mat6c FrictionEffect::complex_tangent(const Mat3& F_base, double omega) const {
  return inner_->complex_tangent(F_base, omega) + (p_.stiffness * symmetric_identity_voigt()).cast<std::complex<double>>();
}

std::string FrictionEffect::describe() const {
  std::ostringstream o;
  o << "friction branch (k = " << p_.stiffness * 1e3 << " kPa, s_y = " << p_.yield_stress * 1e3 << " kPa, h = "
    << p_.hardening * 1e3 << " kPa) over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
