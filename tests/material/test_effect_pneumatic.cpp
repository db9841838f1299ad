// Requirement: the pneumatic (Darcy air-flow) effect adds the documented lumped extra pressure
// eta R^2/(8 K(J)) (-dJ/dt)/J, reduces to the Darcy layer formula of docs/physics.md 5.1 at small strain,
// scales with R^2, has an exact increment tangent, and its complex tangent matches a time-domain sine. With a finite
// air modulus M (trapped air in series with the flow) it is a Maxwell branch: the pressure relaxes under a hold with
// tau(J) = c(J)/M (backward Euler exactly, the exponential to O(dt/tau)), a huge M gives back the dashpot, and the
// complex tangent i w c/(1 + i w tau) matches a time-domain sine. A power-law flow (rate exponent q != 1) gives
// p = c(J) |v|^q at a constant volumetric rate v, relaxes under a hold as the closed form of dp/dt = -M (p/c)^(1/q),
// has an exact increment tangent in both forms, and refuses a small-amplitude complex tangent. An air modulus that
// grows as the cells shrink, M(J) = M0 J^-r, follows Boyle's law for closed cells (r = 1: p = M0 (1/J - 1)), keeps
// exact tangents, and its complex tangent at a preload matches a time-domain sine with M(J) there.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <limits>
#include <string>

#include "material/effect_pneumatic.hpp"
#include "tests/material/pneumatic_test_support.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

using namespace pneumatic_test;

TEST(EffectPneumatic, TangentMatchesFiniteDifferences) {
  // Random F_old, F_new (det > 0.2), dt = 0.01 s, over hyperfoam and over a viscoelastic inner with a
  // non-trivial state; tolerance 1e-6 relative.
  std::mt19937 rng(11);
  const PneumaticEffect on_foam(test::effect_test_foam(), strong_air());
  const PneumaticEffect on_visco(test::effect_test_visco(), strong_air());
  const PneumaticEffect maxwell(test::effect_test_foam(), trapped_air(2e-3));
  PneumaticParameters rising = strong_air();
  rising.permeability_exponent = -1.5;  // permeability rising with compression (diagnose's empirical range)
  const PneumaticEffect on_foam_rising(test::effect_test_foam(), rising);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
    EXPECT_LT(test::increment_tangent_error(on_foam, F_old, F_new, 0.01, virgin(on_foam)), 1e-6) << "trial " << trial;
    EXPECT_LT(test::increment_tangent_error(on_foam_rising, F_old, F_new, 0.01, virgin(on_foam_rising)), 1e-6)
        << "n_K -1.5, trial " << trial;
    SCOPED_TRACE("Maxwell, trial " + std::to_string(trial));
    expect_exact_tangent_from_air_pressure(maxwell, F_old, F_new);
    std::vector<double> state(on_visco.state_size()), next(on_visco.state_size());
    on_visco.initial_state(state);
    on_visco.integrate(Mat3::Identity(), F_old, 0.02, state, next);
    EXPECT_LT(test::increment_tangent_error(on_visco, F_old, F_new, 0.01, next), 1e-6) << "trial " << trial;
  }
}

