#include "material/effect_friction.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cushion::material {

FrictionEffect::FrictionEffect(std::shared_ptr<const Material> inner, FrictionParameters parameters)
    : EffectDecorator(std::move(inner), 6), p_(parameters) {
  if (!(p_.stiffness > 0.0) || !std::isfinite(p_.stiffness)) throw std::invalid_argument("friction: stiffness must be > 0");
  if (!(p_.yield_stress > 0.0) || !std::isfinite(p_.yield_stress))
    throw std::invalid_argument("friction: yield stress must be > 0");
  if (!(p_.hardening >= 0.0) || !std::isfinite(p_.hardening)) throw std::invalid_argument("friction: hardening must be >= 0");
  if (!std::isfinite(p_.stretch_exponent)) throw std::invalid_argument("friction: stretch exponent must be finite");
}

PointResponse FrictionEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                        std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  const double n = p_.stretch_exponent, h = p_.hardening;
  const double J = F_new.determinant();
  if (n != 0.0 && !(J > 0.0)) {
    combine_status(r, Status::failed, "friction: det F = " + std::to_string(J) + " <= 0 with a stretch exponent");
    return r;
  }
  const double a = p_.stiffness * std::pow(J, -2.0 * n), b = p_.yield_stress * std::pow(J, -n);
  // d(J^-m)/dE = -m J^-m dJ/dE / J (stress-like row over engineering dE)
  const Vec6 dlnJ = dJ_dE(F_new) / J;
  const Vec6 da = -2.0 * n * a * dlnJ, db = -n * b * dlnJ;
  // Tensor components in Voigt order (stress-like storage for E and E_p alike).
  const Vec6 E = to_voigt_stress(green_lagrange(F_new));
  const Vec6 Ep_old = Eigen::Map<const Vec6>(own(state_old).data());
  const Vec6 xi_trial = a * (E - Ep_old) - h * Ep_old;
  const double norm_trial = tensor_norm(xi_trial);
  const Mat6 I = symmetric_identity_voigt();
  const Mat6 dxi = a * I + (E - Ep_old) * da.transpose();  // maps engineering dE
  Vec6 Ep = Ep_old;
  Vec6 S_f = a * (E - Ep_old);
  Mat6 tangent = dxi;
  if (norm_trial > b) {
    // Radial return along the trial direction N; |S_f - h E_p| = b after it.
    const Vec6 N = xi_trial / norm_trial;
    Ep += (norm_trial - b) / (a + h) * N;
    const double g = (h * norm_trial + a * b) / (a + h);
    const Vec6 NW = to_voigt_strain(from_voigt_stress(N));  // engineering shear: N : X = NW . X (stress-like X)
    const Eigen::Matrix<double, 1, 6> dnorm = NW.transpose() * dxi;
    const Eigen::Matrix<double, 1, 6> dg = (h * dnorm + (b - g) * da.transpose() + a * db.transpose()) / (a + h);
    S_f = h * Ep_old + g * N;
    tangent = N * dg + g / norm_trial * (dxi - N * dnorm);
  }
  Eigen::Map<Vec6>(own(state_new).data()) = Ep;
  r.S += S_f;
  r.dS_dE += tangent;
  return r;
}

Mat6c FrictionEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const double a = p_.stiffness * std::pow(F_base.determinant(), -2.0 * p_.stretch_exponent);
  return inner_->complex_tangent(F_base, omega) + (a * symmetric_identity_voigt()).cast<std::complex<double>>();
}

std::string FrictionEffect::describe() const {
  std::ostringstream o;
  o << "friction branch (k = " << p_.stiffness * 1e3 << " kPa, s_y = " << p_.yield_stress * 1e3
    << " kPa, h = " << p_.hardening * 1e3 << " kPa";
  if (p_.stretch_exponent != 0.0) o << ", k J^" << -2.0 * p_.stretch_exponent << ", s_y J^" << -p_.stretch_exponent;
  o << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
