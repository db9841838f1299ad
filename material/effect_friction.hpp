#pragma once
/// Rate-independent frictional hysteresis (cell walls sliding on each other) as an elasto-plastic
/// branch IN PARALLEL with the inner model, small-strain plasticity written on the Green-Lagrange
/// strain E (reference frame, tensor components):
///   S_f = k (E - E_p),  back stress X = h E_p (linear kinematic hardening, h = 0: perfectly plastic),
///   yield  f = |S_f - X| - s_y <= 0  on the FULL tensor (Frobenius norm; foam cells slide in
///   volumetric compression too, so no deviatoric split),
///   flow   dE_p = dgamma N, N = (S_f - X)/|S_f - X|  (associative),
/// integrated by radial return (exact for this linear model):
///   xi_tr = k (E - E_p^n) - h E_p^n, dgamma = (|xi_tr| - s_y)/(k + h), E_p = E_p^n + dgamma N,
/// consistent tangent dS_f/dE = k I - k^2/(k+h) N (x) N - k^2 dgamma/|xi_tr| (I - N (x) N).
/// In 1D (only E11 non-zero) a strain cycle of amplitude e_a > e_y = s_y/k dissipates the loop area
/// 4 s_y (k e_a - s_y)/(k + h) per cycle, independent of the rate: the loss per cycle does not vanish
/// at slow rates and does not depend on frequency (unlike Prony or pneumatic damping).
/// Stretch exponent n (J = det F): the branch's stiffness and sliding stress grow with the compression,
///   k(J) = k J^(-2n),  s_y(J) = s_y J^(-n)   (n = 0: the constants above),
/// evaluated at the end of the increment (radial return at that J, exact for fixed J). In a uniaxial test at nu = 0
/// (J = l, E11 = (l^2 - 1)/2, nominal stress P = l S11), n = 1 makes the branch a nominal Jenkins element: the sliding
/// stress is |P_f| = l s_y(l) = s_y at every strain level and the sticking stiffness dP_f/de = k (1 - (E - E_p)/l^2),
/// k to first order in the elastic range e_y; with n = 0 both fall as l and l^2 (derivation: docs/physics.md 5.2b).
/// Tangent with a = k(J), b = s_y(J), da/dE = -2n a C^-1, db/dE = -n b C^-1:
///   sticking  dS_f/dE = a I + (E - E_p) (x) da/dE,
///   sliding   S_f = h E_p^n + g N, g = (h |xi_tr| + a b)/(a + h), xi_tr = a (E - E_p^n) - h E_p^n,
///             dS_f/dE = N (x) dg/dE + g (I - N (x) N) dxi/dE / |xi_tr|, dxi/dE = a I + (E - E_p^n) (x) da/dE,
///             dg/dE = (h N:dxi/dE + (b - g) da/dE + a db/dE)/(a + h)
/// (with n = 0: the classical k I - k^2/(k+h) N (x) N - k^2 dgamma/|xi_tr| (I - N (x) N)).
/// Own state: E_p (6 doubles, tensor components in Voigt order [11, 22, 33, 12, 23, 13]).
/// complex_tangent: NOT a linear effect. It returns the inner complex tangent plus the elastic
/// branch k(J) I at the base state, i.e. the tangent for amplitudes inside the elastic range (|S_f - X| < s_y) about
/// any unloaded/virgin state; finite-amplitude loss (the loop above) is not represented there.
#include "material/effect_decorator.hpp"

namespace cushion::material {

/// Parameters in internal units (MPa).
struct FrictionParameters {
  double stiffness = 0.01;      ///< k [MPa], > 0: elastic modulus of the branch (S_f = k E before sliding)
  double yield_stress = 2e-4;   ///< s_y [MPa], > 0: radius of the elastic range in |S_f - X|
  double hardening = 0.0;       ///< h [MPa], >= 0: linear kinematic hardening modulus
  /// n [-], finite: k J^(-2n), s_y J^(-n) (1: a nominal Jenkins element in uniaxial nu = 0)
  double stretch_exponent = 0.0;
};

class FrictionEffect final : public EffectDecorator {
 public:
  /// Throws std::invalid_argument on parameters outside the ranges above.
  FrictionEffect(std::shared_ptr<const Material> inner, FrictionParameters parameters);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  const FrictionParameters& parameters() const { return p_; }

 private:
  FrictionParameters p_;
};

}  // namespace cushion::material
