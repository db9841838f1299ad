#include "material/effect_pneumatic.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace cushion::material {

PneumaticEffect::PneumaticEffect(std::shared_ptr<const Material> inner, PneumaticParameters parameters)
    : EffectDecorator(std::move(inner), parameters.pressure_share < 1.0 ? 7 : 1), p_(parameters) {
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(p_.drainage_length)) throw std::invalid_argument("pneumatic: drainage length must be > 0");
  if (!positive(p_.permeability)) throw std::invalid_argument("pneumatic: permeability must be > 0");
  if (!(p_.permeability_exponent >= 0.0) || !std::isfinite(p_.permeability_exponent))
    throw std::invalid_argument("pneumatic: permeability exponent must be >= 0");
  if (!positive(p_.air_viscosity)) throw std::invalid_argument("pneumatic: air viscosity must be > 0");
  if (!(p_.air_modulus > 0.0)) throw std::invalid_argument("pneumatic: air modulus must be > 0 (infinite: dashpot)");
  if (!(p_.air_modulus_exponent >= 0.0 && p_.air_modulus_exponent <= 5.0))
    throw std::invalid_argument("pneumatic: air modulus exponent must be in [0, 5]");
  if (!(p_.rate_exponent >= 0.1 && p_.rate_exponent <= 3.0))
    throw std::invalid_argument("pneumatic: rate exponent must be in [0.1, 3]");
  if (!(p_.pressure_share >= 0.0 && p_.pressure_share <= 1.0))
    throw std::invalid_argument("pneumatic: pressure share must be in [0, 1]");
  if (p_.pressure_share < 1.0 && p_.rate_exponent != 1.0)
    throw std::invalid_argument("pneumatic: a drag share (pressure share < 1) needs the linear flow (rate exponent 1)");
}

namespace {

/// The power-law flow g(v) = v (v^2 + v_eps^2)^((q-1)/2) [1/s] and its derivative g'(v) [-].
struct Flow {
  double g, dg;
};
Flow power_flow(double v, double q) {
  const double r2 = v * v + kPneumaticRestRate * kPneumaticRestRate;
  const double w = std::pow(r2, 0.5 * (q - 1.0));
  return {v * w, w * (q * v * v + kPneumaticRestRate * kPneumaticRestRate) / r2};
}

/// The dashpot rate v [1/s] of a Maxwell branch with a power-law dashpot, and g at it: the root of
/// R(v) = c g(v) - a + Mdt v (c [MPa s], Mdt = M dt [MPa s], a [MPa]).
std::pair<double, Flow> maxwell_dashpot_rate(double c, double Mdt, double a, double q) {
  // R increases with v and R(0) = -a, so the root has the sign of a and |v| <= |a|/Mdt (where the spring term alone
  // reaches a); the pure power law's g^-1(|a|/c) is a tighter bound when R does not change sign there (v_eps can move
  // it for q < 1).
  const double sign = a < 0.0 ? -1.0 : 1.0;
  double bound = std::abs(a) / Mdt;
  if (const double power = std::pow(std::abs(a) / c, 1.0 / q); power < bound) {
    const Flow at = power_flow(sign * power, q);
    if (sign * (c * at.g - a + Mdt * sign * power) >= 0.0) bound = power;
  }
  // Newton on x = |v|^r (r = q for q < 1, else 1), from the bound down: in x, R is convex with a slope of at least c
  // (q < 1: c g(v) ~ c x) or Mdt (q >= 1), so Newton from above converges monotonically; bisection when a step leaves
  // the bracket [0, x(bound)]. In v itself, q < 1 made it creep through the steep g near rest (11 iterations on
  // average, up to 50, on a foreign campaign's tests; 3 on average, at most 5, in x).
  const double r = std::min(q, 1.0);
  double lo = 0.0, hi = std::pow(bound, r), x = hi, v = sign * bound;
  Flow f = power_flow(v, q);
  for (int it = 0; it < 100 && a != 0.0; ++it) {
    const double R = sign * (c * f.g - a + Mdt * v);  // increasing in x
    if (std::abs(R) <= 1e-14 * (std::abs(a) + c * std::abs(f.g) + Mdt * std::abs(v))) break;  // round-off level
    (R > 0.0 ? hi : lo) = x;
    const double dv_dx = x > 0.0 ? std::pow(x, 1.0 / r - 1.0) / r : 0.0;
    const double slope = (c * f.dg + Mdt) * dv_dx;
    const double newton = slope > 0.0 ? x - R / slope : lo;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    const bool converged = std::abs(next - x) <= 1e-13 * x || hi - lo <= 1e-15 * hi;
    x = next;
    v = sign * std::pow(x, 1.0 / r);
    f = power_flow(v, q);
    if (converged) break;
  }
  return {v, f};
}

}  // namespace

