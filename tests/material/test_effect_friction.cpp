// Requirement: the friction branch is rate-independent hysteresis: its 1D loop area equals the
// closed form 4 s_y (k e_a - s_y)/(k + h) of an elasto-plastic loop, is identical for a slow and a
// 10x faster cycle (also on top of a rate-dependent Prony model), and its increment tangent is exact.
#include <gtest/gtest.h>

#include "material/effect_friction.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

/// F with Green-Lagrange strain E11 = e and no other component (laterally confined).
Mat3 F_of_E11(double e) { return Vec3(std::sqrt(1.0 + 2.0 * e), 1.0, 1.0).asDiagonal(); }

/// Trapezoidal area of S11 over E11 for the cycle E11 = n dE, n: N -> -N -> N after a first loading
/// 0 -> N (loading and unloading share the same E samples, so an elastic part cancels exactly).
/// period: duration of the closed cycle [s].
double loop_area(const Material& m, double dE, int N, double period) {
  std::vector<int> path;
  for (int n = 0; n <= N; ++n) path.push_back(n);
  const std::size_t cycle_start = path.size() - 1;
  for (int n = N - 1; n >= -N; --n) path.push_back(n);
  for (int n = -N + 1; n <= N; ++n) path.push_back(n);
  const double dt = period / (4.0 * N);
  std::vector<double> state(m.state_size()), next(m.state_size()), S11{0.0};
  m.initial_state(state);
  for (std::size_t k = 1; k < path.size(); ++k) {
    const PointResponse r = m.integrate(F_of_E11(path[k - 1] * dE), F_of_E11(path[k] * dE), dt, state, next);
    EXPECT_EQ(r.status, Status::ok) << r.message;
    S11.push_back(r.S(0));
    state.swap(next);
  }
  double area = 0.0;
  for (std::size_t k = cycle_start + 1; k < path.size(); ++k)
    area += 0.5 * (S11[k] + S11[k - 1]) * (path[k] - path[k - 1]) * dE;
  return area;
}

TEST(EffectFriction, OneDimensionalLoopAreaIsTheClosedForm) {
  // k = 10 kPa, s_y = 0.01 kPa (e_y = 1e-3), amplitude e_a = 5 e_y, steps e_y/10 so the yield points
  // are samples (trapezoid exact); h = 0 and h = 5 kPa. Tolerance 1e-10 relative.
  for (double h : {0.0, 0.005}) {
    const double k = 0.01, s_y = 1e-5, e_a = 5e-3;
    const FrictionEffect m(test::effect_test_foam(), {k, s_y, h});
    const double closed_form = 4.0 * s_y * (k * e_a - s_y) / (k + h);
    EXPECT_NEAR(loop_area(m, 1e-4, 50, 1.0), closed_form, 1e-10 * closed_form) << "h = " << h;
  }
}

TEST(EffectFriction, LossPerCycleIsRateIndependent) {
  // Friction over the Table 3 Prony model: the visco loop changes with the rate (checked), the loss
  // added by the friction branch does not; periods 10 s and 1 s, tolerance 1e-10 relative; it also
  // equals the 1D closed form.
  const double k = 0.01, s_y = 1e-5, e_a = 5e-3;
  const auto visco = test::effect_test_visco();
  const FrictionEffect m(visco, {k, s_y, 0.0});
  const double slow = loop_area(m, 1e-4, 50, 10.0) - loop_area(*visco, 1e-4, 50, 10.0);
  const double fast = loop_area(m, 1e-4, 50, 1.0) - loop_area(*visco, 1e-4, 50, 1.0);
  const double closed_form = 4.0 * s_y * (e_a - s_y / k);
  EXPECT_NEAR(fast, slow, 1e-10 * slow);
  EXPECT_NEAR(slow, closed_form, 1e-10 * closed_form);
  const double visco_slow = loop_area(*visco, 1e-4, 50, 10.0), visco_fast = loop_area(*visco, 1e-4, 50, 1.0);
  EXPECT_GT(std::abs(visco_fast / visco_slow - 1.0), 0.05);  // the comparison is not trivial
}

TEST(EffectFriction, TangentMatchesFiniteDifferences) {
  // Random F and random plastic strain E_p (sliding increments), with and without hardening, and an
  // elastic increment (large s_y); over hyperfoam. Tolerance 1e-6 relative.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (const FrictionParameters& p : {FrictionParameters{0.01, 2e-4, 0.0}, FrictionParameters{0.01, 2e-4, 0.004},
                                      FrictionParameters{0.01, 10.0, 0.0}}) {
    const FrictionEffect m(test::effect_test_foam(), p);
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<double> state(6);
      for (double& x : state) x = u(rng);
      const Mat3 F = test::random_F(rng, 0.3);
      EXPECT_LT(test::increment_tangent_error(m, Mat3::Identity(), F, 0.1, state), 1e-6)
          << "s_y = " << p.yield_stress << ", h = " << p.hardening << ", trial " << trial;
    }
  }
}

TEST(EffectFriction, ReturnedStressLiesOnTheYieldSurface) {
  // After a sliding increment |S_f - h E_p| = s_y (radial return), tolerance 1e-12 relative.
  const FrictionParameters p{0.01, 2e-4, 0.003};
  const FrictionEffect m(test::effect_test_foam(), p);
  std::mt19937 rng(3);
  const Mat3 F = test::random_F(rng, 0.3);
  std::vector<double> state(6, 0.0), next(6);
  const PointResponse r = m.integrate(Mat3::Identity(), F, 0.0, state, next);
  const Vec6 Ep = Eigen::Map<const Vec6>(next.data());
  const Vec6 S_f = r.S - m.inner().integrate(Mat3::Identity(), F, 0.0, {}, {}).S;
  EXPECT_NEAR(tensor_norm(S_f - p.hardening * Ep), p.yield_stress, 1e-12 * p.yield_stress);
  EXPECT_GT(tensor_norm(Ep), 0.0);
}

TEST(EffectFriction, ComplexTangentIsTheElasticBranchTangent) {
  // Inside the elastic range the increment tangent equals complex_tangent (inner + k I); 1e-12 relative.
  const FrictionEffect m(test::effect_test_foam(), {0.01, 2e-4, 0.0});
  const Mat3 F = F_of_E11(1e-2);
  std::vector<double> state(6), next(6);
  m.initial_state(state);
  state[0] = 1e-2;  // E_p = E: the branch is unloaded at F
  const PointResponse r = m.integrate(F, F, 0.0, state, next);
  EXPECT_LT(test::rel_diff(r.dS_dE, m.complex_tangent(F, 30.0).real().eval()), 1e-12);
  EXPECT_EQ(m.complex_tangent(F, 30.0).imag(), Mat6::Zero());
}

}  // namespace
}  // namespace cushion::material
