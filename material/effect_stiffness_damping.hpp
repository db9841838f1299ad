#pragma once
/// Stiffness-proportional (Rayleigh beta) damping at material level, the paper's beta = 1e-4 s:
///   S_d = beta_s C0 : (E_new - E_old) / dt      (backward-Euler rate; dt = 0: no extra stress),
/// C0 = tangent of the elastic base at F = I (constant: ABAQUS also damps hyperfoam with the initial
/// elastic stiffness). Tangent adds beta_s C0 / dt. No own state (uses F_old).
/// Frequency domain: C* = C*_inner + i omega beta_s C0 (loss growing linearly with frequency).
/// Mass-proportional (Rayleigh alpha) damping is a structural term, not a material one: it belongs
/// to the solver's dynamic step, not here.
#include "material/effect_decorator.hpp"
#include "material/hyperelastic.hpp"

namespace cushion::material {

class StiffnessDampingEffect final : public EffectDecorator {
 public:
  /// elastic_base: supplies C0 = dS/dE at F = I (not null); beta_s [s] >= 0, else std::invalid_argument.
  StiffnessDampingEffect(std::shared_ptr<const Material> inner, const Hyperelastic& elastic_base, double beta_s);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  const Mat6& initial_tangent() const { return C0_; }  ///< C0 [MPa], Voigt
  double beta_s() const { return beta_; }             ///< [s]

 private:
  Mat6 C0_;
  double beta_;
};

}  // namespace cushion::material
