// Requirement: the ABAQUS/CalculiX compressible Ogden model (*HYPERELASTIC, OGDEN and NEO HOOKE) returns
// the PK2 stress of its energy in closed form and its exact tangent dS/dE, also at equal stretches.
#include <gtest/gtest.h>

#include <cmath>

#include "material/ogden.hpp"
#include "tests/material/fd.hpp"

namespace cushion::material {
namespace {

using test::fd_dS_dE;
using test::fd_dW_dE;
using test::rel_diff;

// Two terms of opposite alpha and two compressibility terms [MPa, -, 1/MPa].
const Ogden kModel({{0.4, 2.5}, {0.05, -1.5}}, {0.5, 2.0});

TEST(Ogden, NeoHookeClosedForm) {
  // alpha = 2, mu = 2 C10: W = C10 (I1bar - 3) + (J - 1)^2 / D1, so
  // S = 2 C10 J^(-2/3) (I - I1/3 C^-1) + 2 (J - 1)/D1 J C^-1 (closed form); 1e-12 relative.
  const double C10 = 1.92505, D1 = 0.026;
  const Ogden neo({{2.0 * C10, 2.0}}, {D1});
  std::mt19937 rng(11);
  for (int k = 0; k < 6; ++k) {
    const Mat3 F = test::random_F(rng);
    const Mat3 C = F.transpose() * F, Ci = C.inverse();
    const double J = F.determinant(), I1 = C.trace();
    const Mat3 S = 2.0 * C10 * std::pow(J, -2.0 / 3.0) * (Mat3::Identity() - I1 / 3.0 * Ci) + 2.0 * (J - 1.0) / D1 * J * Ci;
    const ElasticEval e = neo.evaluate(F);
    ASSERT_EQ(e.status, Status::ok);
    EXPECT_LT(rel_diff(e.S, to_voigt_stress(S)), 1e-12);
    EXPECT_NEAR(e.W, C10 * (std::pow(J, -2.0 / 3.0) * I1 - 3.0) + (J - 1.0) * (J - 1.0) / D1, 1e-12 * std::abs(e.W));
  }
}

TEST(Ogden, PrincipalStressClosedForm) {
  // F = diag(l1, l2, l3): Cauchy sigma_a = [sum 2 mu/alpha (lb_a^alpha - mean lb^alpha) + J U'(J)] / J; 1e-12.
  const Vec3 l(1.3, 0.8, 0.95);
  const double J = l.prod();
  const ElasticEval e = kModel.evaluate(l.asDiagonal());
  const double j = J - 1.0, dU = 2.0 * j / 0.5 + 4.0 * j * j * j / 2.0;
  for (int a = 0; a < 3; ++a) {
    double tau = J * dU;
    for (const OgdenTerm& t : kModel.terms()) {
      double mean = 0.0;
      for (int b = 0; b < 3; ++b) mean += std::pow(std::pow(J, -1.0 / 3.0) * l(b), t.alpha) / 3.0;
      tau += 2.0 * t.mu / t.alpha * (std::pow(std::pow(J, -1.0 / 3.0) * l(a), t.alpha) - mean);
    }
    EXPECT_NEAR(e.S(a) * l(a) * l(a) / J, tau / J, 1e-12 * std::abs(tau));
  }
}

TEST(Ogden, TangentMatchesFiniteDifferences) {
  // Central differences (h = 1e-6); random states plus equal and nearly equal stretches; 1e-6 relative.
  std::mt19937 rng(7);
  std::vector<Mat3> states{Mat3::Identity(), Vec3(1.2, 1.2, 0.9).asDiagonal(), Vec3(0.7, 0.7, 0.7).asDiagonal(),
                           test::F_with_stretches(Vec3(1.1, 1.1 + 1e-9, 0.8), rng)};
  for (int k = 0; k < 8; ++k) states.push_back(test::random_F(rng));
  const auto S_of = [](const Mat3& F) { return kModel.evaluate(F).S; };
  for (const Mat3& F : states) {
    const ElasticEval e = kModel.evaluate(F);
    ASSERT_EQ(e.status, Status::ok);
    EXPECT_LT(rel_diff(fd_dS_dE(S_of, F), e.dS_dE), 1e-6);
    if (e.S.norm() > 0.0)  // S = 0 at F = I
      EXPECT_LT(rel_diff(fd_dW_dE([](const Mat3& G) { return kModel.evaluate(G).W; }, F), e.S), 1e-7);
  }
}

TEST(Ogden, InitialModuliScalingAndBadParameters) {
  const Mat6 D = kModel.evaluate(Mat3::Identity()).dS_dE;
  EXPECT_NEAR(D(3, 3), kModel.initial_shear_modulus(), 1e-14);
  EXPECT_NEAR((D(0, 0) + 2.0 * D(0, 1)) / 3.0, kModel.initial_bulk_modulus(), 1e-13);
  const Mat3 F = Vec3(1.2, 0.9, 1.05).asDiagonal();
  EXPECT_LT(rel_diff(kModel.scaled(0.5)->evaluate(F).S, 0.5 * kModel.evaluate(F).S), 1e-14);
  EXPECT_EQ(kModel.evaluate(Vec3(1.0, 1.0, -0.5).asDiagonal()).status, Status::failed);
  EXPECT_THROW(Ogden({{1.0, 0.0}}, {0.1}), std::invalid_argument);
  EXPECT_THROW(Ogden({{1.0, 2.0}}, {0.0}), std::invalid_argument);
  EXPECT_THROW(Ogden({{-1.0, 2.0}}, {0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::material
