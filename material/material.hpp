#pragma once
/// The solver-material contract (after MFront/MGIS): a material is constant parameters plus a
/// pure function of the increment. The caller (solver, point driver) owns the internal-state
/// arrays, passes the committed `state_old`, receives `state_new`, and alone decides to commit
/// or revert. Materials hold no mutable data and are safe to call from several threads.
///
/// Units everywhere inside cushion: length mm, force N, time s, stress and moduli MPa (N/mm^2),
/// energy density MPa (mJ/mm^3), mass density t/mm^3. Files carry their own units (e.g. "mu_kPa")
/// and are converted on reading.
#include <span>
#include <string>

#include "material/tensor.hpp"

namespace cushion::material {

/// Outcome of a material-point integration (three-valued, as in MGIS).
enum class Status {
  ok,          ///< converged, stress and tangent valid
  unreliable,  ///< valid but outside the range the model was checked for (e.g. Drucker-unstable)
  failed       ///< no valid result (J <= 0, non-finite stress): the caller must cut back
};

/// Result of one increment at one point.
struct PointResponse {
  Vec6 S = Vec6::Zero();      ///< second Piola-Kirchhoff stress at F_new [MPa], reference frame, Voigt stress order
  Mat6 dS_dE = Mat6::Zero();  ///< consistent tangent dS_new/dE_new [MPa], reference frame, Voigt (engineering shear in E)
  Status status = Status::ok;
  double dt_factor = 1.0;     ///< proposed factor for the next increment (< 1 asks for a cut-back)
  std::string message;        ///< why, when status != ok
};

/// Any constitutive model. Implementations: Hyperfoam, NeoHookean (elastic bases) and
/// Viscoelastic (Prony wrapper over any elastic base).
class Material {
 public:
  virtual ~Material() = default;

  /// Number of doubles of internal state per integration point (0 for elastic models).
  virtual std::size_t state_size() const = 0;

  /// Writes the virgin state (undeformed, fully relaxed) into `state` (size state_size()).
  virtual void initial_state(std::span<double> state) const;

  /// Integrates from the committed state at F_old to F_new over the time increment dt [s].
  /// F_old, F_new: deformation gradients (reference -> current, dimensionless). `state_old` is
  /// read only; `state_new` (same size) receives the updated state. dt = 0 gives the
  /// instantaneous (elastic) response from state_old.
  virtual PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                  std::span<const double> state_old,
                                  std::span<double> state_new) const = 0;

  /// Small-amplitude complex tangent dS/dE*(omega) [MPa] about a base state F_base held long
  /// enough to be fully relaxed (long-term base, the ABAQUS *STEADY STATE DYNAMICS convention).
  /// omega in rad/s; convention: strain e^{+i omega t}, Im > 0 is loss. Elastic models return
  /// their real tangent. Reference frame, Voigt as in tensor.hpp.
  virtual Mat6c complex_tangent(const Mat3& F_base, double omega) const = 0;

  /// Viscous part of the PK2 stress [MPa] (reference frame, Voigt stress order) at F_new = F with
  /// the state `state` that integrate() wrote there (state_new): the part that relaxes at rest
  /// (Prony terms; S - S_inf for Viscoelastic). For output only. Default: zero (no viscous stress).
  virtual Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const;

  /// One-line human-readable description (model name and main parameters, with units).
  virtual std::string describe() const = 0;
};

}  // namespace cushion::material
