#pragma once
/// Pneumatic (air-flow, Darcy) damping of open-cell foam as a LUMPED extra pressure (docs/physics.md 5.1).
///
/// Air expelled from a layer of half-width R compressed at volumetric rate -dJ/dt flows laterally
/// through the cells by Darcy's law; the mean extra stress of the layer is eta eps_dot R^2 / (8 K)
/// (Darcy + continuity, lateral escape). This effect adds that mean pressure at every point:
///   extra Kirchhoff pressure  p_air = -(eta_air R^2 / (8 K(J))) (dJ/dt) / J,
///   extra PK2 stress          S_air = -p_air C^{-1}       (Kirchhoff tau_air = -p_air I),
///   permeability              K(J) = K0 J^{n_K}           (n_K >= 0: K falls with compression [A],
///                                                          cf. Dawson, Germaine & Gibson, IJSS 44, 2007),
/// with the backward-Euler rate dJ/dt = (J_new - J_old)/dt from F_old (dt = 0: no extra stress).
/// Compression (dJ/dt < 0) gives p_air > 0, a compressive extra stress. Time scale of the effect
/// tau_air ~ eta R^2 / (8 K M) (M: drained modulus): it grows as K falls and with R^2.
///
/// It is NOT a poroelastic (Biot) FE model: the pore pressure is not a field and does not diffuse
/// between elements; R is a user/case parameter (half the specimen width or drainage path), which
/// makes the model SIZE-DEPENDENT: a Prony series fitted on a small block misses it on a large one.
/// No own state (uses F_old). Frequency domain about a relaxed base F_b (p_air = 0 there):
///   dS* = i omega (eta R^2 / (8 K(J_b))) C_b^{-1} (x) C_b^{-1} : dE*   added to the inner tangent.
#include "material/effect_decorator.hpp"

namespace cushion::material {

/// Parameters in internal units (mm, s, MPa).
struct PneumaticParameters {
  double drainage_length = 40.0;     ///< R [mm], > 0: half-width of the specimen (lateral drainage path)
  double permeability = 1e-3;        ///< K0 [mm^2] at J = 1, > 0 (1e-3 mm^2 = 1e-9 m^2)
  double permeability_exponent = 2;  ///< n_K [-], >= 0: K = K0 J^{n_K}
  double air_viscosity = 1.8e-11;    ///< eta_air [MPa s] (1.8e-5 Pa s), > 0
};

class PneumaticEffect final : public EffectDecorator {
 public:
  /// Throws std::invalid_argument on parameters outside the ranges above.
  PneumaticEffect(std::shared_ptr<const Material> inner, PneumaticParameters parameters);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  std::string describe() const override;

  /// Damping coefficient eta R^2 / (8 K(J)) [MPa s] at volume ratio J.
  double coefficient(double J) const;
  const PneumaticParameters& parameters() const { return p_; }

 private:
  PneumaticParameters p_;
};

}  // namespace cushion::material
