// Requirement: stiffness-proportional damping adds beta_s C_d dE/dt at any strain, C_d = (1 - w) C0 + w C_e(F_old)
// (C0: initial elastic tangent, C_e: the current one at the start of the increment), has an exact increment
// tangent, and its complex tangent (i omega beta_s C_d(F_base) added) matches a time-domain sine run by the point
// driver, for w = 0 and w = 1. With a fractional order q < 1 (a spring-pot, D^q E in place of dE/dt) the extra stress
// of a uniaxial ramp follows the closed form beta omega_r^(1-q) C0 t^(1-q)/Gamma(2-q) E_dot, the increment tangent is
// exact with a non-trivial memory, the complex tangent matches a time-domain sine, and q = 1 is the dashpot.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

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

TEST(EffectStiffnessDamping, FractionalRampFollowsTheClosedForm) {
  // E(t) = t E_dot from the virgin state on a hyperelastic base (w = 0, so C_d = C0 is constant and the term is
  // linear): S_d(t) = beta (2 pi f_r)^(1-q) C0 E_dot t^(1-q)/Gamma(2-q). 200 steps of 5 ms; within 0.3 % (the bank's
  // own error) at t = 0.1, 0.5 and 1 s, q = 0.3 and 0.7.
  const auto foam = test::effect_test_foam();
  const double beta = 2e-3, f_r = 5.0, dt = 5e-3;
  Vec6 E_dot;
  E_dot << -0.2, 0.02, 0.01, 0.03, -0.01, 0.005;
  for (double q : {0.3, 0.7}) {
    const StiffnessDampingEffect m(foam, foam, beta, 0.0, q, f_r);
    EXPECT_NEAR(m.coefficient(), beta * std::pow(2.0 * std::numbers::pi * f_r, 1.0 - q), 1e-15);
    std::vector<double> state(m.state_size()), next(m.state_size());
    m.initial_state(state);
    auto F_at = [&](int k) { return test::F_from_C(Mat3::Identity() + 2.0 * from_voigt_strain(k * dt * E_dot)); };
    for (int k = 0; k < 200; ++k) {
      const Vec6 S = m.integrate(F_at(k), F_at(k + 1), dt, state, next).S;
      state = next;
      const double t = (k + 1) * dt;
      if (k + 1 == 20 || k + 1 == 100 || k + 1 == 200) {
        const Vec6 expected =
            m.coefficient() * std::pow(t, 1.0 - q) / std::tgamma(2.0 - q) * m.initial_tangent() * E_dot;
        EXPECT_LT(test::rel_diff(Vec6(S - foam->evaluate(F_at(k + 1)).S), expected), 3e-3) << "q " << q << ", t " << t;
      }
    }
  }
}

TEST(EffectStiffnessDamping, FractionalTangentMatchesFiniteDifferences) {
  // q = 0.5 over hyperfoam (w = 0 and 0.6) and over the viscoelastic model (w = 1), each after two increments that
  // fill the memory; dt = 0.01 s; tolerance 1e-6 relative.
  std::mt19937 rng(37);
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const std::shared_ptr<const Hyperelastic> long_term(visco, &visco->long_term_base());
  const StiffnessDampingEffect models[] = {
      {foam, foam, 1e-3, 0.0, 0.5}, {foam, foam, 1e-3, 0.6, 0.5}, {visco, long_term, 1e-3, 1.0, 0.5}};
  for (const StiffnessDampingEffect& m : models)
    for (int trial = 0; trial < 3; ++trial) {
      const Mat3 F_a = test::random_F(rng, 0.3), F_old = test::random_F(rng, 0.3), F = test::random_F(rng, 0.3);
      std::vector<double> s0(m.state_size()), s1(m.state_size()), s2(m.state_size());
      m.initial_state(s0);
      m.integrate(Mat3::Identity(), F_a, 0.05, s0, s1);
      m.integrate(F_a, F_old, 0.02, s1, s2);
      EXPECT_LT(test::increment_tangent_error(m, F_old, F, 0.01, s2), 1e-6) << m.describe() << ", trial " << trial;
    }
}

