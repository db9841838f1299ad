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
  if (!(p_.permeability_exponent >= -2.0) || !std::isfinite(p_.permeability_exponent))
    throw std::invalid_argument("pneumatic: permeability exponent must be >= -2");
  if (!positive(p_.air_viscosity)) throw std::invalid_argument("pneumatic: air viscosity must be > 0");
  if (!(p_.air_modulus > 0.0)) throw std::invalid_argument("pneumatic: air modulus must be > 0 (infinite: dashpot)");
  if (!(p_.air_modulus_exponent >= -2.0 && p_.air_modulus_exponent <= 5.0))
    throw std::invalid_argument("pneumatic: air modulus exponent must be in [-2, 5]");
  if (!(p_.rate_exponent >= 0.1 && p_.rate_exponent <= 3.0))
    throw std::invalid_argument("pneumatic: rate exponent must be in [0.1, 3]");
  if (!(p_.pressure_share >= 0.0 && p_.pressure_share <= 1.0))
    throw std::invalid_argument("pneumatic: pressure share must be in [0, 1]");
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

namespace {

/// A: B for symmetric 3x3 tensors.
double ddot(const Mat3& A, const Mat3& B) { return A.cwiseProduct(B).sum(); }

}  // namespace

PneumaticEffect::Drag PneumaticEffect::linear_drag(double J, const Mat3& dE, double dt, const Mat3& Y_old) const {
  const double c = coefficient(J), n = p_.permeability_exponent;
  if (std::isinf(p_.air_modulus)) {  // dashpot: Y = c(J) dE/dt, d(c/dt)/dJ = -n c/(dt J)
    const double alpha = c / dt;
    return {alpha * dE, alpha, -n * alpha * dE, Mat3::Zero(), Mat3::Zero()};
  }
  // Maxwell: Y = (Y_old + M dE)/B, B = 1 + dt M(J)/c(J) (as in darcy_pressure).
  const double M = air_modulus(J), dM = -p_.air_modulus_exponent * M / J;
  const auto [B, dB] = maxwell_denominator(J, dt);
  const Mat3 Y = (Y_old + M * dE) / B;
  return {Y, M / B, J * (dM * dE - dB * Y) / B, Mat3::Zero(), Mat3::Zero()};
}

