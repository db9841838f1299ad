#pragma once
/// Pneumatic (air-flow, Darcy) damping of open-cell foam as a LUMPED extra pressure (docs/physics.md 5.1).
///
/// Air expelled from a layer of half-width R compressed at volumetric rate -dJ/dt flows laterally
/// through the cells by Darcy's law; the mean extra stress of the layer is eta eps_dot R^2 / (8 K)
/// (Darcy + continuity, lateral escape). This effect adds that mean pressure at every point:
///   extra Kirchhoff pressure  p_air = -(eta_air R^2 / (8 K(J))) (dJ/dt) / J,
///   extra PK2 stress          S_air = -p_air C^{-1}       (Kirchhoff tau_air = -p_air I),
///   permeability              K(J) = K0 J^{n_K}           (n_K > 0: K falls with compression [A],
///                                                          cf. Dawson, Germaine & Gibson, IJSS 44, 2007;
///                                                          n_K in [-2, 0): K rising, an empirical stretch
///                                                          dependence of the lumped drag, docs/physics.md 5.1),
/// with the backward-Euler rate dJ/dt = (J_new - J_old)/dt from F_old (dt = 0: no extra stress).
/// Compression (dJ/dt < 0) gives p_air > 0, a compressive extra stress. Time scale of the effect
/// tau_air ~ eta R^2 / (8 K M) (M: drained modulus): it grows as K falls and with R^2.
///
/// Trapped air (optional, air_modulus M finite): the air in the cells is itself a spring of stiffness M (isothermal air
/// at 1 atm: M ~ p_atm = 101 kPa) in series with the Darcy flow, a MAXWELL branch
///   dp/dt + p / tau(J) = -M (dJ/dt)/J,   tau(J) = c(J)/M,   c(J) = eta R^2/(8 K(J)),
/// integrated by backward Euler with p the own state:  p = [p_old - M (J - J_old)/J] / (1 + dt M / c(J)).
/// The trapped air stiffens as the cells shrink (air_modulus_exponent r, default 0: constant): M = M(J) = M0 J^-r,
/// evaluated at the increment's end; an isothermal ideal gas filling the cells gives r = 1 (Boyle: p_abs ~ 1/J, so
/// dp/d(ln J) = -p_abs ~ -p_atm/J; docs/physics.md 5.1). r in [-2, 0) softens the spring with compression, an
/// empirical stretch dependence of the branch (its nominal spring in a uniaxial test at nu = 0 goes as l^-(2 + r)).
/// M -> infinity gives back the dashpot p = -c(J) (dJ/dt)/J (the default: air_modulus infinite); with M finite the
/// air raises the storage modulus at frequencies above 1/(2 pi tau) and relaxes under a hold, and tau depends on the
/// compression through K(J) (docs/physics.md 5.1).
/// It is NOT a poroelastic (Biot) FE model: the pore pressure is not a field and does not diffuse
/// between elements; R is a user/case parameter (half the specimen width or drainage path), which
/// makes the model SIZE-DEPENDENT: a Prony series fitted on a small block misses it on a large one.
/// Flow law (rate_exponent q, default 1: Darcy): the dashpot's pressure follows the volumetric rate v = -(dJ/dt)/J
/// [1/s] as a power law, p = c(J) g(v), g(v) = v (v^2 + v_eps^2)^((q-1)/2) [1/s] with the reference rate 1/s
/// (g = sign(v) |v|^q for |v| >> v_eps = 1e-4 /s, a regularisation that keeps the tangent finite at rest; q = 1: g = v
/// exactly, Darcy). q < 1: a flow resistance that thins with rate (an empirical description [A], no mechanism sourced);
/// q > 1: inertial (Forchheimer-like) losses growing faster than the rate. With the trapped-air
/// spring the branch is M in series with this dashpot; the dashpot rate v_d is the root of the monotone
///   c(J) g(v_d) - p_old - M (J_old/J - 1) + M dt v_d = 0,    p = c(J) g(v_d),
/// solved by safeguarded Newton (docs/physics.md 5.1).
/// Pressure or drag (pressure_share s in [0, 1], default 1): the lumped pressure is isotropic, so on a laterally FREE
/// specimen it also pushes sideways and the specimen inflates: with lateral modulus E_l the air then sees a spring
/// about E_l/2 in series, and the axial damping saturates (phase falls above omega c ~ E_l/2) where a 1D air dashpot
/// keeps rising. With lateral drainage the real pore pressure vanishes at the free faces, so the lumped mean pressure
/// overstates that inflation [A]. The share 1 - s of the air's stress is instead a DRAG along the rate of
/// deformation, Kirchhoff tau_d = c(J) D (D = sym(dF/dt F^-1)), pulled back S_d = C^-1 Y C^-1 with the Lagrangian
/// state Y [MPa]:  dashpot Y = c(J) dE/dt;  trapped air  dY/dt + Y/tau(J) = M(J) dE/dt,  backward Euler
///   Y = (Y_old + M(J) (E - E_old)) / (1 + dt M(J)/c(J)).
/// In a laterally confined test (F = diag(l, 1, 1)) the drag gives the pressure form's axial stress to first order in
/// the increment (P11 = c(l) l_dot/l^2 as a dashpot, the same Maxwell spring M dl/l^2 per increment; the stored Y is
/// carried in Lagrangian components, (l_old/l)^2 more than the pressure); with nu = 0 and free laterals it adds no
/// lateral stress (D22 = D33 = 0), so the air acts as an axial dashpot or Maxwell branch there. Both parts share c(J),
/// M(J) and tau(J); S_air = s S_pressure + (1 - s) S_drag (docs/physics.md 5.1). With a power-law flow the drag follows
/// the norm of the rate of deformation, tau_d = c(J) h(|D|) D, h(r) = (r^2 + v_eps^2)^((q-1)/2), |D| = |dE/dt|_C
/// (|A|_C = sqrt(C^-1 A C^-1 : A)); with trapped air the dashpot rate is parallel to the trial stress Y_old + M dE and
/// its norm solves the pressure form's scalar equation (a radial return, power_law_drag).
/// Own state: the air pressure p [MPa] (one double), then Y (6 doubles, stress-like Voigt) when s < 1. dt = 0 (an
/// instantaneous response) adds no air stress and keeps the state.
/// Frequency domain about a relaxed base F_b (p_air = 0 and Y = 0 there), added to the inner tangent:
///   dS* = (i omega c(J_b) / (1 + i omega tau(J_b))) [s C_b^{-1} (x) C_b^{-1} : dE* + (1 - s) C_b^{-1} dE* C_b^{-1}].
/// A power-law flow (q != 1) has no amplitude-free small-amplitude tangent: complex_tangent throws
/// std::invalid_argument (run the time-domain dynamic step instead).
#include <limits>