TEST(EffectPneumatic, ConstantVolumetricRateGivesTheDocumentedPressure) {
  // Confined compression J(t) = 1 - rate t (exactly constant dJ/dt): extra P11 = -p/J with
  // p = eta R^2 rate / (8 K0 J^n J); checked along the ramp to J = 0.4, tolerance 1e-10 relative. n = 2 (permeability
  // falling with compression) and n = -1.5 (rising: the empirical range diagnose fits, docs/physics.md 5.1).
  for (const double n : {2.0, -1.5}) {
    PneumaticParameters p = strong_air();
    p.permeability_exponent = n;
    const PneumaticEffect m(test::effect_test_foam(), p);
    const double rate = 2.0, dt = 1e-3;
    for (int k = 0; k < 300; k += 37) {
      const double J_old = 1.0 - rate * dt * k, J_new = 1.0 - rate * dt * (k + 1);
      const double K = p.permeability * std::pow(J_new, p.permeability_exponent);
      const double pressure = p.air_viscosity * p.drainage_length * p.drainage_length * rate / (8.0 * K * J_new);
      EXPECT_NEAR(extra_P11(m, J_old, J_new, dt), -pressure / J_new, 1e-10 * pressure / J_new)
          << "n = " << n << ", J = " << J_new;
    }
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
  std::vector<double> none, next(m.state_size());
  const Mat3 F = confined(0.7);
  EXPECT_EQ(m.integrate(Mat3::Identity(), F, 0.0, virgin(m), next).S, m.inner().integrate(F, F, 0.0, none, none).S);
  EXPECT_EQ(m.integrate(F, F, 0.5, virgin(m), next).S, m.inner().integrate(F, F, 0.5, none, none).S);
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

TEST(EffectPneumatic, TrappedAirRelaxesUnderAHoldWithItsTime) {
  // Confined: 2 % compression in 1 ms from J = 0.8, then a hold at J_h in steps of dt. Backward Euler gives
  // p_k = p_(k-1)/(1 + dt/tau(J_h)) exactly (tolerance 1e-12 relative) and, at dt = tau/200, the exponential
  // e^(-t/tau) within 1 % over three relaxation times.
  const PneumaticEffect m(test::effect_test_foam(), trapped_air(2e-3));
  const double J_h = 0.78, tau = m.relaxation_time(J_h), dt = tau / 200.0;
  EXPECT_NEAR(tau, m.coefficient(J_h) / 2e-3, 1e-15);
  std::vector<double> state;
  const double s0 = extra_P11(m, 0.8, J_h, 1e-3, {}, &state);
  EXPECT_LT(s0, 0.0);  // compressive
  double expected = state.back();
  for (int k = 1; k <= 600; ++k) {
    std::vector<double> next;
    const double s = extra_P11(m, J_h, J_h, dt, state, &next);
    expected /= 1.0 + dt / tau;
    EXPECT_NEAR(next.back(), expected, 1e-12 * std::abs(expected)) << k;
    if (k % 200 == 0) {
      EXPECT_NEAR(s / s0, std::exp(-k * dt / tau), 0.01 * std::exp(-k * dt / tau)) << k;
    }
    state = next;
  }
}

TEST(EffectPneumatic, HugeAirModulusIsTheDashpot) {
  // M = 1e9 MPa (tau ~ 1e-13 s) vs the dashpot (M infinite) along a compression ramp: 1e-6 relative.
  const PneumaticEffect dashpot(test::effect_test_foam(), strong_air());
  const PneumaticEffect stiff(test::effect_test_foam(), trapped_air(1e9));
  expect_same_along_a_ramp(dashpot, stiff, 1e-6);
}

TEST(EffectPneumatic, TrappedAirComplexTangentMatchesTimeDomainSine) {
  // As ComplexTangentMatchesTimeDomainSine with M = 2 kPa (tau about 30 ms at the preload, the Maxwell corner near
  // 5 Hz): 0.5 % on |E*|, 0.2 deg on the phase. At 20 Hz the trapped air adds storage modulus (E' above the foam's
  // alone by more than 1 %) and less loss than the dashpot (phase below the dashpot's).
  const PneumaticEffect maxwell(test::effect_test_foam(), trapped_air(2e-3));
  const PneumaticEffect dashpot(test::effect_test_foam(), strong_air());
  const auto& foam = maxwell.inner();
  for (double f : {1.0, 5.0, 20.0}) {
    const test::SineComparison c = test::compare_sine(maxwell, -0.25, 1.0, 100, f, 6, 1000);
    std::printf("  %5.1f Hz: |E*| rel. diff %.2e, phase diff %.4f deg (phase %.3f deg)\n", f, c.modulus_error(),
                c.phase_error_deg(), c.phase_deg());
    EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
    if (f == 20.0) {
      const test::SineComparison d = test::compare_sine(dashpot, -0.25, 1.0, 1, f, 6, 1000);
      const test::SineComparison e = test::compare_sine(foam, -0.25, 1.0, 1, f, 6, 1000);
      std::printf("  20 Hz E' [MPa]: foam %.5f, + dashpot %.5f, + trapped air %.5f; phase %.3f, %.3f, %.3f deg\n",
                  e.frequency_domain.real(), d.frequency_domain.real(), c.frequency_domain.real(), e.phase_deg(),
                  d.phase_deg(), c.phase_deg());
      EXPECT_GT(c.frequency_domain.real(), 1.01 * e.frequency_domain.real());
      EXPECT_LT(c.phase_deg(), d.phase_deg());
    }
  }
}

TEST(EffectPneumatic, PowerLawFlowTangentMatchesFiniteDifferences) {
  // As TangentMatchesFiniteDifferences for q = 0.6 and 1.7, dashpot and Maxwell (M = 2 kPa, from a non-zero air
  // pressure): 1e-6 relative.
  std::mt19937 rng(12);
  for (double q : {0.6, 1.7}) {
    const PneumaticEffect dashpot(test::effect_test_foam(), power_law_air(q));
    const PneumaticEffect maxwell(test::effect_test_foam(), power_law_air(q, 2e-3));
    for (int trial = 0; trial < 4; ++trial) {
      const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
      EXPECT_LT(test::increment_tangent_error(dashpot, F_old, F_new, 0.01, virgin(dashpot)), 1e-6) << q << " " << trial;
      SCOPED_TRACE("Maxwell, q " + std::to_string(q) + ", trial " + std::to_string(trial));
      expect_exact_tangent_from_air_pressure(maxwell, F_old, F_new);
    }
  }
}

TEST(EffectPneumatic, PowerLawFlowAtConstantRateIsThePowerOfTheRate) {
  // Confined compression at a constant dJ/dt from J = 0.9: extra P11 = -c(J) v^q / J with v = -(dJ/dt)/J (backward
  // Euler: v = (J_old/J - 1)/dt), q = 0.5 and 1.5 at 0.02, 0.2 and 2 /s. The regularisation v_eps = 1e-4 /s changes it
  // by |q - 1| (v_eps/v)^2 / 2 <= 1.3e-5: tolerance 2e-5 relative. The same step J 0.9 -> 0.899 taken in a tenth of the
  // time gives a stress ratio 10^q (1e-4 relative).
  for (double q : {0.5, 1.5}) {
    const PneumaticEffect m(test::effect_test_foam(), power_law_air(q));
    std::vector<double> at_rate;
    for (double rate : {0.02, 0.2, 2.0}) {
      const double dt = 1e-3 / rate, J_old = 0.9, J_new = J_old - rate * dt, v = (J_old / J_new - 1.0) / dt;
      const double expected = -m.coefficient(J_new) * std::pow(v, q) / J_new;
      const double s = extra_P11(m, J_old, J_new, dt);
      EXPECT_NEAR(s, expected, 2e-5 * std::abs(expected)) << "q " << q << ", rate " << rate;
      at_rate.push_back(s);
    }
    EXPECT_NEAR(at_rate[2] / at_rate[1], std::pow(10.0, q), 1e-4 * std::pow(10.0, q)) << q;
  }
}

TEST(EffectPneumatic, PowerLawTrappedAirRelaxesAsTheClosedForm) {
  // Confined: a 2 % step in 1 ms from J = 0.8, then a hold. With v_eps negligible, dp/dt = -M (p/c)^r, r = 1/q, gives
  // p(t)^(1-r) = p0^(1-r) - (1-r) M c^-r t. q = 0.6 and 1.6, M = 2 kPa, dt = 1e-5 s (backward Euler, O(dt)): within
  // 1 % while p falls to a fifth of p0 (the dashpot rate stays above 1e-2 /s, far above v_eps).
  for (double q : {0.6, 1.6}) {
    const double M = 2e-3, r = 1.0 / q;
    const PneumaticEffect m(test::effect_test_foam(), power_law_air(q, M));
    const double J_h = 0.78, c = m.coefficient(J_h), dt = 1e-5;
    std::vector<double> state;
    extra_P11(m, 0.8, J_h, 1e-3, {}, &state);
    const double p0 = state.back();
    ASSERT_GT(p0, 0.0);  // compression: positive air pressure
    double t = 0.0, p = p0;
    int checked = 0;
    for (int k = 0; k < 2000000 && p > 0.2 * p0; ++k) {
      std::vector<double> next;
      extra_P11(m, J_h, J_h, dt, state, &next);
      state = next, t += dt, p = state.back();
      if (p < (0.8 - 0.2 * checked) * p0) {
        const double exact = std::pow(std::pow(p0, 1.0 - r) - (1.0 - r) * M * std::pow(c, -r) * t, 1.0 / (1.0 - r));
        EXPECT_NEAR(p, exact, 0.01 * exact) << "q " << q << ", t " << t;
        ++checked;
      }
    }
    EXPECT_EQ(checked, 4) << q;
  }
}

TEST(EffectPneumatic, PowerLawHugeAirModulusIsThePowerLawDashpot) {
  // As HugeAirModulusIsTheDashpot for q = 0.6: 1e-6 relative along a compression ramp.
  const PneumaticEffect dashpot(test::effect_test_foam(), power_law_air(0.6));
  const PneumaticEffect stiff(test::effect_test_foam(), power_law_air(0.6, 1e9));
  expect_same_along_a_ramp(dashpot, stiff, 1e-6);
}

TEST(EffectPneumatic, PowerLawFlowHasNoSmallAmplitudeTangentAndRateExponentIsChecked) {
  const PneumaticEffect m(test::effect_test_foam(), power_law_air(0.6));
  EXPECT_THROW(m.complex_tangent(confined(0.8), 10.0), std::invalid_argument);
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), power_law_air(0.05)), std::invalid_argument);
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), power_law_air(3.5)), std::invalid_argument);
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), power_law_air(std::nan(""))), std::invalid_argument);
}

