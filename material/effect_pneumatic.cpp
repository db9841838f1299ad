#include "material/effect_pneumatic.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

PneumaticEffect::PneumaticEffect(std::shared_ptr<const Material> inner, PneumaticParameters parameters)
    : EffectDecorator(std::move(inner), 1), p_(parameters) {
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(p_.drainage_length)) throw std::invalid_argument("pneumatic: drainage length must be > 0");
  if (!positive(p_.permeability)) throw std::invalid_argument("pneumatic: permeability must be > 0");
  if (!(p_.permeability_exponent >= 0.0) || !std::isfinite(p_.permeability_exponent))
    throw std::invalid_argument("pneumatic: permeability exponent must be >= 0");
  if (!positive(p_.air_viscosity)) throw std::invalid_argument("pneumatic: air viscosity must be > 0");
  if (!(p_.air_modulus > 0.0)) throw std::invalid_argument("pneumatic: air modulus must be > 0 (infinite: dashpot)");
}

double PneumaticEffect::relaxation_time(double J) const {
  return std::isinf(p_.air_modulus) ? 0.0 : coefficient(J) / p_.air_modulus;
}

double PneumaticEffect::coefficient(double J) const {
  const double K = p_.permeability * std::pow(J, p_.permeability_exponent);
  return p_.air_viscosity * p_.drainage_length * p_.drainage_length / (8.0 * K);
}

PointResponse PneumaticEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                         std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  const double p_old = own(state_old)[0];
  own(state_new)[0] = p_old;
  if (r.status == Status::failed || dt == 0.0) return r;
  const double J = F_new.determinant(), J_old = F_old.determinant(), n = p_.permeability_exponent;
  const double c0 = coefficient(1.0), M = p_.air_modulus;
  double p = 0.0, dp_dJ = 0.0;
  if (std::isinf(M)) {  // dashpot: p = -c(J) (J - J_old) / (dt J) with c(J) = c0 J^{-n}
    p = -(c0 / dt) * std::pow(J, -n - 1.0) * (J - J_old);
    dp_dJ = -(c0 / dt) * std::pow(J, -n - 2.0) * ((-n - 1.0) * (J - J_old) + J);
  } else {  // Maxwell: p = A/B, A = p_old - M (J - J_old)/J, B = 1 + dt M J^n / c0
    const double A = p_old - M * (J - J_old) / J, dA = -M * J_old / (J * J);
    const double B = 1.0 + dt * M * std::pow(J, n) / c0, dB = dt * M * n * std::pow(J, n - 1.0) / c0;
    p = A / B;
    dp_dJ = (dA * B - A * dB) / (B * B);
  }
  own(state_new)[0] = p;
  const Mat3 Ci = (F_new.transpose() * F_new).inverse();
  const Vec6 Ci_v = to_voigt_stress(Ci);
  r.S += -p * Ci_v;
  // dS/dE = -C^{-1} (x) dp/dE - p dC^{-1}/dE, dp/dE = dp/dJ J C^{-1}.
  r.dS_dE += -dp_dJ * J * Ci_v * Ci_v.transpose() - p * dCinv_dE(Ci);
  if (!r.S.allFinite()) {
    r.status = Status::failed;
    r.message = "pneumatic: non-finite stress";
    r.dt_factor = 0.5;
  }
  return r;
}

Mat6c PneumaticEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const Vec6 Ci_v = to_voigt_stress((F_base.transpose() * F_base).inverse());
  const double J = F_base.determinant();
  const Mat6 C_air = coefficient(J) * Ci_v * Ci_v.transpose();
  const std::complex<double> i_omega(0.0, omega);
  return inner_->complex_tangent(F_base, omega) +
         (i_omega / (1.0 + i_omega * relaxation_time(J))) * C_air.cast<std::complex<double>>();
}

std::string PneumaticEffect::describe() const {
  std::ostringstream o;
  o << "pneumatic damping (R = " << p_.drainage_length << " mm, K0 = " << p_.permeability << " mm^2, n_K = "
    << p_.permeability_exponent << ", eta_air = " << p_.air_viscosity * 1e6 << " Pa s, air modulus "
    << (std::isinf(p_.air_modulus) ? std::string("infinite (dashpot)") : std::to_string(p_.air_modulus * 1e3) + " kPa")
    << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
