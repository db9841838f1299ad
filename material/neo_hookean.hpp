#pragma once
/// Compressible neo-Hookean, W = mu/2 (I1 - 3 - 2 ln J) + lambda/2 (ln J)^2 (reference model for tests).
#include "material/hyperelastic.hpp"

namespace cushion::material {

class NeoHookean final : public Hyperelastic {
 public:
  /// mu, lambda: Lame constants [MPa]; mu > 0, lambda > -2 mu / 3.
  NeoHookean(double mu, double lambda);

  ElasticEval evaluate(const Mat3& F) const override;
  std::shared_ptr<const Hyperelastic> scaled(double factor) const override;
  double initial_shear_modulus() const override { return mu_; }
  double initial_bulk_modulus() const override { return lambda_ + 2.0 * mu_ / 3.0; }
  std::string describe() const override;

 private:
  double mu_, lambda_;
};

}  // namespace cushion::material
