// Requirement: the Mullins (Ogden-Roxburgh) effect leaves first loading unchanged, softens unloading
// by the closed-form eta, reloading retraces unloading below W_max and rejoins the base curve above it;
// its increment tangent is exact and its complex tangent is the reversible tangent at W_max. With a relaxation share
// w over a Prony material the memory is driven by eta^w S_e (checked against the test's own recursion), also over
// strain-dependent Prony beneath. The same with
// the strain driver (strain_scale m_e > 0): the Biot strain norm D = ||U - I|| in place of W (here evaluated from the
// eigenvalues of F^T F, not from the effect's principal decomposition; 1 - l on the confined path). With damage
// (damage_limit d_inf > 0) the factor 1 - d_inf (1 - exp(-N_max/e_d)) of the largest Biot strain norm multiplies eta,
// on first loading too, and the tangents, the complex tangent and the memory path follow it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "material/effect_mullins.hpp"
#include "material/effect_strain_dependent_prony.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

const MullinsParameters kParameters{2.0, 2e-4, 0.2};
const MullinsParameters kStrainParameters{2.0, 2e-4, 0.2, 0.0, 0.05};  // m unused

Mat3 confined(double l) { return Vec3(l, 1.0, 1.0).asDiagonal(); }

/// ||U - I|| from the eigenvalues of C = F^T F.
double biot_norm(const Mat3& F) {
  const Vec3 l = Eigen::SelfAdjointEigenSolver<Mat3>(F.transpose() * F).eigenvalues().cwiseSqrt();
  return (l.array() - 1.0).matrix().norm();
}

/// The driver of parameters p at F over the energy base `foam`: W or the Biot strain norm.
double driver(const MullinsParameters& p, const Hyperelastic& foam, const Mat3& F) {
  return p.strain_scale > 0.0 ? biot_norm(F) : foam.evaluate(F).W;
}

/// A maximum of the driver safely above its value at F (the softening active, eta < 1).
double maximum_above(const MullinsParameters& p, const Hyperelastic& foam, const Mat3& F) {
  return 1.3 * driver(p, foam, F) + (p.strain_scale > 0.0 ? p.strain_scale : p.m);
}

/// S11 along the stretches l[k] (laterally confined), from the virgin state with dt = 0.1 s.
std::vector<double> drive(const Material& m, const std::vector<double>& l) {
  std::vector<double> state(m.state_size()), next(m.state_size()), S11;
  m.initial_state(state);
  Mat3 F_old = Mat3::Identity();
  for (double lk : l) {
    const PointResponse r = m.integrate(F_old, confined(lk), 0.1, state, next);
    EXPECT_EQ(r.status, Status::ok) << r.message;
    S11.push_back(r.S(0));
    state.swap(next);
    F_old = confined(lk);
  }
  return S11;
}

/// 1 -> 0.6 (load), 0.6 -> 0.9 (unload), 0.9 -> 0.6 (reload), 0.6 -> 0.5 (beyond), steps of 0.01.
std::vector<double> path() {
  std::vector<double> l;
  for (int n = 99; n >= 60; --n) l.push_back(n / 100.0);  // k = 0..39
  for (int n = 61; n <= 90; ++n) l.push_back(n / 100.0);  // k = 40..69
  for (int n = 89; n >= 50; --n) l.push_back(n / 100.0);  // k = 70..109
  return l;
}

/// Along path(): the base curve on first loading and beyond the previous maximum, eta(D) S_base below it from the
/// closed form with the driver D(l), reloading retracing unloading; 1e-10 relative.
void check_loading_unloading_reloading(const MullinsParameters& p, const std::function<double(double)>& D_of_l) {
  const auto foam = test::effect_test_foam();
  const MullinsEffect m(foam, foam, p);
  const std::vector<double> l = path(), S = drive(m, l), S_base = drive(*foam, l);
  const double D_max = D_of_l(0.6), scale = (p.strain_scale > 0.0 ? p.strain_scale : p.m) + p.beta * D_max;
  for (std::size_t k = 0; k < l.size(); ++k) {
    const double D = D_of_l(l[k]);
    if (k < 40 || k > 99) {
      // First loading and loading beyond the previous maximum: the base curve (eta = 1), exact to 1e-10.
      EXPECT_NEAR(S[k], S_base[k], 1e-10 * std::abs(S_base[k])) << "l = " << l[k];
      continue;
    }
    // Unloading/reloading: eta from the closed form (independent erf evaluation), 1e-10 relative;
    // the stress is strictly below the loading stress in magnitude.
    const double eta = 1.0 - std::erf((D_max - D) / scale) / p.r;
    EXPECT_NEAR(S[k], eta * S_base[k], 1e-10 * std::abs(S_base[k])) << "l = " << l[k];
    if (D < D_max * (1.0 - 1e-9)) {
      EXPECT_LT(std::abs(S[k]), std::abs(S_base[k]) * (1.0 - 1e-6)) << "l = " << l[k];
    }
  }
  // Reload retraces the unloading curve below the maximum: same stretch, same stress, 1e-10 relative.
  for (std::size_t k = 40; k < 69; ++k) {
    const std::size_t k_reload = 138 - k;  // l[k_reload] == l[k] (0.61 .. 0.89)
    ASSERT_DOUBLE_EQ(l[k_reload], l[k]);
    EXPECT_NEAR(S[k_reload], S[k], 1e-10 * std::abs(S[k])) << "l = " << l[k];
  }
  // The softening is substantial at l = 0.9 (not a trivial check).
  EXPECT_LT(std::abs(S[69]), 0.9 * std::abs(S_base[69]));
}