PneumaticEffect::Drag PneumaticEffect::power_law_drag(const Mat3& Ci, double J, const Mat3& dE, double dt,
                                                      const Mat3& Y_old) const {
  // |A|_C = sqrt(C^-1 A C^-1 : A), the norm of the spatial tensor F^-T A F^-1 (for A = dE/dt: |D|); its square varies
  // along X by 2 (C^-1 A C^-1) : dA - 4 (C^-1 A C^-1 A C^-1) : X (dC^-1 = -2 C^-1 X C^-1).
  const double q = p_.rate_exponent, c = coefficient(J), n = p_.permeability_exponent,
               eps2 = kPneumaticRestRate * kPneumaticRestRate;
  if (std::isinf(p_.air_modulus)) {
    // dashpot: Y = c(J) h(r) Edot, Edot = dE/dt, r = |Edot|_C, h(r) = (r^2 + v_eps^2)^((q-1)/2); dh = kappa d(r^2)
    const Mat3 Ed = dE / dt, W = Ci * Ed * Ci, V = W * Ed * Ci;
    const double r2 = ddot(W, Ed), h = std::pow(r2 + eps2, 0.5 * (q - 1.0));
    const double kappa = 0.5 * (q - 1.0) * h / (r2 + eps2);  // (r^2 + v_eps^2)^((q-3)/2) from h, one pow fewer
    const double alpha = c * h / dt;
    return {c * h * Ed, alpha, -n * c * h * Ed, c * kappa * (2.0 * W / dt - 4.0 * V), Ed};
  }
  // Maxwell: trial Y_tr = Y_old + M dE; the dashpot rate Edot_v is parallel to it, Y = Y_tr - M dt Edot_v =
  // c h(rho) Edot_v, so its norm rho solves c g(rho) + M dt rho = a = |Y_tr|_C (maxwell_dashpot_rate) and
  // Y = phi Y_tr, phi = c g(rho)/a (= c h(rho)/(c h(rho) + M dt)).
  const double M = air_modulus(J), dM_dJ = -p_.air_modulus_exponent * M / J, Mdt = M * dt;
  const Mat3 Y_tr = Y_old + M * dE;
  const Mat3 W = Ci * Y_tr * Ci, V = W * Y_tr * Ci;
  const double a = std::sqrt(std::max(0.0, ddot(W, Y_tr)));
  const auto [rho, f] = maxwell_dashpot_rate(c, Mdt, a, q);
  if (a == 0.0) {  // no trial stress: Y = 0, dY = phi(0) dY_tr with phi(0) = c h(0)/(c h(0) + M dt), h(0) = f.dg
    const double phi0 = c * f.dg / (c * f.dg + Mdt);
    return {Mat3::Zero(), phi0 * M, phi0 * J * dM_dJ * dE, Mat3::Zero(), Mat3::Zero()};
  }
  // phi = c g(rho)/a, not 1 - M dt rho/a: with a stiff air spring (phi -> 0) the difference cancels; rho itself is
  // found to relative precision, and so is g(rho).
  const double phi = c * f.g / a;
  // Along X, with s = C^-1 : X: dY_tr = M X + s J M' dE; da = [X : (M W - 2 V) + s J M' (W : dE)]/a;
  // drho = (da - dc g - dM dt rho)/(c g' + M dt), dc = -n c s, dM = J M' s; dphi = (dc g + c g' drho)/a - phi da/a.
  const double slope = c * f.dg + Mdt;
  const Mat3 da_T = (M * W - 2.0 * V) / a;  // da = da_T : X + da_s s
  const double da_s = J * dM_dJ * ddot(W, dE) / a;
  const double drho_s = (da_s + n * c * f.g - J * dM_dJ * dt * rho) / slope;  // drho = da_T:X / slope + drho_s s
  const double dphi_s = (-n * c * f.g + c * f.dg * drho_s) / a - phi * da_s / a;
  const Mat3 dphi_T = (c * f.dg / (slope * a) - phi / a) * da_T;
  return {phi * Y_tr, phi * M, phi * J * dM_dJ * dE + dphi_s * Y_tr, dphi_T, Y_tr};
}

void PneumaticEffect::add_drag(PointResponse& r, const Mat3& Ci, double J, const Mat3& dE, double dt,
                               std::span<const double> Y_old, std::span<double> Y_new, double weight) const {
  const Mat3 Y_prev = from_voigt_stress(Eigen::Map<const Vec6>(Y_old.data()));
  const Drag d = p_.rate_exponent == 1.0 ? linear_drag(J, dE, dt, Y_prev) : power_law_drag(Ci, J, dE, dt, Y_prev);
  Eigen::Map<Vec6>(Y_new.data()) = to_voigt_stress(d.Y);
  const Mat3 CiYCi = Ci * d.Y * Ci;
  r.S += weight * to_voigt_stress(CiYCi);
  // dS[X] = -2 C^-1 X C^-1 Y C^-1 - 2 C^-1 Y C^-1 X C^-1 + C^-1 dY[X] C^-1 (dC^-1 = -2 C^-1 X C^-1), with
  // dY[X] = alpha X + (C^-1 : X) Z + (T : X) H (C^-1 and T symmetric: A : X is the stress-like Voigt A dotted with X).
  r.dS_dE += weight * (d.alpha * box_voigt(Ci, Ci) - 2.0 * (box_voigt(Ci, CiYCi) + box_voigt(CiYCi, Ci)) +
                       to_voigt_stress(Ci * d.Z * Ci) * to_voigt_stress(Ci).transpose() +
                       to_voigt_stress(Ci * d.H * Ci) * to_voigt_stress(d.T).transpose());
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
