// parallel_jobs.hpp: the forward-difference Jacobian of diagnose's candidate fits (its columns on two threads while
// a core is lent) and the job runner that lends the cores of threads with no job left.
//  - the Jacobian equals Ceres' own FORWARD numeric differentiation (DynamicNumericDiffCostFunction, relative step
//    1e-5) bit for bit, with and without a lent core: a fit follows the same path as before, on one thread or two;
//  - it is the analytic Jacobian within the forward-difference error (relative step 1e-5: 1e-4 of the largest entry);
//  - the central-difference Jacobian equals Ceres' CENTRAL one (DynamicNumericDiffCostFunction's default) bit for bit,
//    on one thread or two, and fails where either point fails;
//  - with a cheaper model given for the Jacobian (diagnose: fewer time steps a sine cycle), the columns are Ceres'
//    FORWARD differences of that model bit for bit, the residuals those of the model itself, and a Levenberg-Marquardt
//    fit still ends at the model's own least-squares minimum (the Jacobian only sets the search direction);
//  - parallel_for calls each index once; run_all returns results in job order and lends nothing once it returns.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <vector>

#include <ceres/dynamic_numeric_diff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "calibration/parallel_jobs.hpp"

namespace cc = cushion::calibration;

namespace {

constexpr int kParameters = 5, kResiduals = 7;

/// r_i = sin((i + 1) u_0 u_1) + exp(0.1 i u_2) + u_3^3 / (1 + i) + (i - 3) u_4 and its analytic Jacobian.
bool model(const double* u, double* r) {
  for (int i = 0; i < kResiduals; ++i)
    r[i] = std::sin((i + 1) * u[0] * u[1]) + std::exp(0.1 * i * u[2]) + std::pow(u[3], 3) / (1 + i) + (i - 3) * u[4];
  return true;
}

double analytic(const double* u, int i, int j) {
  const double c = std::cos((i + 1) * u[0] * u[1]) * (i + 1);
  switch (j) {
    case 0: return c * u[1];
    case 1: return c * u[0];
    case 2: return 0.1 * i * std::exp(0.1 * i * u[2]);
    case 3: return 3.0 * u[3] * u[3] / (1 + i);
    default: return i - 3.0;
  }
}

/// `model` with a smooth error of a few percent, as a coarser time step would make it: the "cheaper model".
bool cheaper_model(const double* u, double* r) {
  model(u, r);
  for (int i = 0; i < kResiduals; ++i) r[i] *= 1.0 + 0.03 * std::sin(u[0] + 0.2 * i);
  return true;
}

template <bool (*f)(const double*, double*)>
struct FunctorOf {
  bool operator()(double const* const* p, double* r) const { return f(p[0], r); }
};
using Functor = FunctorOf<model>;

std::vector<double> jacobian_of(const ceres::CostFunction& cost, const std::vector<double>& u) {
  std::vector<double> r(kResiduals), J(kResiduals * kParameters);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  EXPECT_TRUE(cost.Evaluate(p, r.data(), j));
  return J;
}

/// Ceres' own numeric Jacobian of `model` at u (DynamicNumericDiffCostFunction with `method` and this relative step).
template <ceres::NumericDiffMethodType method, class F = Functor>
std::vector<double> ceres_jacobian(double relative_step, const std::vector<double>& u) {
  ceres::NumericDiffOptions nd;
  nd.relative_step_size = relative_step;
  ceres::DynamicNumericDiffCostFunction<F, method> reference(new F, ceres::TAKE_OWNERSHIP, nd);
  reference.AddParameterBlock(kParameters);
  reference.SetNumResiduals(kResiduals);
  return jacobian_of(reference, u);
}

/// The Jacobian of the cost made by make(spare) equals `expected` bit for bit, without a spare core and with one lent,
/// and the lent core is given back afterwards.
template <class Make>
void expect_bit_for_bit_on_one_thread_or_two(const Make& make, const std::vector<double>& u,
                                             const std::vector<double>& expected) {
  EXPECT_EQ(jacobian_of(make(nullptr), u), expected);
  cc::SpareCores spare;
  spare.lend();
  EXPECT_EQ(jacobian_of(make(&spare), u), expected);
  EXPECT_TRUE(spare.borrow()) << "the core is given back after the Jacobian";
}

/// Every entry of J within tolerance x the largest analytic entry of the analytic Jacobian at u.
void expect_near_analytic(const std::vector<double>& J, const std::vector<double>& u, double tolerance) {
  double largest = 0.0;
  for (int i = 0; i < kResiduals; ++i)
    for (int j = 0; j < kParameters; ++j) largest = std::max(largest, std::abs(analytic(u.data(), i, j)));
  for (int i = 0; i < kResiduals; ++i)
    for (int j = 0; j < kParameters; ++j)
      EXPECT_NEAR(J[i * kParameters + j], analytic(u.data(), i, j), tolerance * largest) << i << ", " << j;
}

}  // namespace

