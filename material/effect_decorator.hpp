#pragma once
/// Common frame of the optional physical effects (material/effect_*.hpp): an effect is a Material
/// DECORATOR that wraps an inner Material and adds to or modifies its PK2 stress, tangent and state.
/// State layout per point: the inner model's state first, then the effect's own doubles, so effects
/// stack (each one sees the previous stack as its inner model). The caller owns the state arrays.
/// Also the kinematic derivatives every effect needs, in the Voigt convention of material/tensor.hpp.
#include <memory>

#include "material/material.hpp"

namespace cushion::material {

/// dJ/dE = J C^{-1}, J = det F (dimensionless), as a stress-like Voigt vector (dJ = dot(dJ_dE, dE_voigt)).
Vec6 dJ_dE(const Mat3& F);

/// d(C^{-1})/dE as a 6x6 Voigt matrix: d(C^{-1})_ij / dE_kl = -(Ci_ik Ci_jl + Ci_il Ci_jk), Ci = C^{-1}.
Mat6 dCinv_dE(const Mat3& C_inverse);

/// The linear map X -> A X B on symmetric X as a 6x6 Voigt matrix (columns strain-like, engineering shear; rows
/// stress-like): (A X B)_ij = sum_K box(A, B)(ij, K) X_K, box(A, B)(ij, kl) = (A_ik B_lj + A_il B_kj)/2.
Mat6 box_voigt(const Mat3& A, const Mat3& B);

/// The symmetric fourth-order identity (dE_ij / dE_kl) in Voigt: diag(1, 1, 1, 1/2, 1/2, 1/2).
Mat6 symmetric_identity_voigt();

/// Frobenius norm sqrt(A:A) of a symmetric tensor given as a stress-like Voigt vector.
double tensor_norm(const Vec6& stress_like);

/// Worse of two statuses (failed > unreliable > ok), keeping the message of the worse one.
void combine_status(PointResponse& into, Status status, const std::string& message);

/// Base of the effect decorators: owns the inner model and splits the state arrays.
class EffectDecorator : public Material {
 public:
  /// inner: the model being decorated (not null, else std::invalid_argument); own_size: the
  /// effect's own state doubles, stored after the inner state.
  EffectDecorator(std::shared_ptr<const Material> inner, std::size_t own_size);

  std::size_t state_size() const override { return inner_->state_size() + own_size_; }
  /// Inner virgin state, then own_initial_state() for the effect's part.
  void initial_state(std::span<double> state) const override;
  /// The inner model's viscous stress [MPa] on the inner part of the state; effects that rescale
  /// the inner stress (Mullins, strain-dependent Prony) scale it alike. Rate terms computed from
  /// F_old (stiffness damping, the pneumatic dashpot) and the pneumatic air pressure are not included.
  Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const override;

  const Material& inner() const { return *inner_; }

 protected:
  /// Virgin value of the effect's own state (default: zeros).
  virtual void own_initial_state(std::span<double> own) const;

  /// Checks the span sizes and integrates the inner model on the inner part of the state.
  /// A response with status failed is returned as is (wrong sizes, dt < 0 or inner failure).
  PointResponse integrate_inner(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                                std::span<double> state_new) const;
  std::span<const double> own(std::span<const double> state) const { return state.subspan(inner_->state_size()); }
  std::span<double> own(std::span<double> state) const { return state.subspan(inner_->state_size()); }

  std::shared_ptr<const Material> inner_;
  std::size_t own_size_;
};

}  // namespace cushion::material