TEST(EffectMullins, LoadingUnloadingReloading) {
  const auto foam = test::effect_test_foam();
  check_loading_unloading_reloading(kParameters, [&](double l) { return foam->evaluate(confined(l)).W; });
}

TEST(EffectMullins, StrainDriverSoftensByTheStrainBelowItsMaximum) {
  // On the confined path the Biot strain norm is the nominal strain 1 - l.
  check_loading_unloading_reloading(kStrainParameters, [](double l) { return 1.0 - l; });
}

TEST(EffectMullins, TangentMatchesFiniteDifferences) {
  // Random F below a previous maximum (1.3 D + m), on the loading branch (maximum 0), over hyperfoam and over the
  // viscoelastic model with a non-trivial state, energy and strain drivers. Tolerance 1e-6 relative.
  std::mt19937 rng(17);
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  for (const MullinsParameters& p : {kParameters, kStrainParameters}) {
    const MullinsEffect on_foam(foam, foam, p);
    const MullinsEffect on_visco(visco, foam, p);
    for (int trial = 0; trial < 4; ++trial) {
      const Mat3 F_old = test::random_F(rng, 0.25), F = test::random_F(rng, 0.25);
      for (double D_max : {maximum_above(p, *foam, F), 0.0}) {
        EXPECT_LT(test::increment_tangent_error(on_foam, F_old, F, 0.05, {D_max}), 1e-6) << "trial " << trial;
        std::vector<double> state(on_visco.state_size()), next(on_visco.state_size());
        on_visco.initial_state(state);
        on_visco.integrate(Mat3::Identity(), F_old, 0.05, state, next);
        next.back() = D_max;
        EXPECT_LT(test::increment_tangent_error(on_visco, F_old, F, 0.05, next), 1e-6) << "trial " << trial;
      }
    }
  }
}

TEST(EffectMullins, ComplexTangentIsTheReversibleTangentAtTheMaximum) {
  // complex_tangent(F_b) equals the increment tangent just below the maximum D_max = D(F_b) (unloading side),
  // 1e-8 relative, is real, and differs from the base tangent (the softening slope); energy and strain drivers.
  const auto foam = test::effect_test_foam();
  const Mat3 F_b = Vec3(0.75, 0.98, 0.98).asDiagonal();
  for (const MullinsParameters& p : {kParameters, kStrainParameters}) {
    const MullinsEffect m(foam, foam, p);
    std::vector<double> state{driver(p, *foam, F_b) * (1.0 + 1e-12)}, next(1);
    const PointResponse r = m.integrate(F_b, F_b, 1.0, state, next);
    const Mat6c C = m.complex_tangent(F_b, 10.0);
    EXPECT_LT(test::rel_diff(r.dS_dE, C.real().eval()), 1e-8);
    EXPECT_EQ(C.imag(), Mat6::Zero());
    EXPECT_GT(test::rel_diff(C.real().eval(), foam->evaluate(F_b).dS_dE), 1e-3);
  }
}

MullinsParameters with_share(double w) {
  MullinsParameters p = kParameters;
  p.relaxation_share = w;
  return p;
}