TEST(ForwardDifferenceCost, EqualsCeresForwardNumericDiffBitForBitOnOneThreadOrTwo) {
  const std::vector<double> u = {0.7, -1.3, 0.0, 2.5, -0.2};  // u_2 = 0: the minimum step sqrt(eps)
  const std::vector<double> expected = ceres_jacobian<ceres::FORWARD>(1e-5, u);

  expect_bit_for_bit_on_one_thread_or_two(
      [](cc::SpareCores* spare) { return cc::ForwardDifferenceCost(model, kParameters, kResiduals, 1e-5, spare); }, u,
      expected);
  expect_near_analytic(expected, u, 1e-4);
}

TEST(ForwardDifferenceCost, ACheaperModelGivesTheColumnsAndTheModelItselfTheResiduals) {
  const std::vector<double> u = {0.7, -1.3, 0.0, 2.5, -0.2};
  const std::vector<double> expected = ceres_jacobian<ceres::FORWARD, FunctorOf<cheaper_model>>(1e-5, u);
  auto make = [](cc::SpareCores* spare) {
    return cc::ForwardDifferenceCost(model, kParameters, kResiduals, 1e-5, spare, {}, cheaper_model);
  };
  expect_bit_for_bit_on_one_thread_or_two(make, u, expected);
  EXPECT_NE(expected, ceres_jacobian<ceres::FORWARD>(1e-5, u)) << "the cheaper model's Jacobian is not the model's";
  std::vector<double> r(kResiduals), r_model(kResiduals), J(kResiduals * kParameters);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  ASSERT_TRUE(make(nullptr).Evaluate(p, r.data(), j));
  model(u.data(), r_model.data());
  EXPECT_EQ(r, r_model) << "the residuals are the model's";
}

TEST(ForwardDifferenceCost, AFitWithACheaperModelsJacobianEndsNextToTheModelsMinimum) {
  // r_i = a exp(-b t_i) + c - y_i on 12 samples of y = 2 exp(-0.7 t) + 0.3 + a wiggle (no exact fit); the cheaper model
  // has b 3 % high (its own minimum: b 3 % lower). Levenberg-Marquardt from (1, 1, 0), with the model's own Jacobian and
  // with the cheaper one's. With a residual left at the minimum, Gauss-Newton steps with an approximate Jacobian J_g
  // stop where J_g^T r = 0, not J^T r = 0: off the minimum by (J^T J)^-1 (J_g - J)^T r, first order in the Jacobian's
  // error times the residual, the cost above it by the second order (docs/physics.md 9.36). Here: each parameter within
  // 2e-3 of the model's minimum (measured 1.4e-4 to 1.2e-3) and the cost within 1 % of the minimum's (the cheaper
  // model's own minimum is 3 % away in b).
  constexpr int n = 12;
  auto curve = [](double b_factor) {
    return [b_factor](const double* u, double* r) {
      for (int i = 0; i < n; ++i) {
        const double t = 0.25 * i, y = 2.0 * std::exp(-0.7 * t) + 0.3 + 0.01 * std::sin(3.0 * t);
        r[i] = u[0] * std::exp(-b_factor * u[1] * t) + u[2] - y;
      }
      return true;
    };
  };
  auto cost_at = [&](const std::vector<double>& u) {
    std::vector<double> r(n);
    curve(1.0)(u.data(), r.data());
    double c = 0.0;
    for (double x : r) c += 0.5 * x * x;
    return c;
  };
  auto fit = [&](cc::DifferenceCost::Residuals jacobian_model) {
    std::vector<double> u = {1.0, 1.0, 0.0};
    ceres::Problem problem;
    problem.AddResidualBlock(new cc::ForwardDifferenceCost(curve(1.0), 3, n, 1e-5, nullptr, {}, jacobian_model),
                             nullptr, u.data());
    ceres::Solver::Options o;
    o.max_num_iterations = 200;
    o.function_tolerance = o.gradient_tolerance = o.parameter_tolerance = 1e-14;
    ceres::Solver::Summary summary;
    ceres::Solve(o, &problem, &summary);
    EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
    return u;
  };
  const std::vector<double> exact = fit({}), approximate = fit(curve(1.03));
  EXPECT_NEAR(exact[1], 0.7, 0.05) << "the fit found the curve";
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(approximate[k], exact[k], 2e-3 * std::abs(exact[k])) << k;
  EXPECT_GE(cost_at(approximate), cost_at(exact));
  EXPECT_LT(cost_at(approximate), 1.01 * cost_at(exact)) << cost_at(approximate) / cost_at(exact);
}

