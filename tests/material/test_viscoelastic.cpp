// Requirement: Viscoelastic reproduces the linear Prony relaxation modulus of the paper's Table 3 at
// small strain (step, ramp, sine with second-order convergence), its increment tangent is exact,
// the MODULI conventions and the frequency-domain factor match the closed forms of docs/physics.md 3.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "material/hyperfoam.hpp"
#include "material/neo_hookean.hpp"
#include "material/viscoelastic.hpp"
#include "tests/material/fd.hpp"

namespace cushion::material {
namespace {

using test::rel_diff;

// Deng et al. Table 3 (kPa -> MPa): long-term modulus and Prony moduli / times.
const double kEinf = 3.05e-3;
const std::vector<double> kE{23.9e-3, 19.7e-3, 8.99e-3, 12.4e-3, 8.14e-3};
const std::vector<double> kTau{0.01, 0.1, 1.0, 10.0, 100.0};

// Long-term base: hyperfoam with nu = 0, so F = diag(1 + eps, 1, 1) is uniaxial stress with free
// lateral faces at every strain, and the small-strain uniaxial modulus is 2 sum mu_i = E_inf.
std::shared_ptr<const Hyperfoam> long_term_foam() {
  return std::make_shared<Hyperfoam>(std::vector<HyperfoamTerm>{{0.35 * kEinf, 6.0, 0.0}, {0.15 * kEinf, -2.0, 0.0}});
}

Viscoelastic table3_material() { return Viscoelastic(long_term_foam(), prony_from_absolute(kEinf, kE, kTau)); }

Mat3 uniaxial(double eps) { return Vec3(1.0 + eps, 1.0, 1.0).asDiagonal(); }

/// Simple shear F = I + gamma e1 (x) e2: gamma is represented exactly (no 1 + eps round-off) and the
/// shear stress is odd in gamma, so at gamma = 1e-6 the nonlinearity is ~1e-12 relative.
Mat3 shear(double gamma) {
  Mat3 F = Mat3::Identity();
  F(0, 1) = gamma;
  return F;
}

/// Drives the point through shears gamma[k] at times t[k] (t[0] = 0, gamma[0] = 0) and returns
/// 2 S12 (the base has nu = 0, so E = 2 G and 2 S12 = E(t) gamma at small strain).
std::vector<double> drive(const Viscoelastic& m, const std::vector<double>& t, const std::vector<double>& gamma) {
  std::vector<double> state(m.state_size()), next(m.state_size()), out{0.0};
  m.initial_state(state);
  for (std::size_t k = 1; k < t.size(); ++k) {
    const PointResponse r = m.integrate(shear(gamma[k - 1]), shear(gamma[k]), t[k] - t[k - 1], state, next);
    EXPECT_EQ(r.status, Status::ok);
    out.push_back(2.0 * r.S(3));
    state.swap(next);
  }
  return out;
}

const double kGamma = 1e-6;

TEST(Viscoelastic, StepRelaxationMatchesPronySeries) {
  // Step in one increment with dt = 0, then held with large steps (exact for any dt). With nu = 0,
  // E = 2 G, so 2 S12 / gamma equals E(t) = E_inf + sum E_i e^{-t/tau_i}; tolerance 1e-8 relative.
  std::vector<double> t{0.0, 0.0}, g{0.0, kGamma};
  for (double tk = 1e-3; tk < 2e3; tk *= 1.5) t.push_back(tk), g.push_back(kGamma);
  const std::vector<double> s = drive(table3_material(), t, g);
  for (std::size_t k = 1; k < t.size(); ++k) {
    double E = kEinf;
    for (std::size_t i = 0; i < kE.size(); ++i) E += kE[i] * std::exp(-t[k] / kTau[i]);
    EXPECT_NEAR(s[k] / kGamma, E, 1e-8 * E) << "t = " << t[k];
  }
}

TEST(Viscoelastic, FiniteStrainStepRelaxesWithTheSameFunction) {
  // Uniaxial step to -40 % (nu = 0: lateral faces free): S11(t) = S_inf11 (1 + sum a_i e^{-t/tau_i})
  // exactly at any strain, i.e. S11(t)/S_inf11 = E(t)/E_inf; tolerance 1e-12 relative.
  const Viscoelastic m = table3_material();
  std::vector<double> s0(m.state_size()), s1(m.state_size());
  m.initial_state(s0);
  const Mat3 F = uniaxial(-0.4);
  const double S_inf = m.long_term_base().evaluate(F).S(0);
  double t = 0.0;
  PointResponse r = m.integrate(Mat3::Identity(), F, 0.0, s0, s1);
  for (double dt : {0.0, 0.003, 0.05, 0.5, 3.0, 30.0, 300.0}) {
    if (dt > 0.0) r = m.integrate(F, F, dt, s0, s1);
    t += dt;
    double E = kEinf;
    for (std::size_t i = 0; i < kE.size(); ++i) E += kE[i] * std::exp(-t / kTau[i]);
    EXPECT_NEAR(r.S(0) / S_inf, E / kEinf, 1e-12 * E / kEinf) << "t = " << t;
    s0.swap(s1);
  }
}

TEST(Viscoelastic, ConstantRateRampMatchesClosedForm) {
  // 2 S12 = E_inf rate t + sum E_i tau_i rate (1 - e^{-t/tau_i}); the recursion is exact for a linear
  // history, so uneven steps are used on purpose; tolerance 1e-8 relative.
  const double rate = kGamma / 20.0;
  std::vector<double> t{0.0}, g{0.0};
  for (double dt = 1e-3; t.back() < 20.0; dt *= 1.2) t.push_back(t.back() + dt), g.push_back(rate * t.back());
  const std::vector<double> s2 = drive(table3_material(), t, g);
  for (std::size_t k = 1; k < t.size(); ++k) {
    double s = kEinf * rate * t[k];
    for (std::size_t i = 0; i < kE.size(); ++i) s += kE[i] * kTau[i] * rate * -std::expm1(-t[k] / kTau[i]);
    EXPECT_NEAR(s2[k], s, 1e-8 * s) << "t = " << t[k];
  }
}

TEST(Viscoelastic, SineHistoryConvergesAtSecondOrder) {
  // gamma = g0 sin(w t); exact H_i = E_inf g0 w tau (cos wt + w tau sin wt - e^{-t/tau}) / (1 + w^2 tau^2).
  // Max error over t in [0, 2 s] for N, 2N, 4N, 8N steps; observed order log2(e_N / e_2N) in 2 +- 0.2.
  const double w = 2.0 * M_PI;
  auto exact = [&](double t) {
    double s = kEinf * kGamma * std::sin(w * t);
    for (std::size_t i = 0; i < kE.size(); ++i) {
      const double wt = w * kTau[i];
      s += kE[i] * kGamma * wt * (std::cos(w * t) + wt * std::sin(w * t) - std::exp(-t / kTau[i])) / (1.0 + wt * wt);
    }
    return s;
  };
  std::vector<double> errors;
  for (int N : {200, 400, 800, 1600}) {
    std::vector<double> t, g;
    for (int k = 0; k <= N; ++k) t.push_back(2.0 * k / N), g.push_back(kGamma * std::sin(w * t.back()));
    const std::vector<double> s2 = drive(table3_material(), t, g);
    double e = 0.0, scale = 0.0;
    for (int k = 0; k <= N; ++k) e = std::max(e, std::abs(s2[k] - exact(t[k]))), scale = std::max(scale, std::abs(exact(t[k])));
    errors.push_back(e / scale);
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    EXPECT_NEAR(order, 2.0, 0.2) << "errors " << errors[k] << " -> " << errors[k + 1];
  }
  EXPECT_LT(errors.back(), 1e-4);
}

TEST(Viscoelastic, IncrementTangentMatchesFiniteDifferences) {
  // dS_new/dE_new at fixed F_old, dt = 0.05 s, nonzero history, by central differences (h = 1e-6):
  // tolerance 1e-6 relative, for a hyperfoam and a neo-Hookean base.
  const auto terms = prony_from_absolute(kEinf, kE, kTau);
  const std::vector<std::shared_ptr<const Hyperelastic>> bases{
      std::make_shared<Hyperfoam>(std::vector<HyperfoamTerm>{{0.002, 6.0, 0.2}, {0.001, -2.0, 0.1}}),
      std::make_shared<NeoHookean>(0.002, 0.005)};
  std::mt19937 rng(17);
  for (const auto& base : bases) {
    const Viscoelastic m(base, terms);
    std::vector<double> state(m.state_size()), next(m.state_size());
    m.initial_state(state);
    Mat3 F_old = Mat3::Identity();
    for (int k = 0; k < 4; ++k) {  // build a history
      const Mat3 F = test::random_F(rng, 0.3);
      ASSERT_EQ(m.integrate(F_old, F, 0.07, state, next).status, Status::ok);
      state.swap(next), F_old = F;
    }
    ASSERT_GT(Eigen::Map<const Vec6>(state.data() + 6).norm(), 0.0);
    const double dt = 0.05;
    auto S_of = [&](const Mat3& F) {
      std::vector<double> out(m.state_size());
      return m.integrate(F_old, F, dt, state, out).S;
    };
    const Mat3 F_new = test::random_F(rng, 0.3);
    const PointResponse r = m.integrate(F_old, F_new, dt, state, next);
    EXPECT_LT(rel_diff(test::fd_dS_dE(S_of, F_new), r.dS_dE), 1e-6) << base->describe();
  }
}

TEST(Viscoelastic, ZeroStepIsInstantaneousJumpAndStateLayout) {
  // dt = 0: H_i^new = H_i^old + (S_inf^new - S_inf^old), tangent C_inf / (1 - sum g); 1e-14 relative.
  const Viscoelastic m = table3_material();
  std::vector<double> s0(m.state_size()), s1(m.state_size()), s2(m.state_size());
  m.initial_state(s0);
  const Mat3 F1 = uniaxial(-0.2), F2 = uniaxial(-0.3);
  m.integrate(Mat3::Identity(), F1, 0.5, s0, s1);
  const PointResponse r = m.integrate(F1, F2, 0.0, s1, s2);
  const ElasticEval e2 = m.long_term_base().evaluate(F2), e1 = m.long_term_base().evaluate(F1);
  EXPECT_LT(rel_diff(Eigen::Map<const Vec6>(s2.data()), e2.S), 1e-15);
  for (std::size_t i = 1; i <= kE.size(); ++i) {
    const Vec6 expected = Eigen::Map<const Vec6>(s1.data() + 6 * i) + (e2.S - e1.S);
    EXPECT_LT(rel_diff(Eigen::Map<const Vec6>(s2.data() + 6 * i), expected), 1e-14);
  }
  double sum_g = 0.0;
  for (const PronyTerm& t : m.terms()) sum_g += t.g;
  EXPECT_LT(rel_diff(r.dS_dE, e2.dS_dE / (1.0 - sum_g)), 1e-13);
}

TEST(Viscoelastic, ModuliConventions) {
  // LONG TERM: the base is the relaxed model, instantaneous = base / (1 - sum g).
  // INSTANTANEOUS: the base is the t = 0+ model, long-term = (1 - sum g) base. 1e-13 relative.
  const auto base = long_term_foam();
  const std::vector<PronyTerm> terms{{0.3, 0.1}, {0.5, 10.0}};
  const double mu0 = base->initial_shear_modulus();
  for (auto conv : {ModuliConvention::long_term, ModuliConvention::instantaneous}) {
    const Viscoelastic m(base, terms, conv);
    std::vector<double> s0(m.state_size()), s1(m.state_size());
    m.initial_state(s0);
    const double G_inst = m.integrate(Mat3::Identity(), Mat3::Identity(), 0.0, s0, s1).dS_dE(3, 3);
    const double G_long = m.long_term_base().evaluate(Mat3::Identity()).dS_dE(3, 3);
    EXPECT_NEAR(G_inst / G_long, 1.0 / (1.0 - 0.8), 1e-13 * 5.0);
    if (conv == ModuliConvention::long_term) {
      EXPECT_NEAR(G_long, mu0, 1e-13 * mu0);
    } else {
      EXPECT_NEAR(G_inst, mu0, 1e-13 * mu0);
    }
    EXPECT_NEAR(m.relative_to_long_term()[1], 0.5 / 0.2, 1e-13);
    // Fully relaxed after a long hold: the stress returns to the long-term base stress (1e-12).
    std::vector<double> s2(m.state_size());
    m.integrate(Mat3::Identity(), uniaxial(-0.4), 0.0, s0, s1);
    const PointResponse held = m.integrate(uniaxial(-0.4), uniaxial(-0.4), 1e4, s1, s2);
    EXPECT_LT(rel_diff(held.S, m.long_term_base().evaluate(uniaxial(-0.4)).S), 1e-12);
  }
}

TEST(Viscoelastic, ComplexModulusMatchesClosedForm) {
  // E'(w) = E_inf + sum E_r w^2 T_r^2/(1 + w^2 T_r^2), E''(w) = sum E_r w T_r/(1 + w^2 T_r^2): 1e-12 relative,
  // from prony_complex_factor and from the uniaxial modulus of Viscoelastic::complex_tangent at F = I.
  const auto terms = prony_from_absolute(kEinf, kE, kTau);
  const Viscoelastic m = table3_material();
  for (double w : {0.0, 0.05, 1.0, 2.0 * M_PI, 30.0, 2.0 * M_PI * 20.0, 1e4}) {
    double Es = kEinf, El = 0.0;
    for (std::size_t r = 0; r < kE.size(); ++r) {
      const double wt = w * kTau[r];
      Es += kE[r] * wt * wt / (1.0 + wt * wt);
      El += kE[r] * wt / (1.0 + wt * wt);
    }
    const std::complex<double> f = kEinf * prony_complex_factor(terms, w);
    EXPECT_NEAR(f.real(), Es, 1e-12 * Es) << w;
    EXPECT_NEAR(f.imag(), El, 1e-12 * Es) << w;
    const std::complex<double> Eu = 1.0 / m.complex_tangent(Mat3::Identity(), w).inverse()(0, 0);
    EXPECT_NEAR(Eu.real(), Es, 1e-12 * Es) << w;
    EXPECT_NEAR(Eu.imag(), El, 1e-12 * Es) << w;
  }
}

TEST(Viscoelastic, PronyConversionAndValidation) {
  const auto terms = prony_from_absolute(kEinf, kE, kTau);
  double E0 = kEinf;
  for (double e : kE) E0 += e;
  for (std::size_t i = 0; i < kE.size(); ++i) EXPECT_NEAR(terms[i].g, kE[i] / E0, 1e-16);
  EXPECT_THROW(prony_from_absolute(kEinf, {-1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(prony_from_absolute(kEinf, {1.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(Viscoelastic(long_term_foam(), {{0.6, 1.0}, {0.4, 2.0}}), std::invalid_argument);
  EXPECT_THROW(Viscoelastic(long_term_foam(), {{0.1, 0.0}}), std::invalid_argument);
  EXPECT_THROW(Viscoelastic(long_term_foam(), {{-0.1, 1.0}}), std::invalid_argument);
  const Viscoelastic m = table3_material();
  EXPECT_EQ(m.state_size(), 36u);
  std::vector<double> s0(36), s1(36);
  EXPECT_EQ(m.integrate(Mat3::Identity(), uniaxial(-1.5), 0.1, s0, s1).status, Status::failed);
}

}  // namespace
}  // namespace cushion::material

namespace cushion::material {
namespace {

// prony_recursion remembers recent x = dt/tau per thread (a speed-up): whatever the order of the calls and the
// collisions of its slots, every value must equal the closed form e^-x, (1 - e^-x)/x bit for bit.
TEST(PronyRecursion, RememberedValuesEqualTheClosedFormWhateverTheCallOrder) {
  std::vector<std::pair<double, double>> calls;
  for (int k = 0; k < 400; ++k) calls.push_back({1e-4 * (1 + k % 37), std::pow(10.0, -3.0 + 0.01 * (k % 300))});
  for (int pass = 0; pass < 3; ++pass) {
    for (const auto& [dt, tau] : calls) {
      const double x = dt / tau;
      const PronyRecursion q = prony_recursion(dt, tau);
      ASSERT_EQ(q.decay, std::exp(-x)) << "dt " << dt << " tau " << tau;
      ASSERT_EQ(q.weight, -std::expm1(-x) / x) << "dt " << dt << " tau " << tau;
    }
    std::reverse(calls.begin(), calls.end());
  }
  const PronyRecursion instant = prony_recursion(0.0, 1.0);
  EXPECT_EQ(instant.decay, 1.0);
  EXPECT_EQ(instant.weight, 1.0);
}

}  // namespace
}  // namespace cushion::material
