#pragma once
/// Prony moduli that scale with the compression level (the paper's suspect that a series fitted at
/// one preload fails at another, section 5 "Discussion", point 2). Wraps a Viscoelastic model
///   S = S_inf + sum a_i H_i   (material/viscoelastic.hpp, same state)
/// and makes its viscous part depend on the volume ratio J = det F through f(J) = exp(c g(J)), g = (1 - s)(-ln J)
/// + s (1 - J) (c > 0: stronger relaxation in compression; f ~ 1 + c (1 - J) for small strain, positive at any J and c):
/// the strain measure share s in [0, 1] blends the logarithmic measure (s = 0, default: f = J^{-c}) with the nominal
/// volumetric strain 1 - J (s = 1: f = e^{c (1 - J)}, an exponential in the nominal compression, the foreign
/// generator's "a_j -> a_j exp(k e)"); docs/physics.md 5.5. The dependence is split between where it acts by the
/// history share w in [0, 1]:
///   H_i^{n+1} = e^{-x} H_i^n + (1 - e^{-x})/x f(J_{n+1})^w (S_inf^{n+1} - S_inf^n)   (the increment weighted when it
///                                                                                       enters the state),
///   S = S_inf + f(J)^{1-w} sum a_i H_i                                                 (the stored stress scaled now).
/// w = 0 (default): the whole viscous stress scaled by the current f(J) (on unloading the overstress follows J at
/// once); w = 1: each increment keeps the weight of the compression at which it was made, a_i -> a_i f(J) in the
/// hereditary integral (the foreign generator's "a_j -> a_j l^-c"). Tangent, with phi = f(J_{n+1}), A C_inf the inner
/// viscous tangent (A = sum a_i (1 - e^{-x_i})/x_i), V = sum a_i H_i^{n+1} and dphi/dE = -c phi ((1 - s)/J + s) dJ/dE:
///   dS/dE = C_inf + phi^{1-w} [phi^w A C_inf + w phi^{w-1} (sum a_i (1 - e^{-x_i})/x_i) dS_inf (x) dphi/dE]
///           + (1 - w) phi^{-w} V (x) dphi/dE   (docs/physics.md 5.5).
/// State: exactly the Viscoelastic state (S_inf^n, then H_1..H_n; with w > 0 the H_i hold the weighted history), no own
/// doubles. Small-amplitude relaxation about a relaxed preload J_b has amplitude f(J_b) sum a_i e^{-t/tau_i} for every
/// w, and in the frequency domain (H_i = 0 at the relaxed base, so the dphi/dE terms vanish):
///   C* = C_inf(F_b) (1 + f(J_b) sum a_i i w tau_i / (1 + i w tau_i)).
/// As a PronyMemory (mullins' relaxation share directly above, docs/physics.md 5.2): a long-term stress dS more
/// enters each H_i weighted by phi^w and leaves scaled by phi^(1-w), so the stress rises by k dS, k = phi sum a_i q_i
/// (q_i = (1 - e^{-x_i})/x_i), dk/dE = (sum a_i q_i) dphi/dE; its complex factor is 1 + f(J_b) sum a_i i w tau_i /
/// (1 + i w tau_i).
#include "material/effect_decorator.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::material {

class StrainDependentPronyEffect final : public EffectDecorator, public PronyMemory {
 public:
  /// inner: the Viscoelastic model whose Prony part is scaled (not null); c [-] finite; history_share w and
  /// strain_measure_share s in [0, 1]; else std::invalid_argument.
  StrainDependentPronyEffect(std::shared_ptr<const Viscoelastic> inner, double coefficient_c,
                             double history_share = 0.0, double strain_measure_share = 0.0);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  /// f(J)^{1-w} sum a_i H_i [MPa].
  Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const override;
  std::string describe() const override;
  MemoryGain drive_memory(const Mat3& F_new, std::span<double> state_new, double dt, const Vec6& dS) const override;
  std::complex<double> memory_complex_factor(const Mat3& F_base, double omega) const override;

  /// Scale factor f(J) = exp(c ((1 - s)(-ln J) + s (1 - J))) [-] of the Prony contributions.
  double factor(double J) const;
  /// df/dE at F [-] (E the Green-Lagrange strain, reference frame).
  Vec6 dfactor_dE(const Mat3& F) const;
  double coefficient_c() const { return c_; }
  double history_share() const { return w_; }  ///< w [-]
  double strain_measure_share() const { return s_; }  ///< s [-]

 private:
  std::shared_ptr<const Viscoelastic> visco_;
  double c_, w_, s_;
};

}  // namespace cushion::material