/// S11 of the foreign order along path() (laterally confined, dt = 0.1 s), by this test's own recursion:
/// S = eta^(1-w) [zeta S_e + phi^(1-w_s) sum a_i H_i], H_i <- e^{-x} H_i + (1 - e^{-x})/x phi^w_s (zeta S_e -
/// previous), zeta = eta^w, with the strain-dependent Prony factor phi = J^-c (J = l here) of history share w_s
/// beneath (c = 0: phi = 1, the Mullins effect directly over the Prony material).
std::vector<double> softened_memory_reference(const Viscoelastic& visco, const Hyperelastic& base, double w,
                                              double c = 0.0, double w_s = 0.0) {
  const std::vector<double> l = path();
  std::vector<double> H(visco.terms().size(), 0.0), S11;
  double W_max = 0.0, driving_old = 0.0, sum_g = 0.0;
  for (const PronyTerm& t : visco.terms()) sum_g += t.g;
  for (double lk : l) {
    const ElasticEval e = base.evaluate(confined(lk));
    W_max = std::max(W_max, e.W);
    const double eta = 1.0 - std::erf((W_max - e.W) / (kParameters.m + kParameters.beta * W_max)) / kParameters.r;
    const double driving = std::pow(eta, w) * e.S(0), phi = std::pow(lk, -c);
    double viscous = 0.0;
    for (std::size_t i = 0; i < H.size(); ++i) {
      const double x = 0.1 / visco.terms()[i].tau;
      H[i] = std::exp(-x) * H[i] + (1.0 - std::exp(-x)) / x * std::pow(phi, w_s) * (driving - driving_old);
      viscous += visco.terms()[i].g / (1.0 - sum_g) * H[i];  // a_i = g_i / (1 - sum g)
    }
    driving_old = driving;
    S11.push_back(std::pow(eta, 1.0 - w) * (driving + std::pow(phi, 1.0 - w_s) * viscous));
  }
  return S11;
}

TEST(EffectMullins, RelaxationShareDrivesThePronyMemoryWithTheSoftenedStress) {
  // Over the Prony material, w = 1 (the softened long-term stress drives the memory), w = 0.5 and w = 0 against the
  // test's own recursion, 1e-9 relative; on unloading w = 1 differs from w = 0 by more than 1 % (not a vacuous check).
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const std::vector<double> l = path();
  std::vector<std::vector<double>> S;
  for (double w : {1.0, 0.5, 0.0}) {
    const MullinsEffect m(visco, foam, with_share(w));
    S.push_back(drive(m, l));
    const std::vector<double> reference = softened_memory_reference(*visco, *foam, w);
    for (std::size_t k = 0; k < l.size(); ++k)
      EXPECT_NEAR(S.back()[k], reference[k], 1e-9 * std::abs(reference[k])) << "w = " << w << ", l = " << l[k];
  }
  EXPECT_GT(std::abs(S[0][69] - S[2][69]), 0.01 * std::abs(S[2][69]));
}

TEST(EffectMullins, RelaxationShareComposesWithStrainDependentPronyBeneath) {
  // Directly over strain-dependent Prony (c = 1.5, history share 0, 0.6 and 1) the memory is driven by eta^w S_e
  // weighted by phi^w_s and read scaled by phi^(1-w_s): against the test's own recursion, 1e-9 relative, w = 1 and
  // 0.5; and the result differs from the same Mullins over the plain Prony material by more than 1 % (the strain
  // dependence is not lost).
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const std::vector<double> l = path();
  for (double w_s : {0.0, 0.6, 1.0})
    for (double w : {1.0, 0.5}) {
      const auto sdp = std::make_shared<StrainDependentPronyEffect>(visco, 1.5, w_s);
      const std::vector<double> S = drive(MullinsEffect(sdp, foam, with_share(w)), l);
      const std::vector<double> reference = softened_memory_reference(*visco, *foam, w, 1.5, w_s);
      for (std::size_t k = 0; k < l.size(); ++k)
        EXPECT_NEAR(S[k], reference[k], 1e-9 * std::abs(reference[k]))
            << "w_s = " << w_s << ", w = " << w << ", l = " << l[k];
      const std::vector<double> plain = drive(MullinsEffect(visco, foam, with_share(w)), l);
      EXPECT_GT(std::abs(S[69] - plain[69]), 0.01 * std::abs(plain[69]));
    }
}

