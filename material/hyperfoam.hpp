#pragma once
/// ABAQUS "Hyperfoam" (Hill / Storakers compressible Ogden) without thermal strain:
///   W = sum_i 2 mu_i / alpha_i^2 [ l1^a_i + l2^a_i + l3^a_i - 3 + (1/beta_i)(J^(-a_i beta_i) - 1) ],
///   beta_i = nu_i / (1 - 2 nu_i), with the beta_i -> 0 limit (1/beta)(J^(-a beta) - 1) -> -a ln J.
/// Kirchhoff principal stress tau_a = 2 sum_i (mu_i/alpha_i)(l_a^a_i - J^(-a_i beta_i)); PK2 S_a = tau_a / l_a^2.
/// Initial moduli: mu0 = sum mu_i, K0 = sum 2 mu_i (1/3 + beta_i).
#include <cstdint>
#include <vector>

#include "material/hyperelastic.hpp"

namespace cushion::material {

/// One term of the hyperfoam series (ABAQUS *HYPERFOAM data line: mu_i, alpha_i, nu_i).
struct HyperfoamTerm {
  double mu = 0.0;     ///< mu_i [MPa] (may be negative if the sum stays stable)
  double alpha = 0.0;  ///< alpha_i [-], non-zero
  double nu = 0.0;     ///< nu_i [-] in [0, 0.5): finite-strain Poisson ratio of the term
  double beta() const { return nu / (1.0 - 2.0 * nu); }
};

class Hyperfoam final : public Hyperelastic {
 public:
  /// 1 <= terms.size() <= 6; throws std::invalid_argument otherwise or on alpha = 0, nu outside [0, 0.5).
  explicit Hyperfoam(std::vector<HyperfoamTerm> terms);

  /// W [MPa], S [MPa, PK2] and dS/dE [MPa] at F. Remembers its last result per thread, keyed by this instance (a
  /// number no other Hyperfoam of the process has; the terms never change after construction) and the exact F, and
  /// returns it again for the same F: a Viscoelastic and a Mullins effect above it evaluate the same base at the same
  /// F in one increment, and a held strain repeats F (docs/physics.md 9.11).
  ElasticEval evaluate(const Mat3& F) const override;
  std::shared_ptr<const Hyperelastic> scaled(double factor) const override;
  double initial_shear_modulus() const override;
  double initial_bulk_modulus() const override;
  std::string describe() const override;

  const std::vector<HyperfoamTerm>& terms() const { return terms_; }

  /// Kirchhoff principal stresses tau_a [MPa] for principal stretches l (closed form).
  Vec3 principal_kirchhoff(const Vec3& l) const;

 private:
  std::vector<HyperfoamTerm> terms_;
  std::uint64_t id_ = 0;  ///< the evaluation memo's key (copies share it: same terms)
};

}  // namespace cushion::material
