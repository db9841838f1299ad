// early_stop.hpp: the early stop of diagnose's pair fits.
//  - a fit whose chi2 is still above the bound after k iterations stops there (USER_SUCCESS, k iterations made), at a
//    usable point no worse than its start;
//  - a fit that is below the bound by then, or with the stop inactive, runs as without the callback, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <ceres/ceres.h>

#include "calibration/early_stop.hpp"

namespace cc = cushion::calibration;

namespace {

/// y = a exp(-b t) + c against data of other parameters (a 2, b 0.7, c 0.3) with a deterministic scatter.
struct Decay {
  template <class T>
  bool operator()(const T* u, T* r) const {
    for (int i = 0; i < 20; ++i) {
      const double t = 0.25 * i;
      r[i] = u[0] * exp(-u[1] * t) + u[2] - (2.0 * std::exp(-0.7 * t) + 0.3 + 0.01 * std::sin(3.0 * i));
    }
    return true;
  }
};

struct FitEnd {
  std::vector<double> u;
  ceres::Solver::Summary summary;
};

FitEnd fit(const cc::EarlyStop& stop) {
  FitEnd end{{0.5, 3.0, 0.0}, {}};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Decay, 20, 3>(new Decay), nullptr, end.u.data());
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 50;
  so.logging_type = ceres::SILENT;
  cc::EarlyStopCallback callback(stop);
  if (stop.active()) so.callbacks.push_back(&callback);
  ceres::Solve(so, &problem, &end.summary);
  return end;
}

TEST(EarlyStop, AFitStillAboveTheBoundAfterKIterationsStopsThere) {
  const FitEnd free = fit({});
  ASSERT_GT(free.summary.iterations.size(), 5u);  // the fit needs more than 3 iterations
  const double final_chi2 = 2.0 * free.summary.final_cost;
  const FitEnd stopped = fit({3, 1.5 * final_chi2});
  EXPECT_EQ(stopped.summary.termination_type, ceres::USER_SUCCESS);
  EXPECT_EQ(stopped.summary.iterations.back().iteration, 3);
  EXPECT_TRUE(stopped.summary.IsSolutionUsable());
  EXPECT_LE(stopped.summary.final_cost, stopped.summary.initial_cost);
  EXPECT_GT(2.0 * stopped.summary.final_cost, 1.5 * final_chi2);  // it was above the bound when it stopped
}

TEST(EarlyStop, AFitBelowTheBoundOrWithTheStopInactiveRunsAsWithoutIt) {
  const FitEnd free = fit({});
  const FitEnd below = fit({3, 2.0 * free.summary.initial_cost});  // every point after the start is below it
  const FitEnd inactive = fit({0, 0.0});
  for (const FitEnd* f : {&below, &inactive}) {
    EXPECT_EQ(f->u, free.u);
    EXPECT_EQ(f->summary.final_cost, free.summary.final_cost);
    EXPECT_EQ(f->summary.termination_type, free.summary.termination_type);
    EXPECT_EQ(f->summary.iterations.size(), free.summary.iterations.size());
  }
}

}  // namespace
