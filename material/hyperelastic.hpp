#pragma once
/// Elastic (stateless) base models: a strain energy W(C) with its PK2 stress and material tangent.
#include <memory>

#include "material/material.hpp"

namespace cushion::material {

/// Energy, stress and tangent of a hyperelastic model at one F.
struct ElasticEval {
  double W = 0.0;             ///< strain energy per reference volume [MPa = mJ/mm^3]
  Vec6 S = Vec6::Zero();      ///< PK2 stress 2 dW/dC [MPa], reference frame, Voigt stress order
  Mat6 dS_dE = Mat6::Zero();  ///< material tangent 4 d2W/dC2 [MPa], Voigt (engineering shear in E)
  Status status = Status::ok;
  std::string message;
};

/// A hyperelastic model: pure function of F. Also a Material with no internal state.
class Hyperelastic : public Material {
 public:
  /// W, S, dS/dE at F (dimensionless deformation gradient).
  virtual ElasticEval evaluate(const Mat3& F) const = 0;

  /// A copy with every modulus multiplied by `factor` (used for the INSTANTANEOUS/LONG TERM
  /// conversion: W scales linearly with the moduli in every model here).
  virtual std::shared_ptr<const Hyperelastic> scaled(double factor) const = 0;

  /// Initial (small-strain) shear and bulk moduli at F = I [MPa].
  virtual double initial_shear_modulus() const = 0;
  virtual double initial_bulk_modulus() const = 0;

  std::size_t state_size() const override { return 0; }
  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                          std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
};

}  // namespace cushion::material
