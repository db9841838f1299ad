#pragma once
/// Finite-strain Prony viscoelasticity wrapping any elastic base (FEBio-style, on the total PK2 stress):
///   S = S_inf(E) + sum_i a_i H_i,   H_i(t) = int_0^t exp(-(t-s)/tau_i) dS_inf/ds ds,
/// with S_inf the LONG-TERM base stress and a_i = g_i / (1 - sum_j g_j) for ABAQUS relative moduli g_i
/// (g_R(t) = 1 - sum g_i (1 - e^{-t/tau_i})). Small strain: E(t) = E_inf (1 + sum a_i e^{-t/tau_i}).
/// Update, exact for S_inf linear in time over the increment (second order in dt):
///   H_i^{n+1} = e^{-x} H_i^n + (1 - e^{-x})/x (S_inf^{n+1} - S_inf^n),  x = dt / tau_i,
/// tangent dS/dE = C_inf (1 + sum a_i (1 - e^{-x})/x). Same relaxation for shear and bulk, as ABAQUS
/// requires for hyperfoam. State per point: S_inf^n (6) then H_1..H_n (6 each).
/// Frequency domain about a relaxed base F_b: dS* = (1 + sum a_i i w tau_i / (1 + i w tau_i)) C_inf(F_b) dE*.
#include <memory>
#include <vector>

#include "material/hyperelastic.hpp"

namespace cushion::material {

/// One Prony term in ABAQUS form: relative modulus g_i (fraction of the instantaneous modulus) and time.
struct PronyTerm {
  double g = 0.0;    ///< relative modulus g_i [-], g_i >= 0, sum g_i < 1
  double tau = 0.0;  ///< relaxation time tau_i [s], > 0
};

/// How the base hyperelastic constants are to be read when combined with viscoelasticity.
enum class ModuliConvention {
  long_term,     ///< base constants are the fully relaxed ones (ABAQUS default MODULI=LONG TERM)
  instantaneous  ///< base constants are the instantaneous (t = 0+) ones (MODULI=INSTANTANEOUS)
};

/// Converts absolute moduli (the paper's Table 3: E_inf, E_1..E_n, same unit) to relative g_i = E_i / E_0,
/// E_0 = E_inf + sum E_i (the instantaneous modulus). Throws std::invalid_argument on negative values.
std::vector<PronyTerm> prony_from_absolute(double E_inf, const std::vector<double>& E, const std::vector<double>& tau);

/// Decay e^{-x} and weight (1 - e^{-x})/x, x = dt/tau, of the exact recursion of a Prony state over an
/// increment dt [s] for a relaxation time tau [s] when the long-term stress is linear in time over the
/// increment (expm1 form; both 1 at dt = 0, the instantaneous jump): H_n+1 = decay H_n + weight dS_inf.
struct PronyRecursion {
  double decay, weight;
};
PronyRecursion prony_recursion(double dt, double tau);

/// Complex modulus factor 1 + sum a_i i w tau_i / (1 + i w tau_i), a_i = g_i/(1 - sum g) (w in rad/s):
/// multiply a long-term modulus by it to get the storage (real) and loss (imaginary) moduli.
std::complex<double> prony_complex_factor(const std::vector<PronyTerm>& terms, double omega);

/// What an edit of a Prony memory gives (PronyMemory::drive_memory): the stress at F_new rises by k dS, and dk_dE
/// [Voigt, per unit Green-Lagrange strain] is k's gradient at fixed dS (0 unless the memory's weight depends on F).
struct MemoryGain {
  double k = 0.0;  ///< [-]
  Vec6 dk_dE = Vec6::Zero();
};

/// A model whose stress holds a Prony memory that an effect directly above may drive with more long-term stress
/// (mullins' relaxation share): the Viscoelastic, or strain_dependent_prony over it. Its state starts with the
/// long-term stress S_inf^n [MPa, PK2] that the Viscoelastic stored (6 doubles), the reference of the next increment.
class PronyMemory {
 public:
  virtual ~PronyMemory() = default;
  /// Adds to the memory of state_new (which this model's integrate wrote over an increment dt [s] to F_new) as if the
  /// long-term stress had risen by dS [MPa, PK2] more over that increment.
  virtual MemoryGain drive_memory(const Mat3& F_new, std::span<double> state_new, double dt, const Vec6& dS) const = 0;
  /// About a relaxed base F_base at omega [rad/s]: the complex factor of a long-term stress oscillation that enters
  /// the memory (Viscoelastic: prony_complex_factor; 1 + the viscous part).
  virtual std::complex<double> memory_complex_factor(const Mat3& F_base, double omega) const = 0;
};

class Viscoelastic final : public Material, public PronyMemory {
 public:
  /// base: elastic model whose constants are read per `convention`; at most 20 terms; throws
  /// std::invalid_argument on g < 0, sum g >= 1, tau <= 0.
  Viscoelastic(std::shared_ptr<const Hyperelastic> base, std::vector<PronyTerm> terms,
               ModuliConvention convention = ModuliConvention::long_term);

  std::size_t state_size() const override { return 6 * (1 + terms_.size()); }
  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                          std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  /// sum a_i H_i [MPa] from the state (= S - S_inf(F)).
  Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const override;
  std::string describe() const override;

  const Hyperelastic& long_term_base() const { return *long_term_; }
  const std::vector<PronyTerm>& terms() const { return terms_; }
  /// a_i = g_i / (1 - sum g): Prony moduli relative to the long-term modulus.
  const std::vector<double>& relative_to_long_term() const { return a_; }
  /// Adds q_i dS [MPa] to every memory H_i of `state` (a state this model wrote over an increment dt [s]; q_i =
  /// (1 - e^{-x})/x, x = dt/tau_i): as if the long-term stress had risen by dS more over that increment. Returns
  /// sum a_i q_i, the factor of that rise on the viscous stress. For effects that change what enters the memory
  /// (strain_dependent_prony's history share, mullins' relaxation share).
  double add_to_memory(std::span<double> state, double dt, const Vec6& dS) const;
  /// k = add_to_memory's factor, dk_dE = 0.
  MemoryGain drive_memory(const Mat3& F_new, std::span<double> state_new, double dt, const Vec6& dS) const override;
  std::complex<double> memory_complex_factor(const Mat3& F_base, double omega) const override;

 private:
  std::shared_ptr<const Hyperelastic> long_term_;
  std::vector<PronyTerm> terms_;
  std::vector<double> a_;
};

}  // namespace cushion::material