double PneumaticEffect::air_modulus(double J) const {  // r = 0 (the default) skips a pow in every increment
  return p_.air_modulus_exponent == 0.0 ? p_.air_modulus : p_.air_modulus * std::pow(J, -p_.air_modulus_exponent);
}

double PneumaticEffect::relaxation_time(double J) const {
  return std::isinf(p_.air_modulus) ? 0.0 : coefficient(J) / air_modulus(J);
}

double PneumaticEffect::coefficient(double J) const {
  const double K = p_.permeability * std::pow(J, p_.permeability_exponent);
  return p_.air_viscosity * p_.drainage_length * p_.drainage_length / (8.0 * K);
}

PointResponse PneumaticEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                         std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  const std::span<const double> own_old = own(state_old);
  const std::span<double> own_new = own(state_new);
  std::copy(own_old.begin(), own_old.end(), own_new.begin());
  if (r.status == Status::failed || dt == 0.0) return r;
  const double J = F_new.determinant(), share = p_.pressure_share;
  const Mat3 C = F_new.transpose() * F_new, Ci = C.inverse();
  if (share > 0.0) {
    const double J_old = F_old.determinant();
    const auto [p, dp_dJ] = p_.rate_exponent == 1.0 ? darcy_pressure(J, J_old, dt, own_old[0])
                                                     : power_law_pressure(J, J_old, dt, own_old[0]);
    own_new[0] = p;
    const Vec6 Ci_v = to_voigt_stress(Ci);
    r.S += -share * p * Ci_v;
    // dS/dE = -C^{-1} (x) dp/dE - p dC^{-1}/dE, dp/dE = dp/dJ J C^{-1}.
    r.dS_dE += share * (-dp_dJ * J * Ci_v * Ci_v.transpose() - p * dCinv_dE(Ci));
  }
  if (share < 1.0) {
    const Mat3 dE = 0.5 * (C - F_old.transpose() * F_old);
    add_drag(r, Ci, J, dE, dt, own_old.subspan(1), own_new.subspan(1), 1.0 - share);
  }
  if (!r.S.allFinite()) {
    r.status = Status::failed;
    r.message = "pneumatic: non-finite stress";
    r.dt_factor = 0.5;
  }
  return r;
}

PneumaticEffect::Pressure PneumaticEffect::darcy_pressure(double J, double J_old, double dt, double p_old) const {
  const double c0 = coefficient(1.0), n = p_.permeability_exponent;
  if (std::isinf(p_.air_modulus))  // dashpot: p = -c(J) (J - J_old) / (dt J) with c(J) = c0 J^{-n}
    return {-(c0 / dt) * std::pow(J, -n - 1.0) * (J - J_old),
            -(c0 / dt) * std::pow(J, -n - 2.0) * ((-n - 1.0) * (J - J_old) + J)};
  // Maxwell: p = A/B, A = p_old - M(J) (J - J_old)/J, B = 1 + dt M(J) J^n / c0, M(J) = M0 J^-r (dM/dJ = -r M/J; r = 0:
  // the terms with dM vanish exactly, so a constant modulus gives the same numbers as before the exponent existed)
  const double M = air_modulus(J), dM = -p_.air_modulus_exponent * M / J;
  const double A = p_old - M * (J - J_old) / J, dA = -M * J_old / (J * J) - dM * (J - J_old) / J;
  const auto [B, dB] = maxwell_denominator(J, dt);
  return {A / B, (dA * B - A * dB) / (B * B)};
}

PneumaticEffect::Denominator PneumaticEffect::maxwell_denominator(double J, double dt) const {
  const double c0 = coefficient(1.0), n = p_.permeability_exponent;
  const double M = air_modulus(J), dM = -p_.air_modulus_exponent * M / J;
  return {1.0 + dt * M * std::pow(J, n) / c0, dt * M * n * std::pow(J, n - 1.0) / c0 + dt * dM * std::pow(J, n) / c0};
}

