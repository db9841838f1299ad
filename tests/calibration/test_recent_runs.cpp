// recent_runs.hpp: the memo of diagnose's model runs.
//  - a point is found only when every component is equal; a failed run is kept as failed; the oldest is forgotten
//    beyond the capacity;
//  - a bounded Levenberg-Marquardt fit (Ceres, the cost-only line search diagnose uses, ForwardDifferenceCost) whose
//    model runs go through the memo ends at the same parameters and cost bit for bit as without it, with fewer model
//    runs: Ceres asks for some points twice (an accepted step's point again with its Jacobian).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <vector>

#include <ceres/ceres.h>

#include "calibration/ceres_options.hpp"
#include "calibration/parallel_jobs.hpp"
#include "calibration/recent_runs.hpp"

namespace cc = cushion::calibration;

namespace {

TEST(RecentRuns, FindsOnlyAnEqualPointKeepsFailuresAndForgetsTheOldest) {
  cc::RecentRuns<double> memo(2);
  EXPECT_FALSE(memo.find({1.0, 2.0}).has_value());
  memo.keep({1.0, 2.0}, 3.0);
  memo.keep({1.0, 2.5}, std::nullopt);  // a failed run
  const auto hit = memo.find({1.0, 2.0});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(**hit, 3.0);
  EXPECT_FALSE(memo.find({1.0, std::nextafter(2.0, 3.0)}).has_value());
  const auto failed = memo.find({1.0, 2.5});
  ASSERT_TRUE(failed.has_value());
  EXPECT_FALSE(failed->has_value());
  memo.keep({4.0, 4.0}, 5.0);  // capacity 2: {1, 2} is forgotten
  EXPECT_FALSE(memo.find({1.0, 2.0}).has_value());
  EXPECT_TRUE(memo.find({4.0, 4.0}).has_value());
  EXPECT_EQ(memo.hits(), 3);
}

/// Residuals of a bounded exponential-decay fit (data from other parameters than the start), counting model runs.
struct DecayModel {
  int runs = 0;
  cc::RecentRuns<std::vector<double>>* memo = nullptr;
  std::vector<double> run(const double* u) {
    ++runs;
    std::vector<double> r;
    for (int i = 0; i < 20; ++i) {
      const double t = 0.25 * i;
      r.push_back(u[0] * std::exp(-u[1] * t) + u[2] - (2.0 * std::exp(-0.7 * t) + 0.3 + 0.01 * std::sin(3.0 * i)));
    }
    return r;
  }
  bool residuals(const double* u, double* out) {
    const std::vector<double> x(u, u + 3);
    std::optional<std::vector<double>> r;
    if (memo) {
      if (auto known = memo->find(x)) r = *known;
    }
    if (!r) {
      r = run(u);
      if (memo) memo->keep(x, r);
    }
    std::copy(r->begin(), r->end(), out);
    return true;
  }
};

struct FitEnd {
  std::vector<double> u;
  double cost;
  int runs;
};

FitEnd fit(bool with_memo) {
  cc::RecentRuns<std::vector<double>> memo;
  DecayModel m;
  if (with_memo) m.memo = &memo;
  std::vector<double> u{0.5, 1.1, 0.0};
  ceres::Problem problem;
  problem.AddResidualBlock(new cc::ForwardDifferenceCost([&m](const double* x, double* r) { return m.residuals(x, r); },
                                                         3, 20, 1e-5, nullptr, {10.0, 1.2, 1.0}),
                           nullptr, u.data());
  const std::vector<double> lower{0.0, 0.05, -1.0}, upper{10.0, 1.2, 1.0};
  for (int i = 0; i < 3; ++i) {
    problem.SetParameterLowerBound(u.data(), i, lower[static_cast<std::size_t>(i)]);
    problem.SetParameterUpperBound(u.data(), i, upper[static_cast<std::size_t>(i)]);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  cc::use_cost_only_line_search(so);
  so.max_num_iterations = 30;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  return {u, summary.final_cost, m.runs};
}

TEST(RecentRuns, ABoundedLevenbergMarquardtFitEndsBitForBitWhereItDidWithFewerModelRuns) {
  const FitEnd plain = fit(false), memo = fit(true);
  EXPECT_EQ(plain.u, memo.u);
  EXPECT_EQ(plain.cost, memo.cost);
  EXPECT_LT(memo.runs, plain.runs);
  EXPECT_NEAR(plain.u[1], 0.7, 0.05);  // the fit did move (from 1.1, near the bound 1.2, to the decay rate)
  std::cout << "model runs: " << plain.runs << " without the memo, " << memo.runs << " with it\n";
}

}  // namespace