TEST(EffectPneumatic, StiffeningAirInClosedCellsFollowsBoylesLaw) {
  // Cells that let no air out (K0 = 1e-12 mm^2: tau ~ 2e6 s, against 0.4 s of loading) compressed confined from J = 1
  // to 0.6 in 4000 increments: dp = -M(J) dJ/J integrates to p = M0 (J^-r - 1)/r, for r = 1 the isothermal ideal gas
  // p_abs/p_atm = 1/J (Boyle) with M0 = p_atm. Backward Euler takes M at each increment's end (a right-endpoint rule,
  // O(dJ)): tolerance 1e-3 relative at J = 0.8 and 0.6, for r = 1 and 2.5; r = 0 gives the constant-modulus -M0 ln J.
  for (double r : {0.0, 1.0, 2.5}) {
    PneumaticParameters closed = trapped_air(0.101, r);  // M0 = p_atm [MPa]
    closed.permeability = 1e-12;
    const PneumaticEffect m(test::effect_test_foam(), closed);
    std::vector<double> state = virgin(m);
    const int steps = 4000;
    for (int k = 1; k <= steps; ++k) {
      const double J_old = 1.0 - 0.4 * (k - 1) / steps, J = 1.0 - 0.4 * k / steps;
      std::vector<double> next;
      extra_P11(m, J_old, J, 1e-4, state, &next);
      state = next;
      if (k == steps / 2 || k == steps) {
        const double boyle = r == 0.0 ? -0.101 * std::log(J) : 0.101 * (std::pow(J, -r) - 1.0) / r;
        EXPECT_NEAR(state.back(), boyle, 1e-3 * boyle) << "r " << r << ", J " << J;
      }
    }
  }
}

