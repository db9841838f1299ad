#pragma once
/// Stiffness-proportional (Rayleigh beta) damping at material level, the paper's beta = 1e-4 s:
///   S_d = beta_s C_d : (E_new - E_old) / dt      (backward-Euler rate; dt = 0: no extra stress),
///   C_d = (1 - w) C0 + w C_e(F_old),
/// C0 = tangent dS/dE of the elastic base at F = I (w = 0, the default: ABAQUS-like damping of hyperfoam with the
/// initial elastic stiffness), C_e(F) = the elastic base's tangent at the current deformation (w = 1: damping that
/// follows the foam's stiffness, soft on the plateau, stiff in densification). w in [0, 1] mixes the two. C_e is
/// taken at the start of the increment (F_old): a first-order lag that keeps the increment tangent exact,
/// dS/dE = dS_inner/dE + beta_s C_d / dt (docs/physics.md 5.4). No own state (uses F_old).
/// Frequency domain about F_base: C* = C*_inner + i omega beta_s C_d(F_base) (loss growing linearly with frequency).
/// Mass-proportional (Rayleigh alpha) damping is a structural term, not a material one: it belongs
/// to the solver's dynamic step, not here.
#include "material/effect_decorator.hpp"
#include "material/hyperelastic.hpp"

namespace cushion::material {

class StiffnessDampingEffect final : public EffectDecorator {
 public:
  /// elastic_base: supplies C0 = dS/dE at F = I and C_e(F) (not null); beta_s [s] >= 0; current_share w in [0, 1];
  /// else std::invalid_argument.
  StiffnessDampingEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> elastic_base,
                         double beta_s, double current_share = 0.0);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  const Mat6& initial_tangent() const { return C0_; }  ///< C0 [MPa], Voigt
  /// C_d(F) = (1 - w) C0 + w C_e(F) [MPa], Voigt, F the deformation gradient (reference frame).
  Mat6 damping_tangent(const Mat3& F) const;
  double beta_s() const { return beta_; }             ///< [s]
  double current_share() const { return share_; }     ///< w [-]

 private:
  std::shared_ptr<const Hyperelastic> base_;
  Mat6 C0_;
  double beta_, share_;
};

}  // namespace cushion::material