void PneumaticEffect::add_drag(PointResponse& r, const Mat3& Ci, double J, const Mat3& dE, double dt,
                               std::span<const double> Y_old, std::span<double> Y_new, double weight) const {
  const double c = coefficient(J), n = p_.permeability_exponent;
  // Y and its derivative dY[X] = alpha X + (C^-1 : X) Z along a strain direction X (dJ = J C^-1 : X).
  double alpha = c / dt;
  Mat3 Y = alpha * dE, Z = -n * alpha * dE;  // dashpot: alpha = c(J)/dt, d alpha/dJ = -n alpha/J
  if (!std::isinf(p_.air_modulus)) {
    // Maxwell: Y = (Y_old + M dE)/B, B = 1 + dt M(J)/c(J) (as in darcy_pressure).
    const double M = air_modulus(J), dM = -p_.air_modulus_exponent * M / J;
    const auto [B, dB] = maxwell_denominator(J, dt);
    alpha = M / B;
    Y = (from_voigt_stress(Eigen::Map<const Vec6>(Y_old.data())) + M * dE) / B;
    Z = J * (dM * dE - dB * Y) / B;
  }
  Eigen::Map<Vec6>(Y_new.data()) = to_voigt_stress(Y);
  const Mat3 CiYCi = Ci * Y * Ci;
  r.S += weight * to_voigt_stress(CiYCi);
  // dS[X] = -2 C^-1 X C^-1 Y C^-1 - 2 C^-1 Y C^-1 X C^-1 + C^-1 dY[X] C^-1 (dC^-1 = -2 C^-1 X C^-1), column by column.
  for (int k = 0; k < 6; ++k) {
    const Mat3 X = from_voigt_strain(Vec6::Unit(k));
    const Mat3 dY = alpha * X + Ci.cwiseProduct(X).sum() * Z;
    const Mat3 dS = -2.0 * (Ci * X * CiYCi + CiYCi * X * Ci) + Ci * dY * Ci;
    r.dS_dE.col(k) += weight * to_voigt_stress(dS);
  }
}

PneumaticEffect::Pressure PneumaticEffect::power_law_pressure(double J, double J_old, double dt, double p_old) const {
  const double q = p_.rate_exponent;
  const double c = coefficient(J), dc_dJ = -p_.permeability_exponent * c / J;
  const double strain = J_old / J - 1.0, dstrain_dJ = -J_old / (J * J);  // -(J - J_old)/J
  if (std::isinf(p_.air_modulus)) {  // dashpot: p = c(J) g(v), v = strain/dt
    const Flow f = power_flow(strain / dt, q);
    return {c * f.g, dc_dJ * f.g + c * f.dg * dstrain_dJ / dt};
  }
  // Maxwell: the dashpot rate v solves R = c g(v) - a + M dt v = 0 with a = p_old + M strain, M = M(J)
  // (maxwell_dashpot_rate); dR/dJ at fixed v = c' g - M' strain - M strain' + M' dt v.
  const double M = air_modulus(J), dM = -p_.air_modulus_exponent * M / J;
  const double a = p_old + M * strain;
  const auto [v, f] = maxwell_dashpot_rate(c, M * dt, a, q);
  const double dR_dJ = dc_dJ * f.g - (M * dstrain_dJ + dM * strain) + dM * dt * v;
  const double dv_dJ = -dR_dJ / (c * f.dg + M * dt);
  return {c * f.g, dc_dJ * f.g + c * f.dg * dv_dJ};
}

Mat6c PneumaticEffect::complex_tangent(const Mat3& F_base, double omega) const {
  if (p_.rate_exponent != 1.0)
    throw std::invalid_argument(
        "pneumatic: a power-law air flow (rate exponent != 1) has no small-amplitude frequency-domain tangent; run the "
        "time-domain dynamic step");
  const Mat3 Ci = (F_base.transpose() * F_base).inverse();
  const Vec6 Ci_v = to_voigt_stress(Ci);
  const double J = F_base.determinant(), share = p_.pressure_share;
  Mat6 C_air = share * coefficient(J) * Ci_v * Ci_v.transpose();
  for (int k = 0; k < 6; ++k)  // the drag: dS = c C^-1 dE C^-1 per unit rate
    C_air.col(k) += (1.0 - share) * coefficient(J) * to_voigt_stress(Ci * from_voigt_strain(Vec6::Unit(k)) * Ci);
  const std::complex<double> i_omega(0.0, omega);
  return inner_->complex_tangent(F_base, omega) +
         (i_omega / (1.0 + i_omega * relaxation_time(J))) * C_air.cast<std::complex<double>>();
}

std::string PneumaticEffect::describe() const {
  std::ostringstream o;
  o << "pneumatic damping (R = " << p_.drainage_length << " mm, K0 = " << p_.permeability << " mm^2, n_K = "
    << p_.permeability_exponent << ", eta_air = " << p_.air_viscosity * 1e6 << " Pa s, air modulus "
    << (std::isinf(p_.air_modulus) ? std::string("infinite (dashpot)")
                                   : std::to_string(p_.air_modulus * 1e3) + " kPa" +
                                         (p_.air_modulus_exponent == 0.0
                                              ? std::string()
                                              : " x J^-" + std::to_string(p_.air_modulus_exponent)))
    << ", flow rate exponent q = " << p_.rate_exponent << ", pressure share " << p_.pressure_share
    << ", drag share " << 1.0 - p_.pressure_share << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
