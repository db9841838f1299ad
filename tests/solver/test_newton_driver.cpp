// Requirement: the Newton driver's globalisation works on a problem where plain Newton fails.
// r(x) = atan(x - 1) [N], x in mm, root x = 1. From x0 = 3.5 the full Newton step overshoots
// (|x - 1| > 1.39 diverges): without line search the driver must report "diverged" (residual
// growing twice), with line search it must converge to the root within 1e-9 mm and apply at least
// one step < 1. A residual that is NaN away from the root is treated like a material failure.
// Modified Newton (tangent reuse) from x0 = 1.5 keeps the slope k0 = 1 / (1 + 0.5^2) = 0.8, so its
// error contracts by |1 - r'(1) / k0| = 0.25 per iteration: the observed residual ratio must tend to
// 0.25 (within 0.01) with one factorization.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/newton.hpp"
#include "tests/solver/counting_linear_solver.hpp"

namespace cushion::solver {
namespace {

class ArctanProblem final : public NonlinearProblem {
 public:
  explicit ArctanProblem(double nan_beyond = INFINITY) : nan_beyond_(nan_beyond), K_(1, 1) {
    K_.insert(0, 0) = 1.0;
    K_.makeCompressed();
  }
  std::size_t size() const override { return 1; }
  ProblemEvaluation evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool) override {
    const double y = x(0) - 1.0;
    r.resize(1);
    r(0) = std::abs(y) > nan_beyond_ ? NAN : std::atan(y);
    K_.coeffRef(0, 0) = 1.0 / (1.0 + y * y);
    ProblemEvaluation ev;
    ev.force_scale = 1.0;
    return ev;
  }
  const Eigen::SparseMatrix<double>& tangent() const override { return K_; }

 private:
  double nan_beyond_;
  Eigen::SparseMatrix<double> K_;
};

TEST(NewtonDriver, WithoutLineSearchOvershootIsReportedAsDiverged) {
  ArctanProblem problem;
  auto lu = make_linear_solver(LinearSolverKind::lu);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 3.5);
  NewtonOptions options;
  options.line_search = false;
  const NewtonResult result = solve_newton(problem, *lu, x, options);
  EXPECT_EQ(result.outcome, NewtonOutcome::diverged);
  EXPECT_FALSE(result.converged());
  EXPECT_NE(result.message.find("grew"), std::string::npos) << result.message;
}

TEST(NewtonDriver, LineSearchRecoversConvergence) {
  ArctanProblem problem;
  auto lu = make_linear_solver(LinearSolverKind::lu);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 3.5);
  NewtonOptions options;
  options.residual_tolerance = 1e-12;
  const NewtonResult result = solve_newton(problem, *lu, x, options);
  ASSERT_TRUE(result.converged()) << result.message;
  EXPECT_NEAR(x(0), 1.0, 1e-9);
  double smallest_step = 1.0;
  for (const auto& it : result.history)
    if (it.iteration > 0) smallest_step = std::min(smallest_step, it.line_search);
  EXPECT_LT(smallest_step, 1.0);
}

TEST(NewtonDriver, NanResidualIsBacktrackedLikeAFailure) {
  // The full step from 3.5 lands near x = -8: there r is NaN, so the step must be cut.
  ArctanProblem problem(4.0);
  auto lu = make_linear_solver(LinearSolverKind::lu);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 3.5);
  NewtonOptions options;
  options.residual_tolerance = 1e-12;
  const NewtonResult result = solve_newton(problem, *lu, x, options);
  ASSERT_TRUE(result.converged()) << result.message;
  EXPECT_NEAR(x(0), 1.0, 1e-9);
}

TEST(NewtonDriver, TangentReuseContractsAtTheAnalyticLinearRate) {
  ArctanProblem problem;
  test::CountingLinearSolver lu(LinearSolverKind::lu);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.5);
  NewtonOptions options;
  options.residual_tolerance = 1e-12;
  options.max_iterations = 40;
  options.tangent_reuse.enabled = true;
  TangentFactor factor;
  const NewtonResult result = solve_newton(problem, lu, x, options, {}, &factor);
  ASSERT_TRUE(result.converged()) << result.message;
  EXPECT_NEAR(x(0), 1.0, 1e-9);
  EXPECT_EQ(lu.factorizations, 1);
  EXPECT_TRUE(factor.current);
  const auto& h = result.history;
  ASSERT_GE(h.size(), 6u);
  const double rate = h[h.size() - 1].residual_max / h[h.size() - 2].residual_max;
  EXPECT_NEAR(rate, 0.25, 0.01);
  std::printf("modified Newton on atan: %d iterations, last residual ratio %.4f (analytic 0.25)\n",
              result.iterations, rate);

  // Full Newton from the same start: a factorization per correction, quadratic (fewer iterations).
  test::CountingLinearSolver lu_full(LinearSolverKind::lu);
  Eigen::VectorXd y = Eigen::VectorXd::Constant(1, 1.5);
  options.tangent_reuse.enabled = false;
  const NewtonResult full = solve_newton(problem, lu_full, y, options);
  ASSERT_TRUE(full.converged());
  EXPECT_EQ(lu_full.factorizations, full.iterations);
  EXPECT_LT(full.iterations, result.iterations);
}

}  // namespace
}  // namespace cushion::solver
