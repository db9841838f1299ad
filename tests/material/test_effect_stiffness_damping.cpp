// Requirement: stiffness-proportional damping adds beta_s C_d dE/dt at any strain, C_d = (1 - w) C0 + w C_e(F_old)
// (C0: initial elastic tangent, C_e: the current one at the start of the increment), has an exact increment
// tangent, and its complex tangent (i omega beta_s C_d(F_base) added) matches a time-domain sine run by the point
// driver, for w = 0 and w = 1.
#include <gtest/gtest.h>

#include <cstdio>

#include "material/effect_stiffness_damping.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

TEST(EffectStiffnessDamping, ConstantRateGivesBetaC0Rate) {
  // E(t) = E_0 + t E_dot (arbitrary finite E_0 and rate, F from C = I + 2E): the extra stress is
  // beta_s C0 E_dot at every step; tolerance 1e-10 relative. C0 is the base tangent at F = I.
  const auto foam = test::effect_test_foam();
  const double beta = 2e-3;
  const StiffnessDampingEffect m(foam, foam, beta);
  EXPECT_EQ(m.initial_tangent(), foam->evaluate(Mat3::Identity()).dS_dE);
  Vec6 E0, E_dot;
  E0 << -0.15, 0.03, 0.02, 0.05, -0.02, 0.01;      // strain-like Voigt
  E_dot << -0.8, 0.1, 0.05, 0.3, 0.2, -0.1;        // [1/s]
  const double dt = 0.01;
  auto F_at = [&](int k) {
    return test::F_from_C(Mat3::Identity() + 2.0 * from_voigt_strain(E0 + k * dt * E_dot));
  };
  const Vec6 expected = beta * m.initial_tangent() * E_dot;
  for (int k = 0; k < 20; k += 4) {
    std::vector<double> none;
    const Vec6 extra = m.integrate(F_at(k), F_at(k + 1), dt, none, none).S - foam->evaluate(F_at(k + 1)).S;
    EXPECT_LT(test::rel_diff(extra, expected), 1e-10) << "step " << k;
  }
}

TEST(EffectStiffnessDamping, TangentMatchesFiniteDifferences) {
  // Random F_old, F_new over hyperfoam and over the viscoelastic model with a non-trivial state;
  // dt = 0.01 s; tolerance 1e-6 relative.
  std::mt19937 rng(31);
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const StiffnessDampingEffect on_foam(foam, foam, 1e-3);
  const StiffnessDampingEffect on_foam_current(foam, foam, 1e-3, 0.6);
  const std::shared_ptr<const Hyperelastic> long_term(visco, &visco->long_term_base());
  const StiffnessDampingEffect on_visco(visco, long_term, 1e-3, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    const Mat3 F_old = test::random_F(rng, 0.3), F = test::random_F(rng, 0.3);
    EXPECT_LT(test::increment_tangent_error(on_foam, F_old, F, 0.01, {}), 1e-6) << "trial " << trial;
    EXPECT_LT(test::increment_tangent_error(on_foam_current, F_old, F, 0.01, {}), 1e-6) << "trial " << trial;
    std::vector<double> state(on_visco.state_size()), next(on_visco.state_size());
    on_visco.initial_state(state);
    on_visco.integrate(Mat3::Identity(), F_old, 0.05, state, next);
    EXPECT_LT(test::increment_tangent_error(on_visco, F_old, F, 0.01, next), 1e-6) << "trial " << trial;
  }
}

TEST(EffectStiffnessDamping, ComplexTangentMatchesTimeDomainSine) {
  // Point driver, uniaxial stress (nu = 0.1), 25 % preload held 1 s, sine amplitude 1e-4 at 1, 5 and
  // 20 Hz, 1000 steps per cycle (backward-Euler rate: phase error ~ pi/1000 of the damping part).
  // Tolerances 0.5 % on |E*| and 0.2 deg; the damping must be visible (> 5 deg at 20 Hz).
  // w = 1 (current tangent, lagged one step): the same tolerances at 25 % and 50 % preload.
  const auto foam = test::effect_test_foam();
  for (double w : {0.0, 1.0})
    for (double preload : {-0.25, -0.5}) {
      if (w == 0.0 && preload == -0.5) continue;
      const StiffnessDampingEffect m(foam, foam, 2e-3, w);
      for (double f : {1.0, 5.0, 20.0}) {
        const test::SineComparison c = test::compare_sine(m, preload, 1.0, 1, f, 6, 1000);
        std::printf("  w %.0f, preload %.2f, %5.1f Hz: |E*| rel. diff %.2e, phase diff %.4f deg (phase %.3f deg)\n", w,
                    preload, f, c.modulus_error(), c.phase_error_deg(), c.phase_deg());
        EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
        EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
        if (f == 20.0) {
          EXPECT_GT(c.phase_deg(), 5.0);
        }
      }
    }
}

TEST(EffectStiffnessDamping, CurrentShareUsesTheTangentAtTheStartOfTheIncrement) {
  // w = 1 and w = 0.4 at a finite compression: the extra stress is beta_s C_d E_dot with
  // C_d = (1 - w) C0 + w C_e(F_old) computed here from the foam's own evaluate(); tolerance 1e-10 relative. In
  // compression C_e differs from C0 by far more than that (checked), so the test sees the share.
  const auto foam = test::effect_test_foam();
  const double beta = 1e-3, dt = 0.01;
  const Mat3 F_old = Vec3(0.5, 1.02, 1.02).asDiagonal(), F_new = Vec3(0.49, 1.021, 1.021).asDiagonal();
  const Vec6 E_dot = (to_voigt_strain(green_lagrange(F_new)) - to_voigt_strain(green_lagrange(F_old))) / dt;
  const Mat6 C0 = foam->evaluate(Mat3::Identity()).dS_dE, Ce = foam->evaluate(F_old).dS_dE;
  EXPECT_GT((Ce - C0).norm(), 0.1 * C0.norm());
  for (double w : {1.0, 0.4}) {
    const StiffnessDampingEffect m(foam, foam, beta, w);
    std::vector<double> none;
    const Vec6 extra = m.integrate(F_old, F_new, dt, none, none).S - foam->evaluate(F_new).S;
    EXPECT_LT(test::rel_diff(extra, beta * ((1.0 - w) * C0 + w * Ce) * E_dot), 1e-10) << "w " << w;
  }
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, beta, 1.5), std::invalid_argument);
}

TEST(EffectStiffnessDamping, NoExtraStressWithoutRate) {
  // dt = 0 and a held state add nothing: exact.
  const auto foam = test::effect_test_foam();
  const StiffnessDampingEffect m(foam, foam, 1e-3);
  const Mat3 F = Vec3(0.7, 1.05, 1.02).asDiagonal();
  std::vector<double> none;
  EXPECT_EQ(m.integrate(Mat3::Identity(), F, 0.0, none, none).S, foam->evaluate(F).S);
  EXPECT_EQ(m.integrate(F, F, 0.5, none, none).S, foam->evaluate(F).S);
}

}  // namespace
}  // namespace cushion::material