TEST(CentralDifferenceCost, EqualsCeresCentralNumericDiffBitForBitOnOneThreadOrTwo) {
  const std::vector<double> u = {0.7, -1.3, 0.0, 2.5, -0.2};  // u_2 = 0: the minimum step sqrt(eps)
  // DynamicNumericDiffCostFunction's default method, which the base fit's Prony-time polish used
  const std::vector<double> expected = ceres_jacobian<ceres::CENTRAL>(1e-6, u);

  expect_bit_for_bit_on_one_thread_or_two(
      [](cc::SpareCores* spare) { return cc::CentralDifferenceCost(model, kParameters, kResiduals, 1e-6, spare); }, u,
      expected);
  expect_near_analytic(expected, u, 1e-7);  // O(step^2) (the forward difference of this step: about 1e-6)
}

TEST(CentralDifferenceCost, AFailingRunOnEitherSideFailsTheJacobian) {
  auto fails_above = [](const double* u, double* r) {
    for (int i = 0; i < kResiduals; ++i) r[i] = u[0];
    return u[0] <= 0.5;
  };
  const cc::CentralDifferenceCost cost(fails_above, 1, kResiduals, 1e-6, nullptr);
  const std::vector<double> u = {0.5};
  std::vector<double> r(kResiduals), J(kResiduals);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  EXPECT_TRUE(cost.Evaluate(p, r.data(), nullptr));
  EXPECT_FALSE(cost.Evaluate(p, r.data(), j)) << "the forward point u + step fails";
}

TEST(ForwardDifferenceCost, AFailingRunOnBothSidesFailsTheEvaluation) {
  auto fails_off_start = [](const double* u, double* r) {
    for (int i = 0; i < kResiduals; ++i) r[i] = u[0];
    return u[1] == 1.0;  // any step in u_1, forward or backward, fails
  };
  cc::SpareCores spare;
  spare.lend();
  const cc::ForwardDifferenceCost cost(fails_off_start, 2, kResiduals, 1e-5, &spare);
  const std::vector<double> u = {0.5, 1.0};
  std::vector<double> r(kResiduals), J(kResiduals * 2);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  EXPECT_TRUE(cost.Evaluate(p, r.data(), nullptr));
  EXPECT_FALSE(cost.Evaluate(p, r.data(), j));
}

TEST(ForwardDifferenceCost, AFailingForwardStepTakesTheBackwardDifference) {
  // r_i = (i + 1) u_0^2 + u_1, failing for u_0 > 0.5: at u_0 = 0.5 the column of u_0 is the backward difference
  // (i + 1)(2 u_0 - h) with h = 1e-5 x 0.5, exactly as written (1e-9 relative); the column of u_1 stays the forward one.
  auto fails_above = [](const double* u, double* r) {
    for (int i = 0; i < kResiduals; ++i) r[i] = (i + 1) * u[0] * u[0] + u[1];
    return u[0] <= 0.5;
  };
  const cc::ForwardDifferenceCost cost(fails_above, 2, kResiduals, 1e-5, nullptr);
  const std::vector<double> u = {0.5, 2.0};
  std::vector<double> r(kResiduals), J(kResiduals * 2);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  ASSERT_TRUE(cost.Evaluate(p, r.data(), j));
  const double h = 1e-5 * 0.5;
  for (int i = 0; i < kResiduals; ++i) {
    EXPECT_NEAR(J[i * 2], (i + 1) * (2 * 0.5 - h), 1e-9 * (i + 1)) << i;
    EXPECT_NEAR(J[i * 2 + 1], 1.0, 1e-9) << i;
  }
}