TEST(EffectMullins, RelaxationShareTangentsMatchFiniteDifferences) {
  // Below a previous maximum over the Prony material and over strain-dependent Prony on it (c = 1.5, history share
  // 0.6) with a non-trivial state, w = 0.5 and 1, energy and strain drivers: 1e-6 relative.
  std::mt19937 rng(23);
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const std::shared_ptr<const Material> sdp = std::make_shared<StrainDependentPronyEffect>(visco, 1.5, 0.6);
  for (const std::shared_ptr<const Material>& memory : {std::shared_ptr<const Material>(visco), sdp})
    for (const MullinsParameters& driven : {kParameters, kStrainParameters})
      for (double w : {0.5, 1.0}) {
        MullinsParameters p = driven;
        p.relaxation_share = w;
        const MullinsEffect m(memory, foam, p);
        for (int trial = 0; trial < 4; ++trial) {
          const Mat3 F_old = test::random_F(rng, 0.25), F = test::random_F(rng, 0.25);
          std::vector<double> state(m.state_size()), next(m.state_size());
          m.initial_state(state);
          m.integrate(Mat3::Identity(), F_old, 0.05, state, next);
          next.back() = maximum_above(p, *foam, F);
          EXPECT_LT(test::increment_tangent_error(m, F_old, F, 0.05, next), 1e-6) << "w = " << w << ", trial " << trial;
        }
      }
}

TEST(EffectMullins, RelaxationShareComplexTangentMatchesATimeDomainSine) {
  // A small sine about a held, relaxed preload (it shakes down below W_max after its first cycle): |E*| to 1 % and
  // the phase to 0.2 deg at 1 and 10 Hz with w = 1; the w = 1 and w = 0 moduli differ by more than that at 10 Hz.
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const MullinsEffect shared(visco, foam, with_share(1.0)), outside(visco, foam, with_share(0.0));
  for (double f : {1.0, 10.0}) {
    const test::SineComparison c = test::compare_sine(shared, -0.25, 2000.0, 400, f, 8, 400);
    EXPECT_LT(c.modulus_error(), 0.01) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz";
  }
  const test::SineComparison a = test::compare_sine(shared, -0.25, 2000.0, 400, 10.0, 8, 400);
  const test::SineComparison b = test::compare_sine(outside, -0.25, 2000.0, 400, 10.0, 8, 400);
  EXPECT_GT(std::abs(a.frequency_domain / b.frequency_domain - 1.0), 0.02);
  // Over strain-dependent Prony (c = 1.5, history share 0.6): the same tolerances, and the modulus differs from the
  // plain Prony material's by more than them (f(J_b) = 0.75^-1.5 = 1.54 scales the memory).
  const auto sdp = std::make_shared<StrainDependentPronyEffect>(visco, 1.5, 0.6);
  const MullinsEffect over_sdp(sdp, foam, with_share(1.0));
  for (double f : {1.0, 10.0}) {
    const test::SineComparison c = test::compare_sine(over_sdp, -0.25, 2000.0, 400, f, 8, 400);
    EXPECT_LT(c.modulus_error(), 0.01) << f << " Hz";
    EXPECT_LT(c.phase_error_deg(), 0.2) << f << " Hz";
  }
  const test::SineComparison d = test::compare_sine(over_sdp, -0.25, 2000.0, 400, 10.0, 8, 400);
  EXPECT_GT(std::abs(d.frequency_domain / a.frequency_domain - 1.0), 0.02);
}

TEST(EffectMullins, RelaxationShareNeedsMullinsFirstOnAPronyMaterial) {
  const auto foam = test::effect_test_foam();
  EXPECT_THROW(MullinsEffect(foam, foam, with_share(0.5)), std::invalid_argument);
  EXPECT_THROW(MullinsEffect(test::effect_test_visco(), foam, with_share(1.5)), std::invalid_argument);
}

TEST(EffectMullins, NegativeStrainScaleIsRejected) {
  MullinsParameters negative = kStrainParameters;
  negative.strain_scale = -0.1;
  const auto foam = test::effect_test_foam();
  EXPECT_THROW(MullinsEffect(foam, foam, negative), std::invalid_argument);
}

MullinsParameters with_damage(MullinsParameters p, double d_inf = 0.6, double e_d = 0.15) {
  p.damage_limit = d_inf, p.damage_strain = e_d;
  return p;
}

