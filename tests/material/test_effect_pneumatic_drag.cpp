// Requirement: the pneumatic effect's drag share (pressure_share s < 1) adds the Lagrangian form of the Kirchhoff drag
// c(J) D, S = C^-1 Y C^-1 with Y = c(J) dE/dt (dashpot) or dY/dt + Y/tau = M(J) dE/dt (trapped air), with an exact
// increment tangent at any share; in a laterally confined test it is the pressure form's axial stress to first order in
// the increment; on a laterally free specimen of a nu = 0 foam it is an axial dashpot, E* = E*_foam + i w c(l)/l^2,
// where the isotropic pressure inflates the specimen sideways and loses damping; its complex tangent matches a
// time-domain sine at any share; a share out of [0, 1] is refused. With a power-law flow (q != 1) along |D| the drag is
// the closed form c(J) h(|D|) D in a confined test and the power-law pressure to first order, relaxes under a hold as the
// closed form of dy/dt = -M (y/c)^(1/q), and keeps an exact increment tangent (docs/physics.md 5.1).
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

TEST(EffectPneumaticDrag, ShareIsChecked) {
  for (double bad : {-0.1, 1.1, std::nan("")})
    EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), with_share(strong_air(), bad)), std::invalid_argument)
        << bad;
  EXPECT_NO_THROW(PneumaticEffect(test::effect_test_foam(), with_share(power_law_air(0.6), 0.5)));
  // Through a material file: one message naming the file and the effect.
  const EffectSpec spec{"pneumatic", {{"pressure_share", 1.5}}};
  try {
    apply_effects(test::effect_test_foam(), test::effect_test_foam(), {spec}, "seat.json");
    FAIL() << "accepted a pressure share of 1.5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("seat.json: effects[0].pressure_share: must be >= 0 and <= 1"),
              std::string::npos)
        << e.what();
  }
}

TEST(EffectPneumaticDrag, PowerLawDragTangentMatchesFiniteDifferences) {
  // Power-law flow q = 0.6 and 1.7 in the drag (shares 0 and 0.4): dashpot, trapped air (M = 2 kPa) and stiffening
  // trapped air (r = 1.5, over the Prony material), from a non-zero air state: 1e-6 relative, random F, dt = 0.01 s.
  std::mt19937 rng(22);
  for (double q : {0.6, 1.7})
    for (double share : {0.0, 0.4}) {
      const PneumaticEffect dashpot(test::effect_test_foam(), with_share(power_law_air(q), share));
      const PneumaticEffect maxwell(test::effect_test_foam(), with_share(power_law_air(q, 2e-3), share));
      PneumaticParameters stiff = with_share(power_law_air(q, 2e-3), share);
      stiff.air_modulus_exponent = 1.5;
      const PneumaticEffect stiffening(test::effect_test_visco(), stiff);
      for (int trial = 0; trial < 3; ++trial) {
        const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
        SCOPED_TRACE("q " + std::to_string(q) + ", share " + std::to_string(share) + ", trial " +
                     std::to_string(trial));
        EXPECT_LT(test::increment_tangent_error(dashpot, F_old, F_new, 0.01, virgin(dashpot)), 1e-6);
        expect_exact_tangent_from_air_pressure(dashpot, F_old, F_new);
        expect_exact_tangent_from_air_pressure(maxwell, F_old, F_new);
        expect_exact_tangent_from_air_pressure(stiffening, F_old, F_new);
      }
    }
}

TEST(EffectPneumaticDrag, ConfinedPowerLawDragIsItsClosedFormAndThePressureToFirstOrder) {
  // F = diag(l, 1, 1), dashpot drag with q = 0.5 and 1.5: Edot = (l^2 - l_old^2)/(2 dt), |D| = |Edot|/l^2,
  // P11 = c(l) h(|D|) Edot / l^3 with h = (|D|^2 + v_eps^2)^((q-1)/2) (1e-12 relative, at 0.02 to 2 /s). Along a ramp
  // 1 -> 0.8 in steps of 0.004 the power-law pressure form gives the same axial stress to first order in the increment:
  // their rates differ by (l + l_old)/(2 l), so the stresses by its power q, at most 1 + 0.0025 q (tolerance 0.3 % q);
  // a huge air modulus gives back the dashpot (1e-6).
  for (double q : {0.5, 1.5}) {
    const PneumaticEffect drag(test::effect_test_foam(), with_share(power_law_air(q), 0.0));
    for (double l_old : {1.0, 0.9, 0.7})
      for (double rate : {0.02, 2.0}) {
        const double l = l_old - 0.01, dt = 0.01 / rate, Ed = (l * l - l_old * l_old) / (2.0 * dt);
        const double D = std::abs(Ed) / (l * l),
                     h = std::pow(D * D + kPneumaticRestRate * kPneumaticRestRate, 0.5 * (q - 1.0));
        const double exact = drag.coefficient(l) * h * Ed / (l * l * l);
        EXPECT_NEAR(extra_P11(drag, l_old, l, dt), exact, 1e-12 * std::abs(exact)) << q << " " << l_old << " " << rate;
      }
    expect_same_along_a_ramp(PneumaticEffect(test::effect_test_foam(), power_law_air(q)), drag, 3e-3 * q);
    expect_same_along_a_ramp(drag, PneumaticEffect(test::effect_test_foam(), with_share(power_law_air(q, 1e9), 0.0)),
                             1e-6);
  }
}

TEST(EffectPneumaticDrag, PowerLawTrappedAirDragRelaxesAsTheClosedForm) {
  // Confined, a 2 % step in 1 ms from l = 0.8, then a hold: y = |Y|_C = Y11/l^2 = l P11 obeys dy/dt = -M (y/c)^(1/q)
  // (v_eps negligible), y(t)^(1-r) = y0^(1-r) - (1-r) M c^-r t, r = 1/q, as the pressure form does. q = 0.6 and
  // 1.6, M = 2 kPa, dt = 1e-5 s (backward Euler, O(dt)): within 1 % while y falls to a fifth of y0.
  for (double q : {0.6, 1.6}) {
    const double M = 2e-3, r = 1.0 / q, l = 0.78;
    const PneumaticEffect m(test::effect_test_foam(), with_share(power_law_air(q, M), 0.0));
    const double c = m.coefficient(l), dt = 1e-5;
    std::vector<double> state;
    const double y0 = -l * extra_P11(m, 0.8, l, 1e-3, {}, &state);  // compression: P11 < 0
    ASSERT_GT(y0, 0.0);
    double t = 0.0, y = y0;
    int checked = 0;
    for (int k = 0; k < 2000000 && y > 0.2 * y0; ++k) {
      std::vector<double> next;
      y = -l * extra_P11(m, l, l, dt, state, &next);
      state = next, t += dt;
      if (y < (0.8 - 0.2 * checked) * y0) {
        const double exact = std::pow(std::pow(y0, 1.0 - r) - (1.0 - r) * M * std::pow(c, -r) * t, 1.0 / (1.0 - r));
        EXPECT_NEAR(y, exact, 0.01 * exact) << "q " << q << ", t " << t;
        ++checked;
      }
    }
    EXPECT_EQ(checked, 4) << q;
  }
}

}  // namespace
}  // namespace cushion::material
