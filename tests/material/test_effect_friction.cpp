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
  // Also with the stretch exponent n = 1 and n = -0.5 (k J^-2n, s_y J^-n), sliding and elastic.
  for (const FrictionParameters& p :
       {FrictionParameters{0.01, 2e-4, 0.0}, FrictionParameters{0.01, 2e-4, 0.004}, FrictionParameters{0.01, 10.0, 0.0},
        FrictionParameters{0.01, 2e-4, 0.0, 1.0}, FrictionParameters{0.01, 2e-4, 0.004, -0.5},
        FrictionParameters{0.01, 10.0, 0.0, 1.0}}) {
    const FrictionEffect m(test::effect_test_foam(), p);
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<double> state(6);
      for (double& x : state) x = u(rng);
      const Mat3 F = test::random_F(rng, 0.3);
      EXPECT_LT(test::increment_tangent_error(m, Mat3::Identity(), F, 0.1, state), 1e-6)
          << "s_y = " << p.yield_stress << ", h = " << p.hardening << ", n = " << p.stretch_exponent << ", trial "
          << trial;
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

/// The friction branch's nominal stress P_f = l S_f11 along a uniaxial compression l: 1 -> l_min -> l_back (F =
/// diag(l, 1, 1): J = l, the kinematics of a uniaxial test at nu = 0) in `steps` steps each way.
std::vector<std::pair<double, double>> nominal_friction_path(const FrictionEffect& m, double l_min, double l_back,
                                                             int steps) {
  std::vector<double> l_path;
  for (int i = 0; i <= steps; ++i) l_path.push_back(1.0 + (l_min - 1.0) * i / steps);
  for (int i = 1; i <= steps; ++i) l_path.push_back(l_min + (l_back - l_min) * i / steps);
  std::vector<double> state(m.state_size()), next(m.state_size());
  m.initial_state(state);
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 1; i < l_path.size(); ++i) {
    const Mat3 F0 = Vec3(l_path[i - 1], 1.0, 1.0).asDiagonal(), F1 = Vec3(l_path[i], 1.0, 1.0).asDiagonal();
    const PointResponse r = m.integrate(F0, F1, 0.1, state, next);
    EXPECT_EQ(r.status, Status::ok) << r.message;
    const double S_f = r.S(0) - m.inner().integrate(F0, F1, 0.1, {}, {}).S(0);
    out.push_back({l_path[i], l_path[i] * S_f});
    state.swap(next);
  }
  return out;
}

TEST(EffectFriction, StretchExponentOneIsANominalJenkinsElementInUniaxialCompression) {
  // Closed form (effect_friction.hpp): with n = 1 the sliding branch's nominal stress is -s_y at every stretch of the
  // compression to l = 0.25 (tolerance 1e-12 relative), +s_y on the way back once it slides again, and the sticking
  // nominal stiffness just after the reversal is k (1 - (E - E_p)/l^2) = k + s_y/l (E - E_p = -s_y l/k there; k = 10
  // kPa, s_y = 0.05 kPa: 2 % above k at l = 0.25; one step of 1.2e-4 in l, tolerance 1e-3 relative). With
  // n = 0 the sliding nominal stress is -s_y l instead (it falls with the compression): the test can tell them apart.
  const double k = 0.01, s_y = 5e-5;
  const FrictionEffect nominal(test::effect_test_foam(), {k, s_y, 0.0, 1.0});
  const FrictionEffect green(test::effect_test_foam(), {k, s_y, 0.0, 0.0});
  const int steps = 3000;
  const auto p1 = nominal_friction_path(nominal, 0.25, 0.6, steps);
  const auto p0 = nominal_friction_path(green, 0.25, 0.6, steps);
  for (int i = steps / 10; i < steps; i += steps / 10) {
    EXPECT_NEAR(p1[i].second, -s_y, 1e-12 * s_y) << "l = " << p1[i].first;
    EXPECT_NEAR(p0[i].second, -s_y * p0[i].first, 1e-12 * s_y) << "l = " << p0[i].first;
  }
  EXPECT_NEAR(p1.back().second, s_y, 1e-12 * s_y);  // sliding again in extension, at l = 0.6
  // the first step back from l = 0.25 sticks: its stiffness in compression, d(-P_f)/de = dP_f/dl (e = 1 - l)
  const double dl = p1[steps].first - p1[steps - 1].first;
  const double stiffness = (p1[steps].second - p1[steps - 1].second) / dl;
  EXPECT_NEAR(stiffness, k + s_y / 0.25, 1e-3 * k);
  EXPECT_LT(std::abs(p1[steps].second), s_y);
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
  // with n = 1, k(J) = k J^-2 at the base state; the branch unloaded at F (E = E_p)
  const FrictionEffect stretched(test::effect_test_foam(), {0.01, 2e-4, 0.0, 1.0});
  const PointResponse s = stretched.integrate(F, F, 0.0, state, next);
  EXPECT_LT(test::rel_diff(s.dS_dE, stretched.complex_tangent(F, 30.0).real().eval()), 1e-12);
  EXPECT_GT(test::rel_diff(s.dS_dE, r.dS_dE), 1e-3);  // J^-2 differs from 1 at E11 = 1e-2
}

}  // namespace
}  // namespace cushion::material