#include "material/effect_decorator.hpp"

namespace cushion::material {

/// Parameters in internal units (mm, s, MPa).
struct PneumaticParameters {
  double drainage_length = 40.0;     ///< R [mm], > 0: half-width of the specimen (lateral drainage path)
  double permeability = 1e-3;        ///< K0 [mm^2] at J = 1, > 0 (1e-3 mm^2 = 1e-9 m^2)
  double permeability_exponent = 2;  ///< n_K [-], >= -2: K = K0 J^{n_K}
  double air_viscosity = 1.8e-11;    ///< eta_air [MPa s] (1.8e-5 Pa s), > 0
  double air_modulus = std::numeric_limits<double>::infinity();  ///< M0 [MPa], > 0, at J = 1; infinite: Darcy dashpot
  double air_modulus_exponent = 0.0;  ///< r [-], in [-2, 5]: M(J) = M0 J^-r (0: constant; 1: isothermal gas, Boyle)
  double rate_exponent = 1.0;        ///< q [-], in [0.1, 3]: flow law p = c(J) g(v), g ~ sign(v)|v|^q; 1: Darcy
  double pressure_share = 1.0;       ///< s [-], in [0, 1]: share of isotropic pressure; 1 - s: drag c(J) h(|D|) D
};

/// Regularisation rate v_eps [1/s] of the power-law flow g(v) = v (v^2 + v_eps^2)^((q-1)/2).
inline constexpr double kPneumaticRestRate = 1e-4;

class PneumaticEffect final : public EffectDecorator {
 public:
  /// Throws std::invalid_argument on parameters outside the ranges above.
  PneumaticEffect(std::shared_ptr<const Material> inner, PneumaticParameters parameters);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  /// Damping coefficient eta R^2 / (8 K(J)) [MPa s] at volume ratio J.
  double coefficient(double J) const;
  /// Trapped-air modulus M(J) = M0 J^-r [MPa] at volume ratio J (infinite for the dashpot).
  double air_modulus(double J) const;
  /// Relaxation time c(J)/M(J) [s] of the trapped air at volume ratio J (0 for the dashpot, M infinite).
  double relaxation_time(double J) const;
  const PneumaticParameters& parameters() const { return p_; }

 private:
  struct Pressure {
    double p, dp_dJ;  ///< air pressure [MPa] at the increment's end and its derivative by J [MPa]
  };
  /// Linear flow (q = 1): closed form, dashpot or Maxwell.
  Pressure darcy_pressure(double J, double J_old, double dt, double p_old) const;
  /// Power-law flow (q != 1): dashpot closed form, or Maxwell by Newton for the dashpot rate (maxwell_dashpot_rate).
  Pressure power_law_pressure(double J, double J_old, double dt, double p_old) const;
  struct Denominator {
    double B, dB_dJ;  ///< B = 1 + dt M(J)/c(J) [-] of the backward-Euler Maxwell step, and its derivative by J
  };
  Denominator maxwell_denominator(double J, double dt) const;
  /// The drag's Lagrangian stress Y [MPa] at the increment's end and its derivative along a strain direction X,
  ///   dY[X] = alpha X + (C^-1 : X) Z + (T : X) H   (alpha [MPa], Z, T, H tensors; T = 0 for the linear flow).
  struct Drag {
    Mat3 Y;
    double alpha;
    Mat3 Z, T, H;
  };
  /// Linear flow (q = 1): dashpot Y = c(J) dE/dt, or Maxwell (Y_old + M dE)/B; Y_old [MPa].
  Drag linear_drag(double J, const Mat3& dE, double dt, const Mat3& Y_old) const;
  /// Power-law flow (q != 1) along the norm |dE/dt|_C = |D| of the rate (docs/physics.md 5.1): dashpot closed form, or
  /// Maxwell by the same scalar Newton as the pressure (maxwell_dashpot_rate) on the norm of the trial stress.
  Drag power_law_drag(const Mat3& Ci, double J, const Mat3& dE, double dt, const Mat3& Y_old) const;
  /// Adds weight x the drag's PK2 stress C^-1 Y C^-1 [MPa] and its exact increment tangent to r; Y_new <- Y. C^-1 and J
  /// at the increment's end, dE = E - E_old (Green-Lagrange).
  void add_drag(PointResponse& r, const Mat3& Ci, double J, const Mat3& dE, double dt, std::span<const double> Y_old,
                std::span<double> Y_new, double weight) const;

  PneumaticParameters p_;
};

}  // namespace cushion::material
