// Requirement: Hyperfoam returns the ABAQUS hyperfoam stresses of docs/physics.md section 2.3 in every
// homogeneous mode, the exact tangent dS/dE (also at equal and nearly equal stretches), S = 2 dW/dC,
// objective stresses, the documented initial moduli, and Status::failed for J <= 0 or overflow; its evaluation memo
// never answers for another instance.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <thread>

#include "material/hyperfoam.hpp"
#include "tests/material/fd.hpp"

namespace cushion::material {
namespace {

using test::fd_dS_dE;
using test::rel_diff;

// Closed forms of docs/physics.md 2.3 written independently of the implementation (std::pow only).
struct ClosedForm {
  std::vector<HyperfoamTerm> t;
  double nu;  // the common nu of all terms
  double sum(double (*f)(const HyperfoamTerm&, double, double), double l) const {
    double r = 0.0;
    for (const auto& k : t) r += f(k, l, nu);
    return r;
  }
  double uniaxial(double l) const {  // T_U, lateral stretch l^-nu
    return sum([](const HyperfoamTerm& k, double l, double nu) {
      return 2.0 * k.mu / k.alpha * (std::pow(l, k.alpha - 1.0) - std::pow(l, -k.alpha * nu - 1.0));
    }, l);
  }
  double constrained(double l) const {  // F = diag(l, 1, 1): P11 = sum 2mu/a (l^a - l^(-a beta)) / l
    return sum([](const HyperfoamTerm& k, double l, double nu) {
      return 2.0 * k.mu / k.alpha * (std::pow(l, k.alpha) - std::pow(l, -k.alpha * k.beta())) / l;
    }, l);
  }
  double equibiaxial(double l) const {  // T_B, l3 = l^(-2nu/(1-nu))
    return sum([](const HyperfoamTerm& k, double l, double nu) {
      const double l3 = std::pow(l, -2.0 * nu / (1.0 - nu));
      return 2.0 * k.mu / k.alpha * (std::pow(l, k.alpha) - std::pow(l3, k.alpha)) / l;
    }, l);
  }
  double planar(double l) const {  // T_P, l2 = 1, l3 = l^(-nu/(1-nu))
    return sum([](const HyperfoamTerm& k, double l, double nu) {
      const double l3 = std::pow(l, -nu / (1.0 - nu));
      return 2.0 * k.mu / k.alpha * (std::pow(l, k.alpha) - std::pow(l3, k.alpha)) / l;
    }, l);
  }
  double pressure(double J) const {  // p = -(2/J) sum mu/a (J^(a/3) - J^(-a beta))
    double r = 0.0;
    for (const auto& k : t) r += k.mu / k.alpha * (std::pow(J, k.alpha / 3.0) - std::pow(J, -k.alpha * k.beta()));
    return -2.0 / J * r;
  }
};

std::vector<HyperfoamTerm> terms_with_nu(double nu) {
  // A typical seat-foam shape: a stiff high-alpha term, a negative-alpha term, a mild one [MPa].
  return {{0.02, 9.0, nu}, {0.004, -3.0, nu}, {-0.002, 2.0, nu}};
}

Mat3 diag(double a, double b, double c) { return Vec3(a, b, c).asDiagonal(); }

class HyperfoamClosedForm : public ::testing::TestWithParam<double> {};

TEST_P(HyperfoamClosedForm, HomogeneousModesMatchClosedForms) {
  // Tolerance: 1e-10 relative on the nominal stress; free lateral faces carry < 1e-10 of it.
  const double nu = GetParam();
  const Hyperfoam model(terms_with_nu(nu));
  const ClosedForm cf{terms_with_nu(nu), nu};
  const double tol = 1e-10;
  for (double l : {0.15, 0.4, 0.7, 0.95, 0.9999, 1.0001, 1.3, 2.0, 3.0}) {
    {  // uniaxial, lateral faces free
      const double lL = std::pow(l, -nu);
      const Vec6 S = model.evaluate(diag(l, lL, lL)).S;
      const double T = cf.uniaxial(l);
      EXPECT_NEAR(l * S(0), T, tol * std::abs(T)) << "uniaxial l=" << l;
      EXPECT_NEAR(lL * S(1), 0.0, tol * std::abs(T));
      EXPECT_NEAR(lL * S(2), 0.0, tol * std::abs(T));
    }
    {  // laterally constrained uniaxial
      const double T = cf.constrained(l);
      EXPECT_NEAR(l * model.evaluate(diag(l, 1.0, 1.0)).S(0), T, tol * std::abs(T)) << "constrained l=" << l;
    }
    {  // equibiaxial
      const double l3 = std::pow(l, -2.0 * nu / (1.0 - nu));
      const Vec6 S = model.evaluate(diag(l, l, l3)).S;
      const double T = cf.equibiaxial(l);
      EXPECT_NEAR(l * S(0), T, tol * std::abs(T)) << "equibiaxial l=" << l;
      EXPECT_NEAR(l * S(1), T, tol * std::abs(T));
      EXPECT_NEAR(l3 * S(2), 0.0, tol * std::abs(T));
    }
    {  // planar
      const double l3 = std::pow(l, -nu / (1.0 - nu));
      const Vec6 S = model.evaluate(diag(l, 1.0, l3)).S;
      const double T = cf.planar(l);
      EXPECT_NEAR(l * S(0), T, tol * std::abs(T)) << "planar l=" << l;
      EXPECT_NEAR(l3 * S(2), 0.0, tol * std::abs(T));
    }
    {  // volumetric: J = l^3, Cauchy sigma = -p I
      const double J = l * l * l;
      const Mat3 F = diag(l, l, l);
      const Mat3 sigma = cauchy_from_pk2(F, from_voigt_stress(model.evaluate(F).S));
      const double p = cf.pressure(J);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(-sigma(a, a), p, tol * std::abs(p)) << "volumetric J=" << J;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Nu, HyperfoamClosedForm, ::testing::Values(0.0, 0.1, 0.3, 0.45));

TEST(Hyperfoam, InitialModuliFromTangent) {
  // Mixed nu per term: mu0 = sum mu_i, K0 = sum 2 mu_i (1/3 + beta_i); 1e-13 relative.
  const Hyperfoam model({{0.02, 9.0, 0.1}, {0.004, -3.0, 0.3}, {0.001, 2.0, 0.0}});
  const Mat6 D = model.evaluate(Mat3::Identity()).dS_dE;
  const double mu0 = 0.025, K0 = 2.0 * (0.02 * (1.0 / 3 + 0.1 / 0.8) + 0.004 * (1.0 / 3 + 0.3 / 0.4) + 0.001 / 3);
  for (int k = 3; k < 6; ++k) EXPECT_NEAR(D(k, k), mu0, 1e-13 * mu0);
  EXPECT_NEAR(D.block(0, 0, 3, 3).sum() / 9.0, K0, 1e-13 * K0);
  EXPECT_NEAR(model.initial_shear_modulus(), mu0, 1e-15);
  EXPECT_NEAR(model.initial_bulk_modulus(), K0, 1e-15);
  // Isotropy at F = I: D(0,0) - D(0,1) = 2 mu0.
  EXPECT_NEAR(D(0, 0) - D(0, 1), 2.0 * mu0, 1e-13 * mu0);
}

TEST(Hyperfoam, TangentMatchesFiniteDifferences) {
  // Central differences in E (h = 1e-6, engineering shear): tolerance 1e-6 relative (norm-wise).
  const Hyperfoam model({{0.02, 6.0, 0.1}, {0.004, -3.0, 0.3}, {-0.002, 2.0, 0.0}});
  auto S_of = [&](const Mat3& F) { return model.evaluate(F).S; };
  std::mt19937 rng(11);
  std::vector<std::pair<std::string, Mat3>> states{{"identity", Mat3::Identity()}};
  for (int k = 0; k < 6; ++k) states.push_back({"random", test::random_F(rng)});
  states.push_back({"two equal", test::F_with_stretches({1.2, 1.2, 0.7}, rng)});
  states.push_back({"two equal (low)", test::F_with_stretches({0.6, 0.9, 0.6}, rng)});
  states.push_back({"three equal", test::F_with_stretches({0.8, 0.8, 0.8}, rng)});
  states.push_back({"nearly equal", test::F_with_stretches({1.2, 1.2 + 1e-7, 0.7}, rng)});
  states.push_back({"three nearly equal", test::F_with_stretches({1.1, 1.1 + 1e-7, 1.1 - 2e-7}, rng)});
  states.push_back({"near identity", test::F_with_stretches({1.0 + 3e-8, 1.0 - 1e-7, 1.0}, rng)});
  for (const auto& [name, F] : states) {
    const ElasticEval e = model.evaluate(F);
    ASSERT_EQ(e.status, Status::ok) << name;
    EXPECT_LT(rel_diff(fd_dS_dE(S_of, F), e.dS_dE), 1e-6) << name;
    EXPECT_LT((e.dS_dE - e.dS_dE.transpose()).cwiseAbs().maxCoeff(), 1e-13 * e.dS_dE.cwiseAbs().maxCoeff()) << name;
  }
}

TEST(Hyperfoam, TangentContinuousAtCoalescingStretches) {
  // Exactly equal and separated by d stretches give tangents differing by the O(d) change only
  // (tolerance 100 d relative): no accuracy is lost to cancellation as stretches coalesce.
  const Hyperfoam model(terms_with_nu(0.2));
  std::mt19937 rng(5);
  const Mat3 R = test::random_rotation(rng);
  for (double d : {1e-12, 1e-10}) {
    const Mat3 Fe = R * diag(1.3, 1.3, 0.6), Fn = R * diag(1.3, 1.3 + d, 0.6);
    EXPECT_LT(rel_diff(model.evaluate(Fn).dS_dE, model.evaluate(Fe).dS_dE), 100 * d) << d;
    const Mat3 Ge = R * diag(0.7, 0.7, 0.7), Gn = R * diag(0.7 + d, 0.7, 0.7 - d);
    EXPECT_LT(rel_diff(model.evaluate(Gn).dS_dE, model.evaluate(Ge).dS_dE), 100 * d) << d;
  }
}

TEST(Hyperfoam, StressIsEnergyDerivative) {
  // S = 2 dW/dC = dW/dE by central differences of W (h = 1e-6): tolerance 1e-7 relative.
  for (double nu : {0.0, 0.25}) {
    const Hyperfoam model(terms_with_nu(nu));
    std::mt19937 rng(3);
    for (int k = 0; k < 5; ++k) {
      const Mat3 F = test::random_F(rng);
      const Vec6 g = test::fd_dW_dE([&](const Mat3& G) { return model.evaluate(G).W; }, F);
      EXPECT_LT(rel_diff(g, model.evaluate(F).S), 1e-7);
    }
  }
}

TEST(Hyperfoam, ZeroBetaIsTheLimitOfTheEnergy) {
  // (1/beta)(J^(-alpha beta) - 1) -> -alpha ln J: nu = 1e-13 and nu = 0 agree to 1e-11 relative.
  std::mt19937 rng(4);
  const Mat3 F = test::random_F(rng);
  const double W0 = Hyperfoam(terms_with_nu(0.0)).evaluate(F).W;
  const double W1 = Hyperfoam(terms_with_nu(1e-13)).evaluate(F).W;
  EXPECT_NEAR(W1, W0, 1e-11 * std::abs(W0));
  EXPECT_EQ(Hyperfoam(terms_with_nu(0.0)).evaluate(Mat3::Identity()).W, 0.0);
}

TEST(Hyperfoam, ObjectiveStressAndPrincipalKirchhoff) {
  // S(QF) = S(F) to 1e-12 relative; tau = F S F^T matches principal_kirchhoff to 1e-12 relative.
  const Hyperfoam model(terms_with_nu(0.2));
  std::mt19937 rng(21);
  for (int k = 0; k < 4; ++k) {
    const Mat3 F = test::random_F(rng);
    const Vec6 S = model.evaluate(F).S;
    for (int q = 0; q < 3; ++q)
      EXPECT_LT(rel_diff(model.evaluate(test::random_rotation(rng) * F).S, S), 1e-12);
  }
  const Vec3 l(0.5, 1.4, 0.9);
  const Mat3 tau = diag(l(0), l(1), l(2)) * from_voigt_stress(model.evaluate(diag(l(0), l(1), l(2))).S) *
                   diag(l(0), l(1), l(2));
  EXPECT_LT(rel_diff(tau.diagonal(), model.principal_kirchhoff(l)), 1e-12);
}

/// S_11 at F = diag(l) from principal_kirchhoff (not remembered): tau_1 / l_1^2.
double principal_S11(const Hyperfoam& model, const Vec3& l) { return model.principal_kirchhoff(l)(0) / (l(0) * l(0)); }

TEST(Hyperfoam, EvaluationMemoNeverAnswersForAnotherInstance) {
  // evaluate remembers its last result per thread by instance and exact F. Instances made and destroyed in turn (so
  // often at the same address) with other moduli, each evaluated at the same F, give their own S_11 (1e-12 relative
  // against principal_kirchhoff, which does not remember); so do two threads alternating two instances at one F.
  const Vec3 l(0.6, 1.0, 1.0);
  const Mat3 F = diag(l(0), l(1), l(2));
  for (int k = 1; k <= 20; ++k) {
    const auto model = std::make_unique<Hyperfoam>(std::vector<HyperfoamTerm>{{1e-3 * k, 8.0, 0.0}});
    EXPECT_NEAR(model->evaluate(F).S(0), principal_S11(*model, l), 1e-12 * std::abs(principal_S11(*model, l)));
    EXPECT_EQ(model->evaluate(F).S, model->evaluate(F).S);  // the remembered result is the same
  }
  const Hyperfoam soft({{1e-3, 8.0, 0.0}}), stiff({{5e-3, -2.0, 0.1}});
  auto alternate = [&](bool& ok) {
    for (int k = 0; k < 2000; ++k) {
      const Hyperfoam& m = k % 2 ? soft : stiff;
      ok = ok && std::abs(m.evaluate(F).S(0) - principal_S11(m, l)) <= 1e-12 * std::abs(principal_S11(m, l));
    }
  };
  bool ok_first = true, ok_second = true;
  std::thread second(alternate, std::ref(ok_second));
  alternate(ok_first);
  second.join();
  EXPECT_TRUE(ok_first && ok_second);
}

TEST(Hyperfoam, AlignedFrameMatchesRotatedFrame) {
  // A diagonal F takes the aligned path (no eigen-solve, Voigt entries set directly); F R (C = R^T C0 R) takes the
  // general one. For distinct, two equal and three equal stretches: S(F R) = R^T S(F) R and, for a random dE,
  // dS(F R)[R^T dE R] = R^T dS(F)[dE] R, both to 1e-11 relative.
  const Hyperfoam model(terms_with_nu(0.2));
  std::mt19937 rng(33);
  for (const Vec3& l : {Vec3(0.5, 1.4, 0.9), Vec3(0.6, 1.1, 1.1), Vec3(0.8, 0.8, 0.8)}) {
    const Mat3 F = diag(l(0), l(1), l(2));
    const Mat3 R = test::random_rotation(rng);
    const ElasticEval aligned = model.evaluate(F), rotated = model.evaluate(F * R);
    EXPECT_LT(rel_diff(to_voigt_stress(R.transpose() * from_voigt_stress(aligned.S) * R), rotated.S), 1e-11);
    const Mat3 A = test::random_F(rng);
    const Mat3 dE = 0.5 * (A + A.transpose());
    const Mat3 dS = from_voigt_stress(aligned.dS_dE * to_voigt_strain(dE));
    const Mat3 dS_rotated = from_voigt_stress(rotated.dS_dE * to_voigt_strain(R.transpose() * dE * R));
    EXPECT_LT(rel_diff(to_voigt_stress(R.transpose() * dS * R), to_voigt_stress(dS_rotated)), 1e-11) << l.transpose();
  }
}

TEST(Hyperfoam, FailuresAndValidation) {
  const Hyperfoam model(terms_with_nu(0.2));
  const ElasticEval inverted = model.evaluate(diag(1.0, -0.5, 1.0));
  EXPECT_EQ(inverted.status, Status::failed);
  EXPECT_FALSE(inverted.message.empty());
  EXPECT_EQ(model.evaluate(diag(1e-320, 1.0, 1.0)).status, Status::failed);
  const ElasticEval overflow = Hyperfoam({{0.01, 60.0, 0.0}}).evaluate(diag(1e8, 1.0, 1.0));
  EXPECT_EQ(overflow.status, Status::failed);
  EXPECT_THROW(Hyperfoam({}), std::invalid_argument);
  EXPECT_THROW(Hyperfoam({{0.01, 0.0, 0.1}}), std::invalid_argument);
  EXPECT_THROW(Hyperfoam({{0.01, 2.0, 0.5}}), std::invalid_argument);
  EXPECT_THROW(Hyperfoam(std::vector<HyperfoamTerm>(7, {0.01, 2.0, 0.0})), std::invalid_argument);
  EXPECT_NEAR(model.scaled(0.5)->initial_shear_modulus(), 0.5 * model.initial_shear_modulus(), 1e-16);
}

}  // namespace
}  // namespace cushion::material