TEST(EffectStiffnessDamping, FractionalComplexTangentMatchesTimeDomainSine) {
  // Point driver, uniaxial stress (nu = 0.1), 25 % preload held 200 s (the spring-pot's memory of the ramp relaxes as
  // t^-q: a slow drift that the fitted line takes up), sine amplitude 1e-4 at 1, 5 and 20 Hz, 400 steps a cycle, q = 0.4
  // and 0.8, w = 0 and 1. Tolerances 0.5 % on |E*| and 0.2 deg; the damping must be visible (> 3 deg at 20 Hz).
  const auto foam = test::effect_test_foam();
  for (double q : {0.4, 0.8})
    for (double w : {0.0, 1.0}) {
      const StiffnessDampingEffect m(foam, foam, 2e-3, w, q);
      for (double f : {1.0, 5.0, 20.0}) {
        const test::SineComparison c = test::compare_sine(m, -0.25, 200.0, 200, f, 6, 400);
        std::printf("  q %.1f, w %.0f, %5.1f Hz: |E*| rel. diff %.2e, phase diff %.4f deg (phase %.3f deg)\n", q, w, f,
                    c.modulus_error(), c.phase_error_deg(), c.phase_deg());
        EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
        EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
        if (f == 20.0) {
          EXPECT_GT(c.phase_deg(), 3.0);
        }
      }
    }
}

TEST(EffectStiffnessDamping, OrderOneIsTheDashpotAndBadOrdersAreRefused) {
  // derivative_order 1 (explicit) gives the same stress and tangent as the default, bit for bit, and no state; orders
  // outside (0, 1] and a reference frequency <= 0 are refused.
  const auto foam = test::effect_test_foam();
  const StiffnessDampingEffect dashpot(foam, foam, 1e-3), explicit_one(foam, foam, 1e-3, 0.0, 1.0, 2.0);
  EXPECT_EQ(explicit_one.state_size(), 0u);
  const Mat3 F_old = Vec3(0.8, 1.01, 1.01).asDiagonal(), F_new = Vec3(0.79, 1.011, 1.011).asDiagonal();
  std::vector<double> none;
  const PointResponse a = dashpot.integrate(F_old, F_new, 0.01, none, none);
  const PointResponse b = explicit_one.integrate(F_old, F_new, 0.01, none, none);
  EXPECT_EQ(a.S, b.S);
  EXPECT_EQ(a.dS_dE, b.dS_dE);
  EXPECT_GT(StiffnessDampingEffect(foam, foam, 1e-3, 0.0, 0.5).state_size(), 0u);
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, 1e-3, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, 1e-3, 0.0, 1.5), std::invalid_argument);
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, 1e-3, 0.0, 0.5, 0.0), std::invalid_argument);
}

TEST(EffectStiffnessDamping, FractionalMemoryCarriesOverAZeroStep) {
  // dt = 0 after a ramp: the state carries over unchanged and the stress is the memory's.
  const auto foam = test::effect_test_foam();
  const StiffnessDampingEffect m(foam, foam, 1e-3, 0.0, 0.5);
  std::vector<double> s0(m.state_size()), s1(m.state_size()), s2(m.state_size());
  m.initial_state(s0);
  const Mat3 F = Vec3(0.9, 1.01, 1.01).asDiagonal();
  const Vec6 S1 = m.integrate(Mat3::Identity(), F, 0.1, s0, s1).S;
  const Vec6 S = m.integrate(F, F, 0.0, s1, s2).S;
  EXPECT_EQ(s1, s2);
  // the first step's stress less its dashpot part eta/dt C0 dE is the memory's (relative 1e-12)
  const Vec6 dashpot_part =
      m.coefficient() * SpringPotBank(0.5).dashpot() / 0.1 * m.initial_tangent() * to_voigt_strain(green_lagrange(F));
  EXPECT_LT(test::rel_diff(Vec6(S - foam->evaluate(F).S), Vec6(S1 - foam->evaluate(F).S - dashpot_part)), 1e-12);
}

