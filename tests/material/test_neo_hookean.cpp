// Requirement: the neo-Hookean reference model returns S = 2 dW/dC and its exact tangent dS/dE.
#include <gtest/gtest.h>

#include <cmath>

#include "material/neo_hookean.hpp"
#include "tests/material/fd.hpp"

namespace cushion::material {
namespace {

using test::fd_dS_dE;
using test::fd_dW_dE;
using test::rel_diff;

const NeoHookean kModel(0.05, 0.2);  // MPa

Vec6 S_of(const Mat3& F) { return kModel.evaluate(F).S; }

TEST(NeoHookean, TangentMatchesFiniteDifferences) {
  // Central differences with h = 1e-6: truncation ~1e-12, round-off ~1e-10; tolerance 1e-6 relative.
  std::mt19937 rng(7);
  std::vector<Mat3> states{Mat3::Identity()};
  for (int k = 0; k < 8; ++k) states.push_back(test::random_F(rng));
  for (const Mat3& F : states) {
    const ElasticEval e = kModel.evaluate(F);
    ASSERT_EQ(e.status, Status::ok);
    EXPECT_LT(rel_diff(fd_dS_dE(S_of, F), e.dS_dE), 1e-6);
    EXPECT_LT((e.dS_dE - e.dS_dE.transpose()).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(NeoHookean, StressIsEnergyDerivative) {
  std::mt19937 rng(8);
  for (int k = 0; k < 5; ++k) {
    const Mat3 F = test::random_F(rng);
    const Vec6 g = fd_dW_dE([](const Mat3& G) { return kModel.evaluate(G).W; }, F);
    EXPECT_LT(rel_diff(g, kModel.evaluate(F).S), 1e-7);  // tolerance 1e-7 relative
  }
}

TEST(NeoHookean, ConstrainedUniaxialClosedForm) {
  // F = diag(l, 1, 1): S11 = mu (1 - 1/l^2) + lambda ln(l) / l^2, S22 = S33 = lambda ln(l); 1e-13 relative.
  const double mu = 0.05, lambda = 0.2;
  for (double l : {0.3, 0.8, 1.2, 2.5}) {
    const Mat3 F = Vec3(l, 1.0, 1.0).asDiagonal();
    const Vec6 S = kModel.evaluate(F).S;
    const double S11 = mu * (1.0 - 1.0 / (l * l)) + lambda * std::log(l) / (l * l);
    EXPECT_NEAR(S(0), S11, 1e-13 * std::abs(S11));
    EXPECT_NEAR(S(1), lambda * std::log(l), 1e-13 * std::abs(lambda * std::log(l)));
    EXPECT_NEAR(S(3), 0.0, 1e-16);
  }
}

TEST(NeoHookean, InitialModuliAndObjectivity) {
  const Mat6 D = kModel.evaluate(Mat3::Identity()).dS_dE;
  EXPECT_NEAR(D(3, 3), kModel.initial_shear_modulus(), 1e-15);
  EXPECT_NEAR((D(0, 0) + 2.0 * D(0, 1)) / 3.0, kModel.initial_bulk_modulus(), 1e-15);
  std::mt19937 rng(9);
  const Mat3 F = test::random_F(rng);
  const Vec6 S = kModel.evaluate(F).S;
  for (int k = 0; k < 4; ++k)
    EXPECT_LT(rel_diff(kModel.evaluate(test::random_rotation(rng) * F).S, S), 1e-12);
}

TEST(NeoHookean, FailsOnInvertedElementAndScales) {
  const Mat3 F = Vec3(1.0, 1.0, -0.5).asDiagonal();
  EXPECT_EQ(kModel.evaluate(F).status, Status::failed);
  EXPECT_FALSE(kModel.evaluate(F).message.empty());
  std::vector<double> none;
  EXPECT_EQ(kModel.integrate(Mat3::Identity(), F, 0.1, none, none).status, Status::failed);
  EXPECT_NEAR(kModel.scaled(0.5)->initial_shear_modulus(), 0.025, 1e-16);
  EXPECT_THROW(NeoHookean(-1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::material
