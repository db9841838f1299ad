// Requirement: the pneumatic (Darcy air-flow) effect adds the documented lumped extra pressure
// eta R^2/(8 K(J)) (-dJ/dt)/J, reduces to the Darcy layer formula of docs/physics.md 5.1 at small strain,
// scales with R^2, has an exact increment tangent, and its complex tangent matches a time-domain sine.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>

#include "material/effect_pneumatic.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

PneumaticParameters strong_air(double R = 40.0) {
  PneumaticParameters p;
  p.drainage_length = R;
  p.permeability = 1e-4;  // mm^2: coefficient eta R^2/(8 K0) = 3.6e-5 MPa s at R = 40 mm
  p.permeability_exponent = 2.0;
  return p;
}

Mat3 confined(double J) { return Vec3(J, 1.0, 1.0).asDiagonal(); }

/// Extra first Piola-Kirchhoff stress P11 of the effect over its base for one increment.
double extra_P11(const PneumaticEffect& m, double J_old, double J_new, double dt) {
  std::vector<double> none;
  const PointResponse r = m.integrate(confined(J_old), confined(J_new), dt, none, none);
  EXPECT_EQ(r.status, Status::ok) << r.message;
  return J_new * (r.S(0) - m.inner().integrate(confined(J_old), confined(J_new), dt, none, none).S(0));
}

TEST(EffectPneumatic, TangentMatchesFiniteDifferences) {
  // Random F_old, F_new (det > 0.2), dt = 0.01 s, over hyperfoam and over a viscoelastic inner with a
  // non-trivial state; tolerance 1e-6 relative.
  std::mt19937 rng(11);
  const PneumaticEffect on_foam(test::effect_test_foam(), strong_air());
  const PneumaticEffect on_visco(test::effect_test_visco(), strong_air());
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
    EXPECT_LT(test::increment_tangent_error(on_foam, F_old, F_new, 0.01, {}), 1e-6) << "trial " << trial;
    std::vector<double> state(on_visco.state_size()), next(on_visco.state_size());
    on_visco.initial_state(state);
    on_visco.integrate(Mat3::Identity(), F_old, 0.02, state, next);
    EXPECT_LT(test::increment_tangent_error(on_visco, F_old, F_new, 0.01, next), 1e-6) << "trial " << trial;
  }
}

TEST(EffectPneumatic, ConstantVolumetricRateGivesTheDocumentedPressure) {
  // Confined compression J(t) = 1 - rate t (exactly constant dJ/dt): extra P11 = -p/J with
  // p = eta R^2 rate / (8 K0 J^n J); checked along the ramp to J = 0.4, tolerance 1e-10 relative.
  const PneumaticParameters p = strong_air();
  const PneumaticEffect m(test::effect_test_foam(), p);
  const double rate = 2.0, dt = 1e-3;
  for (int k = 0; k < 300; k += 37) {
    const double J_old = 1.0 - rate * dt * k, J_new = 1.0 - rate * dt * (k + 1);
    const double K = p.permeability * std::pow(J_new, p.permeability_exponent);
    const double pressure = p.air_viscosity * p.drainage_length * p.drainage_length * rate / (8.0 * K * J_new);
    EXPECT_NEAR(extra_P11(m, J_old, J_new, dt), -pressure / J_new, 1e-10 * pressure / J_new) << "J = " << J_new;
  }
}

TEST(EffectPneumatic, SmallStrainLimitIsTheDarcyLayerFormula) {
  // docs/physics.md 5.1: mean extra stress of a layer of half-width R at rate eps_dot is eta eps_dot R^2/(8K).
  // First increment from J = 1 with strain 1e-6: agreement to O(strain), tolerance 1e-5 relative.
  const PneumaticParameters p = strong_air();
  const PneumaticEffect m(test::effect_test_foam(), p);
  const double rate = 0.5, dt = 2e-6;
  const double darcy = p.air_viscosity * rate * p.drainage_length * p.drainage_length / (8.0 * p.permeability);
  EXPECT_NEAR(extra_P11(m, 1.0, 1.0 - rate * dt, dt), -darcy, 1e-5 * darcy);
}

TEST(EffectPneumatic, ExtraStressScalesWithDrainageLengthSquared) {
  // Same increment, R = 20, 40, 80 mm: extra stress ratios 4 and 16, tolerance 1e-12 relative.
  const double s20 = extra_P11(PneumaticEffect(test::effect_test_foam(), strong_air(20.0)), 0.8, 0.79, 0.01);
  const double s40 = extra_P11(PneumaticEffect(test::effect_test_foam(), strong_air(40.0)), 0.8, 0.79, 0.01);
  const double s80 = extra_P11(PneumaticEffect(test::effect_test_foam(), strong_air(80.0)), 0.8, 0.79, 0.01);
  EXPECT_NEAR(s40 / s20, 4.0, 4e-12);
  EXPECT_NEAR(s80 / s20, 16.0, 16e-12);
  EXPECT_LT(s20, 0.0);  // compression rate -> compressive extra stress
}

TEST(EffectPneumatic, NoExtraStressWithoutRate) {
  // dt = 0 (instantaneous response) and a held state (F_old = F_new) add nothing: exact.
  const PneumaticEffect m(test::effect_test_foam(), strong_air());
  std::vector<double> none;
  const Mat3 F = confined(0.7);
  EXPECT_EQ(m.integrate(Mat3::Identity(), F, 0.0, none, none).S, m.inner().integrate(F, F, 0.0, none, none).S);
  EXPECT_EQ(m.integrate(F, F, 0.5, none, none).S, m.inner().integrate(F, F, 0.5, none, none).S);
}

TEST(EffectPneumatic, ComplexTangentMatchesTimeDomainSine) {
  // Point driver, uniaxial stress (nu = 0.1), 25 % preload held 1 s, sine amplitude 1e-4 at 1, 5, 20 Hz,
  // 1000 steps per cycle (backward-Euler rate: phase error ~ pi/1000 of the air part). Tolerances
  // 0.5 % on |E*| and 0.2 deg on the phase; the air loss must be visible (> 2 deg at 20 Hz).
  const PneumaticEffect m(test::effect_test_foam(), strong_air());
  for (double f : {1.0, 5.0, 20.0}) {
    const test::SineComparison c = test::compare_sine(m, -0.25, 1.0, 1, f, 6, 1000);
    std::printf("  %5.1f Hz: |E*| rel. diff %.2e, phase diff %.4f deg (phase %.3f deg)\n", f, c.modulus_error(),
                c.phase_error_deg(), c.phase_deg());
    EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
    if (f == 20.0) {
      EXPECT_GT(c.phase_deg(), 2.0);
    }
  }
}

}  // namespace
}  // namespace cushion::material