TEST(EffectStiffnessDamping, StretchExponentTwoGivesAConstantNominalCoefficientInAUniaxialTest) {
  // F = diag(l, 1, 1) (a uniaxial test at nu = 0), w = 0, q = 1: the extra PK2 stress is J_old^-n beta C0 dE/dt, so
  // its nominal stress P = l S is l l_old^-n beta C0_1111 (l^2 - l_old^2)/(2 dt), which for n = 2 tends to
  // beta C0_1111 dl/dt at every compression (the generator's nominal forms, docs/physics.md 9.22): checked against the
  // discrete formula to 1e-10 and, at 25 % and 50 % compression with dl = 1e-6, against beta C0_1111 dl/dt to 1e-5;
  // n = 0 gives l_old^2 times that (0.56 and 0.25 of it: the Green-Lagrange form's nominal coefficient).
  const auto foam = test::effect_test_foam();
  const double beta = 2e-3, dt = 1e-5, C0 = foam->evaluate(Mat3::Identity()).dS_dE(0, 0);  // l-dot 0.1/s
  for (double l_old : {0.75, 0.5}) {
    const double l = l_old - 1e-6;
    const Mat3 F_old = Vec3(l_old, 1.0, 1.0).asDiagonal(), F_new = Vec3(l, 1.0, 1.0).asDiagonal();
    std::vector<double> none;
    for (double n : {2.0, 0.0}) {
      const StiffnessDampingEffect m(foam, foam, beta, 0.0, 1.0, 5.0, n);
      const double nominal = l * (m.integrate(F_old, F_new, dt, none, none).S(0) - foam->evaluate(F_new).S(0));
      const double discrete = l * std::pow(l_old, -n) * beta * C0 * (l * l - l_old * l_old) / (2.0 * dt);
      EXPECT_NEAR(nominal / discrete, 1.0, 1e-10) << "l " << l_old << ", n " << n;
      const double constant = beta * C0 * (l - l_old) / dt;
      if (n == 2.0) EXPECT_NEAR(nominal / constant, 1.0, 1e-5) << "l " << l_old;
      if (n == 0.0) EXPECT_NEAR(nominal / constant, l_old * l_old, 1e-5) << "l " << l_old;
    }
  }
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, beta, 0.0, 1.0, 5.0, std::nan("")), std::invalid_argument);
}

TEST(EffectStiffnessDamping, StretchExponentKeepsTheTangentsExact) {
  // n = 1.5 with w = 0.6, the dashpot and the fractional bank: the increment tangent against finite differences
  // (relative 1e-6; the factor J_old^-n is taken at the start of the increment like C_d, so it adds no term) and the
  // complex tangent against a time-domain sine at 25 % preload (0.5 % on |E*|, 0.2 deg).
  std::mt19937 rng(7);
  const auto foam = test::effect_test_foam();
  const StiffnessDampingEffect dashpot(foam, foam, 1e-3, 0.6, 1.0, 5.0, 1.5);
  const StiffnessDampingEffect bank(foam, foam, 1e-3, 0.6, 0.5, 5.0, 1.5);
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 F_old = test::random_F(rng, 0.3), F = test::random_F(rng, 0.3);
    EXPECT_LT(test::increment_tangent_error(dashpot, F_old, F, 0.01, {}), 1e-6) << "trial " << trial;
    std::vector<double> state(bank.state_size()), next(bank.state_size());
    bank.initial_state(state);
    bank.integrate(Mat3::Identity(), F_old, 0.05, state, next);
    EXPECT_LT(test::increment_tangent_error(bank, F_old, F, 0.01, next), 1e-6) << "trial " << trial;
  }
  for (double f : {1.0, 20.0}) {
    const test::SineComparison c = test::compare_sine(dashpot, -0.25, 1.0, 1, f, 6, 1000);
    EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
  }
}

