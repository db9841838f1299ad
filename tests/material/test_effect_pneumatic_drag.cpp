// Requirement: the pneumatic effect's drag share (pressure_share s < 1) adds the Lagrangian form of the Kirchhoff drag
// c(J) D, S = C^-1 Y C^-1 with Y = c(J) dE/dt (dashpot) or dY/dt + Y/tau = M(J) dE/dt (trapped air), with an exact
// increment tangent at any share; in a laterally confined test it is the pressure form's axial stress to first order in
// the increment; on a laterally free specimen of a nu = 0 foam it is an axial dashpot, E* = E*_foam + i w c(l)/l^2,
// where the isotropic pressure inflates the specimen sideways and loses damping; its complex tangent matches a
// time-domain sine at any share; and a share out of [0, 1], or with a power-law flow, is refused (docs/physics.md 5.1).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

#include "io/input_error.hpp"
#include "material/effect_catalog.hpp"
#include "material/effect_pneumatic.hpp"
#include "tests/material/pneumatic_test_support.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

using namespace pneumatic_test;

PneumaticParameters with_share(PneumaticParameters p, double pressure_share) {
  p.pressure_share = pressure_share;
  return p;
}

/// A hyperfoam with nu = 0 in every term: no lateral stress at lateral stretch 1, so the laterals of a uniaxial test
/// stay at 1 and the axial and lateral responses are decoupled.
std::shared_ptr<const Hyperfoam> lateral_free_foam() {
  return std::make_shared<Hyperfoam>(std::vector<HyperfoamTerm>{{0.010, 10.0, 0.0}, {0.0001, -2.0, 0.0}, {0.0005, 3.0, 0.0}});
}

TEST(EffectPneumaticDrag, TangentMatchesFiniteDifferencesAtAnyShare) {
  // Shares 0 and 0.4; dashpot, trapped air (M = 2 kPa) and stiffening trapped air (r = 1.5), from a non-zero air
  // state; over hyperfoam and over the Prony material: 1e-6 relative, random F (det > 0.2), dt = 0.01 s.
  std::mt19937 rng(21);
  for (double share : {0.0, 0.4}) {
    const PneumaticEffect dashpot(test::effect_test_foam(), with_share(strong_air(), share));
    const PneumaticEffect maxwell(test::effect_test_foam(), with_share(trapped_air(2e-3), share));
    const PneumaticEffect stiffening(test::effect_test_visco(), with_share(trapped_air(2e-3, 1.5), share));
    for (int trial = 0; trial < 4; ++trial) {
      const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
      SCOPED_TRACE("share " + std::to_string(share) + ", trial " + std::to_string(trial));
      EXPECT_LT(test::increment_tangent_error(dashpot, F_old, F_new, 0.01, virgin(dashpot)), 1e-6);
      expect_exact_tangent_from_air_pressure(dashpot, F_old, F_new);
      expect_exact_tangent_from_air_pressure(maxwell, F_old, F_new);
      expect_exact_tangent_from_air_pressure(stiffening, F_old, F_new);
    }
  }
}

TEST(EffectPneumaticDrag, ConfinedDragIsThePressureToFirstOrder) {
  // F = diag(l, 1, 1): the drag dashpot gives P11 = c(l) (l^2 - l_old^2)/(2 dt l^3) (tolerance 1e-12 relative), the
  // pressure form c(l) (l - l_old)/(dt l^2): their ratio (l + l_old)/(2 l) is 1 to first order in the increment. Along
  // a ramp 1 -> 0.8 in steps of 0.004 the two agree to 0.3 %.
  const PneumaticEffect drag(test::effect_test_foam(), with_share(strong_air(), 0.0));
  for (double l_old : {1.0, 0.9, 0.7}) {
    const double l = l_old - 0.01, dt = 0.02;
    const double exact = drag.coefficient(l) * (l * l - l_old * l_old) / (2.0 * dt * l * l * l);
    EXPECT_NEAR(extra_P11(drag, l_old, l, dt), exact, 1e-12 * std::abs(exact)) << l_old;
  }
  expect_same_along_a_ramp(PneumaticEffect(test::effect_test_foam(), strong_air()), drag, 3e-3);
  // With trapped air the two differ by more than the increment: Y keeps its memory in Lagrangian components, which
  // carry a stress (l_old/l)^2 larger into the next increment than the pressure does. A huge M is the drag dashpot.
  expect_same_along_a_ramp(drag, PneumaticEffect(test::effect_test_foam(), with_share(trapped_air(1e9), 0.0)), 1e-6);
}