TEST(EffectPneumatic, StiffeningAirTangentsAndComplexTangent) {
  // M(J) = M0 J^-r, r = 1.5 and r = -0.8 (a spring that softens with compression, the empirical range below 0):
  // increment tangents against finite differences (Darcy and power-law flow q = 0.6, from a non-zero air pressure:
  // 1e-6 relative); the relaxation time c(J)/M(J); and the complex tangent about the preload J = 0.75 against a
  // time-domain sine at 2 and 10 Hz (0.5 % on |E*|, 0.2 deg), which sees M(0.75) = 0.75^-r M0 (1.54 M0 at r = 1.5).
  std::mt19937 rng(13);
  for (double r : {1.5, -0.8}) {
    for (double q : {1.0, 0.6}) {
      PneumaticParameters stiffening = trapped_air(2e-3, r);
      stiffening.rate_exponent = q;
      const PneumaticEffect m(test::effect_test_foam(), stiffening);
      for (int trial = 0; trial < 4; ++trial) {
        const Mat3 F_old = test::random_F(rng, 0.3), F_new = test::random_F(rng, 0.3);
        SCOPED_TRACE("r " + std::to_string(r) + ", q " + std::to_string(q) + ", trial " + std::to_string(trial));
        expect_exact_tangent_from_air_pressure(m, F_old, F_new);
      }
    }
    const PneumaticEffect m(test::effect_test_foam(), trapped_air(2e-3, r));
    EXPECT_NEAR(m.relaxation_time(0.75), m.coefficient(0.75) / (2e-3 * std::pow(0.75, -r)), 1e-12);
    for (double f : {2.0, 10.0}) {
      const test::SineComparison c = test::compare_sine(m, -0.25, 1.0, 100, f, 6, 1000);
      EXPECT_LT(c.modulus_error(), 5e-3) << "r " << r << ", " << f << " Hz";
      EXPECT_LT(c.phase_error_deg(), 0.2) << "r " << r << ", " << f << " Hz: phase " << c.phase_deg();
    }
  }
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), trapped_air(2e-3, -2.1)), std::invalid_argument);
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), trapped_air(2e-3, 5.5)), std::invalid_argument);
  EXPECT_THROW(PneumaticEffect(test::effect_test_foam(), trapped_air(2e-3, std::nan(""))), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::material