TEST(EffectStiffnessDamping, NominalShareGivesTheSlopeOfTheForceDeflectionCurve) {
  // A foam at nu = 0 (its principal stresses uncoupled, so F = diag(l, 1, 1) is a uniaxial test with free laterals),
  // w = 1, q = 1, n = 0. With the nominal share m = 1 the damping's nominal stress over an increment at 25 % and 50 %
  // compression is beta E_t dl/dt, E_t = dP/dl of the foam computed here by central differences of l S_11 (relative
  // step 1e-5): to 1e-5 with dl = 1e-6; with m = 0 it is beta (E_t - S_11) dl/dt (the Green-Lagrange tangent), which
  // differs from it by more than 10 %. In the frequency domain (complex tangent, free laterals) m = 1 gives the loss
  // factor omega beta at both preloads (tan delta to 1e-9 relative); m = 0 does not (off by more than 10 % at 50 %).
  const auto foam = std::make_shared<Hyperfoam>(
      std::vector<HyperfoamTerm>{{0.010, 10.0, 0.0}, {0.0001, -2.0, 0.0}, {0.0005, 3.0, 0.0}});
  auto nominal_stress = [&](double l) { return l * foam->evaluate(Vec3(l, 1.0, 1.0).asDiagonal()).S(0); };
  const double beta = 2e-3, dt = 1e-5, omega = 2.0 * std::numbers::pi * 10.0;
  for (double l_old : {0.75, 0.5}) {
    const double h = 1e-5 * l_old, E_t = (nominal_stress(l_old + h) - nominal_stress(l_old - h)) / (2.0 * h);
    const double S11 = foam->evaluate(Vec3(l_old, 1.0, 1.0).asDiagonal()).S(0);
    const double l = l_old - 1e-6, l_dot = (l - l_old) / dt;
    const Mat3 F_old = Vec3(l_old, 1.0, 1.0).asDiagonal(), F_new = Vec3(l, 1.0, 1.0).asDiagonal();
    std::vector<double> none;
    for (double m_share : {1.0, 0.0}) {
      const StiffnessDampingEffect m(foam, foam, beta, 1.0, 1.0, 5.0, 0.0, m_share);
      const double P_d = l * (m.integrate(F_old, F_new, dt, none, none).S(0) - foam->evaluate(F_new).S(0));
      const double expected = beta * (E_t - (1.0 - m_share) * S11) * l_dot;
      EXPECT_NEAR(P_d / expected, 1.0, 1e-5) << "l " << l_old << ", m " << m_share;
      const std::complex<double> E_star = test::uniaxial_complex_modulus(m, F_old, S11, omega);
      const double loss_factor = E_star.imag() / E_star.real();
      if (m_share == 1.0) EXPECT_NEAR(loss_factor / (omega * beta), 1.0, 1e-9) << "l " << l_old;
      if (m_share == 0.0 && l_old == 0.5) EXPECT_GT(std::abs(loss_factor / (omega * beta) - 1.0), 0.1);
    }
    EXPECT_GT(std::abs(S11), 0.1 * E_t) << "l " << l_old;  // the initial-stress term matters here
  }
  EXPECT_THROW(StiffnessDampingEffect(foam, foam, beta, 1.0, 1.0, 5.0, 0.0, 1.5), std::invalid_argument);
}

TEST(EffectStiffnessDamping, NominalShareKeepsTheTangentsExact) {
  // m = 1 (and 0.5) with w = 0.6 on random F: the increment tangent against finite differences (relative 1e-6; the
  // initial-stress term is taken at the start of the increment like C_e) and, on the nu = 0.1 test foam, the complex
  // tangent against a time-domain sine at 25 % and 50 % preload (0.5 % on |E*|, 0.2 deg, 1000 steps a cycle).
  std::mt19937 rng(11);
  const auto foam = test::effect_test_foam();
  for (double m_share : {1.0, 0.5}) {
    const StiffnessDampingEffect m(foam, foam, 2e-3, 0.6, 1.0, 5.0, 0.0, m_share);
    for (int trial = 0; trial < 3; ++trial) {
      const Mat3 F_old = test::random_F(rng, 0.3), F = test::random_F(rng, 0.3);
      EXPECT_LT(test::increment_tangent_error(m, F_old, F, 0.01, {}), 1e-6) << "trial " << trial;
    }
  }
  const StiffnessDampingEffect m(foam, foam, 2e-3, 1.0, 1.0, 5.0, 0.0, 1.0);
  for (double preload : {-0.25, -0.5})
    for (double f : {1.0, 20.0}) {
      const test::SineComparison c = test::compare_sine(m, preload, 1.0, 1, f, 6, 1000);
      EXPECT_LT(c.modulus_error(), 5e-3) << f << " Hz, preload " << preload;
      EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz: phase " << c.phase_deg();
    }
}

}  // namespace
}  // namespace cushion::material