TEST(EffectMullins, DamageSoftensFirstLoadingAndStaysBelowItsMaximum) {
  // Along path() (confined, N = 1 - l): S = eta(D) (1 - d(N_max)) S_base with the closed forms, 1e-10 relative, for the
  // energy and the strain driver; on first loading (eta = 1) the stress is already (1 - d(N)) S_base, below the base by
  // more than 30 % at l = 0.6; reloading below the maximum retraces unloading.
  const auto foam = test::effect_test_foam();
  for (const MullinsParameters& driven : {kParameters, kStrainParameters}) {
    const MullinsParameters p = with_damage(driven);
    const MullinsEffect m(foam, foam, p);
    const std::vector<double> l = path(), S = drive(m, l), S_base = drive(*foam, l);
    double D_max = 0.0, N_max = 0.0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const double D = driver(p, *foam, confined(l[k])), N = 1.0 - l[k];
      D_max = std::max(D_max, D), N_max = std::max(N_max, N);
      const double scale = (p.strain_scale > 0.0 ? p.strain_scale : p.m) + p.beta * D_max;
      const double eta = 1.0 - std::erf((D_max - D) / scale) / p.r;
      const double factor = 1.0 - p.damage_limit * (1.0 - std::exp(-N_max / p.damage_strain));
      EXPECT_NEAR(S[k], eta * factor * S_base[k], 1e-10 * std::abs(S_base[k])) << "l = " << l[k];
    }
    EXPECT_LT(std::abs(S[39]), 0.7 * std::abs(S_base[39]));  // l = 0.6, first loading
    for (std::size_t k = 40; k < 69; ++k) EXPECT_NEAR(S[138 - k], S[k], 1e-10 * std::abs(S[k])) << "l = " << l[k];
  }
}

TEST(EffectMullins, DamageTangentsMatchFiniteDifferences) {
  // Random F on first loading (both maxima 0) and below previous maxima, over hyperfoam, over the Prony material
  // (w = 0 and w = 1: the damage drives the memory) with a non-trivial state; energy and strain drivers. 1e-6 relative.
  std::mt19937 rng(29);
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  for (const MullinsParameters& driven : {kParameters, kStrainParameters})
    for (double w : {0.0, 1.0}) {
      MullinsParameters p = with_damage(driven);
      p.relaxation_share = w;
      const MullinsEffect on_visco(visco, foam, p);
      const MullinsEffect on_foam(foam, foam, with_damage(driven));
      for (int trial = 0; trial < 4; ++trial) {
        const Mat3 F_old = test::random_F(rng, 0.25), F = test::random_F(rng, 0.25);
        for (bool below : {true, false}) {
          const double D_max = below ? maximum_above(p, *foam, F) : 0.0,
                       N_max = below ? 1.3 * biot_norm(F) + 0.05 : 0.0;
          EXPECT_LT(test::increment_tangent_error(on_foam, F_old, F, 0.05, {D_max, N_max}), 1e-6) << "trial " << trial;
          std::vector<double> state(on_visco.state_size()), next(on_visco.state_size());
          on_visco.initial_state(state);
          on_visco.integrate(Mat3::Identity(), F_old, 0.05, state, next);
          next[next.size() - 2] = D_max, next.back() = N_max;
          EXPECT_LT(test::increment_tangent_error(on_visco, F_old, F, 0.05, next), 1e-6)
              << "w = " << w << ", trial " << trial << (below ? " below" : " loading");
        }
      }
    }
}

TEST(EffectMullins, DamageComplexTangentIsTheReversibleTangentAtTheMaximum) {
  // With damage, complex_tangent(F_b) equals the increment tangent just below both maxima (1e-8 relative) and is
  // (1 - d(N_b)) times the tangent without damage.
  const auto foam = test::effect_test_foam();
  const Mat3 F_b = Vec3(0.75, 0.98, 0.98).asDiagonal();
  for (const MullinsParameters& driven : {kParameters, kStrainParameters}) {
    const MullinsParameters p = with_damage(driven);
    const MullinsEffect m(foam, foam, p), undamaged(foam, foam, driven);
    std::vector<double> state{driver(p, *foam, F_b) * (1.0 + 1e-12), biot_norm(F_b) * (1.0 + 1e-12)}, next(2);
    const PointResponse r = m.integrate(F_b, F_b, 1.0, state, next);
    const Mat6c C = m.complex_tangent(F_b, 10.0);
    EXPECT_LT(test::rel_diff(r.dS_dE, C.real().eval()), 1e-8);
    const double factor = 1.0 - p.damage_limit * (1.0 - std::exp(-biot_norm(F_b) / p.damage_strain));
    EXPECT_LT(test::rel_diff(C.real().eval(), (factor * undamaged.complex_tangent(F_b, 10.0).real()).eval()), 1e-12);
    EXPECT_LT(factor, 0.8);
  }
}

TEST(EffectMullins, DamageOutsideItsRangeIsRejected) {
  const auto foam = test::effect_test_foam();
  EXPECT_THROW(MullinsEffect(foam, foam, with_damage(kParameters, 1.0)), std::invalid_argument);
  EXPECT_THROW(MullinsEffect(foam, foam, with_damage(kParameters, -0.1)), std::invalid_argument);
  EXPECT_THROW(MullinsEffect(foam, foam, with_damage(kParameters, 0.5, 0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::material