TEST(ForwardDifferenceCost, AParameterAtItsUpperBoundTakesTheBackwardDifference) {
  // A model that clamps u_0 to its upper bound 1 (as diagnose's does): r_i = (i + 1) min(u_0, 1)^2 + u_1 (r > 0: the cost
  // falls inward). At u_0 = 1 the forward column would be 0; with the bound given it is the backward difference
  // (i + 1)(2 - h), h = 1e-5 (1e-9 relative), and the column of u_1 (bound 10, far) stays the forward one. Without
  // bounds: the zero column, as before.
  auto clamped = [](const double* u, double* r) {
    const double u0 = std::min(u[0], 1.0);
    for (int i = 0; i < kResiduals; ++i) r[i] = (i + 1) * u0 * u0 + u[1];
    return true;
  };
  const std::vector<double> u = {1.0, 2.0};
  std::vector<double> r(kResiduals), J(kResiduals * 2);
  const double* p[] = {u.data()};
  double* j[] = {J.data()};
  const cc::ForwardDifferenceCost bounded(clamped, 2, kResiduals, 1e-5, nullptr, {1.0, 10.0});
  ASSERT_TRUE(bounded.Evaluate(p, r.data(), j));
  const double h = 1e-5;
  for (int i = 0; i < kResiduals; ++i) {
    EXPECT_NEAR(J[i * 2], (i + 1) * (2.0 - h), 1e-9 * (i + 1)) << i;
    EXPECT_NEAR(J[i * 2 + 1], 1.0, 1e-9) << i;
  }
  const cc::ForwardDifferenceCost unbounded(clamped, 2, kResiduals, 1e-5, nullptr);
  ASSERT_TRUE(unbounded.Evaluate(p, r.data(), j));
  for (int i = 0; i < kResiduals; ++i) EXPECT_EQ(J[i * 2], 0.0) << i;
  // r_i = (i + 1) min(u_0, 1)^2 - 100: the cost falls as u_0 grows, i.e. outward: the bound is active, the column zero
  auto pulled_out = [](const double* u, double* r) {
    const double u0 = std::min(u[0], 1.0);
    for (int i = 0; i < kResiduals; ++i) r[i] = (i + 1) * u0 * u0 - 100.0 + u[1];
    return true;
  };
  const cc::ForwardDifferenceCost active(pulled_out, 2, kResiduals, 1e-5, nullptr, {1.0, 10.0});
  ASSERT_TRUE(active.Evaluate(p, r.data(), j));
  for (int i = 0; i < kResiduals; ++i) {
    EXPECT_EQ(J[i * 2], 0.0) << i;
    EXPECT_NEAR(J[i * 2 + 1], 1.0, 1e-9) << i;
  }
  EXPECT_THROW(cc::ForwardDifferenceCost(clamped, 2, kResiduals, 1e-5, nullptr, {1.0}), std::invalid_argument);
}

TEST(ParallelJobs, ParallelForCallsEachIndexOnceAndRunAllKeepsJobOrder) {
  cc::SpareCores spare;
  spare.lend();
  std::vector<std::atomic<int>> calls(100);
  cc::parallel_for(calls.size(), &spare, [&](std::size_t i) { ++calls[i]; });
  for (const auto& c : calls) EXPECT_EQ(c.load(), 1);

  std::vector<std::function<int()>> jobs;
  for (int k = 0; k < 9; ++k) jobs.push_back([k] { return k * k; });
  const std::vector<double> cost = {1, 9, 2, 8, 3, 7, 4, 6, 5};  // started longest first, returned in job order
  cc::SpareCores stage;
  const std::vector<int> out = cc::run_all(jobs, 2, cost, &stage);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(out[k], k * k);
  EXPECT_FALSE(stage.borrow()) << "no core stays lent once the stage has ended";
}
