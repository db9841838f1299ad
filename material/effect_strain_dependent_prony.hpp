#pragma once
/// Prony moduli that scale with the compression level (the paper's suspect that a series fitted at
/// one preload fails at another, section 5 "Discussion", point 2). Wraps a Viscoelastic model
///   S = S_inf + sum a_i H_i   (material/viscoelastic.hpp, same state and the same H_i update)
/// and scales its viscous part by a function of the volume ratio J = det F:
///   S = S_inf + f(J) sum a_i H_i,   f(J) = J^{-c}   (c > 0: stronger relaxation in compression;
///   f = e^{-c ln J} ~ 1 + c (-ln J) for small strain, and stays positive at any J and c).
/// Tangent: dS/dE = C_inf + f (C_visco - C_inf) + (sum a_i H_i) (x) df/dE, df/dE = -c f C^{-1}.
/// State: exactly the Viscoelastic state (S_inf^n, then H_1..H_n), no own doubles.
/// Small-amplitude relaxation about a relaxed preload J_b has amplitude f(J_b) sum a_i e^{-t/tau_i},
/// and in the frequency domain (H_i = 0 at the relaxed base, so the df/dE term vanishes):
///   C* = C_inf(F_b) (1 + f(J_b) sum a_i i w tau_i / (1 + i w tau_i)).
#include "material/effect_decorator.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::material {

class StrainDependentPronyEffect final : public EffectDecorator {
 public:
  /// inner: the Viscoelastic model whose Prony part is scaled (not null); c [-] finite, else
  /// std::invalid_argument.
  StrainDependentPronyEffect(std::shared_ptr<const Viscoelastic> inner, double coefficient_c);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  /// f(J) sum a_i H_i [MPa].
  Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const override;
  std::string describe() const override;

  /// Scale factor f(J) = J^{-c} [-] of the Prony contributions.
  double factor(double J) const;
  double coefficient_c() const { return c_; }

 private:
  std::shared_ptr<const Viscoelastic> visco_;
  double c_;
};

}  // namespace cushion::material