TEST(EffectPneumaticDrag, TrappedAirDragRelaxesUnderAHoldWithTheAirTime) {
  // Confined: a 2 % step in 1 ms from l = 0.8, then a hold at l_h: every component of Y, and so the extra stress,
  // falls by 1/(1 + dt/tau(l_h)) an increment, tau = c(J)/M(J) as for the pressure (1e-12 relative).
  const PneumaticEffect m(test::effect_test_foam(), with_share(trapped_air(2e-3), 0.0));
  const double l_h = 0.78, tau = m.relaxation_time(l_h), dt = tau / 50.0;
  std::vector<double> state;
  double s = extra_P11(m, 0.8, l_h, 1e-3, {}, &state);
  ASSERT_LT(s, 0.0);
  for (int k = 1; k <= 100; ++k) {
    std::vector<double> next;
    const double expected = s / (1.0 + dt / tau);
    s = extra_P11(m, l_h, l_h, dt, state, &next);
    EXPECT_NEAR(s, expected, 1e-12 * std::abs(expected)) << k;
    state = next;
  }
}

TEST(EffectPneumaticDrag, FreeSpecimenSeesAnAxialDashpotWhereThePressureLosesDamping) {
  // Uniaxial stress on a nu = 0 foam, 25 % preload (l = 0.75), sine 1e-4 at 1, 5 and 20 Hz: with the drag the complex
  // modulus is the foam's plus i w c(l)/l^2 (complex tangent to 1e-9 relative; time domain to 0.5 % and 0.2 deg). The
  // isotropic pressure also pushes sideways and the free laterals give way, so at 20 Hz its phase is below 0.9 of the
  // drag's (the mechanism of docs/physics.md 5.1).
  const auto foam = lateral_free_foam();
  const PneumaticEffect drag(foam, with_share(strong_air(), 0.0));
  const PneumaticEffect pressure(foam, strong_air());
  for (double f : {1.0, 5.0, 20.0}) {
    const double omega = 2.0 * std::numbers::pi * f, l = 0.75;
    const test::SineComparison c = test::compare_sine(drag, -0.25, 1.0, 1, f, 6, 1000);
    const test::SineComparison e = test::compare_sine(*foam, -0.25, 1.0, 1, f, 6, 1000);
    const std::complex<double> expected = e.frequency_domain + std::complex<double>(0.0, omega * drag.coefficient(l) / (l * l));
    EXPECT_LT(std::abs(c.frequency_domain - expected), 1e-9 * std::abs(expected)) << f << " Hz";
    EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
    if (f == 20.0) {
      const test::SineComparison p = test::compare_sine(pressure, -0.25, 1.0, 1, f, 6, 1000);
      std::printf("  20 Hz phase: foam %.3f deg, + drag %.3f deg, + pressure %.3f deg\n", e.phase_deg(), c.phase_deg(),
                  p.phase_deg());
      EXPECT_LT(p.phase_deg(), 0.9 * c.phase_deg());
      EXPECT_GT(c.phase_deg(), e.phase_deg() + 1.0);
    }
  }
}

TEST(EffectPneumaticDrag, MixedShareComplexTangentMatchesTimeDomainSine) {
  // Share 0.5 with trapped air (M = 2 kPa) on the nu = 0.1 foam, 25 % preload: 0.5 % on |E*|, 0.2 deg at 1, 5, 20 Hz.
  const PneumaticEffect m(test::effect_test_foam(), with_share(trapped_air(2e-3), 0.5));
  for (double f : {1.0, 5.0, 20.0}) {
    const test::SineComparison c = test::compare_sine(m, -0.25, 1.0, 100, f, 6, 1000);
    EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
  }
}

TEST(EffectPneumaticDrag, ShareIsCheckedAndNeedsTheLinearFlow) {
  for (double bad : {-0.1, 1.1, std::nan("")})
    EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), with_share(strong_air(), bad)), std::invalid_argument) << bad;
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), with_share(power_law_air(0.6), 0.5)), std::invalid_argument);
  EXPECT_NO_THROW(PneumaticEffect(test::effect_test_foam(), with_share(power_law_air(0.6), 1.0)));
  // Through a material file: one message naming the file and the effect.
  const EffectSpec spec{"pneumatic", {{"pressure_share", 0.5}, {"rate_exponent", 0.6}}};
  try {
    apply_effects(test::effect_test_foam(), test::effect_test_foam(), {spec}, "seat.json");
    FAIL() << "accepted a drag share with a power-law flow";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("seat.json: effects[0]: pneumatic: a drag share"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cushion::material
