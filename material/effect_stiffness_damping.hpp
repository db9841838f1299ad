#pragma once
/// Stiffness-proportional (Rayleigh beta) damping at material level, the paper's beta = 1e-4 s, with an optional
/// fractional order q (a spring-pot in place of the dashpot; docs/physics.md 5.4, 5.4b):
///   S_d = beta_s omega_r^(1-q) C_d : D^q E,   omega_r = 2 pi f_r,
///   C_d = J_old^-n [(1 - w) C0 + w (C_e(F_old) + m G(F_old))],
/// D^q the Caputo derivative from the virgin state (material/spring_pot.hpp); q = 1 (the default) gives the dashpot
/// S_d = beta_s C_d : (E_new - E_old)/dt (backward-Euler rate; dt = 0: no extra stress) with no state. omega_r^(1-q)
/// makes beta_s the damping time at the reference frequency f_r whatever q: the loss tangent the term adds there is
/// omega_r beta_s sin(q pi/2) per unit of C_d, and changing q turns the loss's frequency slope (omega^q) about f_r.
/// C0 = tangent dS/dE of the elastic base at F = I (w = 0, the default: ABAQUS-like damping of hyperfoam with the
/// initial elastic stiffness), C_e(F) = the elastic base's tangent at the current deformation (w = 1: damping that
/// follows the foam's stiffness, soft on the plateau, stiff in densification). w in [0, 1] mixes the two.
/// G(F) : X = sym(C^-1 X S_e) (S_e the elastic base's PK2 stress at F) is the initial-stress part of the nominal
/// (first) elasticity tensor dP/dF with the spin left out (docs/physics.md 5.4d): with the nominal share m = 1 the
/// current tangent is the nominal one, so that in a uniaxial test at nu = 0 (F = diag(l, 1, 1)) the damping's nominal
/// stress is beta_s E_t l_dot, E_t = dP/dl the slope of the force-deflection curve, and the loss factor it adds is
/// omega beta_s at every preload (m = 0: the Green-Lagrange tangent, nominal beta_s (E_t - S_e) l_dot). C_e is
/// taken at the start of the increment (F_old): a first-order lag that keeps the increment tangent exact,
/// dS/dE = dS_inner/dE + beta_s omega_r^(1-q) W(dt) C_d, W the bank's increment weight (1/dt at q = 1). For q < 1 the
/// bank's memories hold C_d-weighted strain increments (stress-like Voigt, MPa), 6 doubles a branch plus 6 for its
/// spring: each increment enters with the C_d of its own start.
/// Frequency domain about F_base: C* = C*_inner + beta_s omega_r^(1-q) G(i omega) C_d(F_base), G the bank's transfer
/// function (i omega at q = 1: loss growing linearly with frequency; (i omega)^q to 0.2 % for q < 1).
/// Mass-proportional (Rayleigh alpha) damping is a structural term, not a material one: it belongs
/// to the solver's dynamic step, not here.
#include "material/effect_decorator.hpp"
#include "material/hyperelastic.hpp"
#include "material/spring_pot.hpp"

namespace cushion::material {

class StiffnessDampingEffect final : public EffectDecorator {
 public:
  /// elastic_base: supplies C0 = dS/dE at F = I and C_e(F) (not null); beta_s [s] >= 0; current_share w in [0, 1];
  /// order q in (0, 1]; reference_frequency_Hz f_r > 0; stretch_exponent n finite; nominal_share m in [0, 1]; else
  /// std::invalid_argument.
  StiffnessDampingEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> elastic_base,
                         double beta_s, double current_share = 0.0, double order = 1.0,
                         double reference_frequency_Hz = 5.0, double stretch_exponent = 0.0,
                         double nominal_share = 0.0);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  const Mat6& initial_tangent() const { return C0_; }  ///< C0 [MPa], Voigt
  /// C_d(F) = J^-n [(1 - w) C0 + w (C_e(F) + m G(F))] [MPa], Voigt (rows stress-like PK2, columns strain-like
  /// Green-Lagrange), F the deformation gradient (reference frame), J = det F.
  Mat6 damping_tangent(const Mat3& F) const;
  double beta_s() const { return beta_; }             ///< [s]
  double current_share() const { return share_; }     ///< w [-]
  double order() const { return bank_.order(); }      ///< q [-]
  double stretch_exponent() const { return exponent_; }  ///< n [-]
  double nominal_share() const { return nominal_; }      ///< m [-]
  /// beta_s omega_r^(1-q) [s^q]: the factor of C_d : D^q E.
  double coefficient() const { return coefficient_; }

 private:
  StiffnessDampingEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> elastic_base,
                         double beta_s, double current_share, SpringPotBank bank, double reference_frequency_Hz,
                         double stretch_exponent, double nominal_share);

  std::shared_ptr<const Hyperelastic> base_;
  Mat6 C0_;
  double beta_, share_;
  SpringPotBank bank_;
  double coefficient_;
  double exponent_;
  double nominal_;
};

}  // namespace cushion::material
