#pragma once
/// ABAQUS/CalculiX compressible Ogden rubber (*HYPERELASTIC, OGDEN; NEO HOOKE is N = 1, alpha = 2,
/// mu = 2 C10), with the isochoric/volumetric split:
///   W = sum_i 2 mu_i / alpha_i^2 (lb1^a_i + lb2^a_i + lb3^a_i - 3) + sum_k (J - 1)^(2k) / D_k,
///   lb_a = J^(-1/3) l_a (deviatoric principal stretches), D_k > 0 or 0 (term absent), not all 0.
/// Kirchhoff principal stress tau_a = sum_i 2 mu_i/alpha_i (lb_a^a_i - m_i) + J U'(J),
/// m_i = (lb1^a_i + lb2^a_i + lb3^a_i) / 3, U(J) = sum_k (J - 1)^(2k) / D_k.
/// Initial moduli: mu0 = sum mu_i, K0 = 2 / D_1.
#include <vector>

#include "material/hyperelastic.hpp"

namespace cushion::material {

/// One Ogden term (*HYPERELASTIC, OGDEN data: mu_i, alpha_i; then the D_i).
struct OgdenTerm {
  double mu = 0.0;     ///< mu_i [MPa]
  double alpha = 0.0;  ///< alpha_i [-], non-zero
};

class Ogden final : public Hyperelastic {
 public:
  /// 1 <= terms.size() <= 6; D: 1..6 compressibility coefficients [1/MPa], each >= 0, D[0] > 0.
  /// Throws std::invalid_argument otherwise, on alpha = 0 or on mu0 = sum mu_i <= 0.
  Ogden(std::vector<OgdenTerm> terms, std::vector<double> D);
  ElasticEval evaluate(const Mat3& F) const override;
  std::shared_ptr<const Hyperelastic> scaled(double factor) const override;
  double initial_shear_modulus() const override;
  double initial_bulk_modulus() const override { return 2.0 / D_.front(); }
  std::string describe() const override;
  const std::vector<OgdenTerm>& terms() const { return terms_; }
  const std::vector<double>& D() const { return D_; }

 private:
  std::vector<OgdenTerm> terms_;
  std::vector<double> D_;
};

}  // namespace cushion::material
