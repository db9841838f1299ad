#pragma once
/// Parallel candidate fits of diagnose (diagnose.hpp): jobs on a few threads, and a forward-difference Jacobian that
/// borrows the core of a thread that has run out of jobs.
///
/// Why: candidates are fitted one per thread; at the end of a stage the last long fit (an air-flow pair: about 3x the
/// model-run cost of the others) ran alone while the other core idled. A thread with no job left lends its core
/// (SpareCores) until the stage ends; a Jacobian evaluated while a core is lent computes its columns on two threads.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <utility>
#include <vector>

#include <ceres/cost_function.h>

namespace cushion::calibration {

/// Cores lent by threads that have run out of jobs, borrowed by Jacobian evaluations. Thread-safe.
class SpareCores {
 public:
  /// One core if one is free (then give it back), else false.
  bool borrow() {
    for (int n = free_.load(); n > 0;)
      if (free_.compare_exchange_weak(n, n - 1)) return true;
    return false;
  }
  void lend() { ++free_; }
  void reset() { free_ = 0; }

 private:
  std::atomic<int> free_{0};
};

/// Runs jobs on `threads` threads; results in job order. With expected costs (any unit, one per job) the jobs start
/// longest first, so that a long job does not start last on one thread while the others idle. With `spare`, a thread
/// that finds no job left lends its core until all jobs have ended (then none is lent).
template <class Result>
std::vector<Result> run_all(const std::vector<std::function<Result()>>& jobs, int threads,
                            const std::vector<double>& expected_cost = {}, SpareCores* spare = nullptr) {
  std::vector<std::size_t> order(jobs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (expected_cost.size() == jobs.size())
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return expected_cost[a] > expected_cost[b]; });
  std::vector<Result> out(jobs.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t k; (k = next++) < jobs.size();) out[order[k]] = jobs[order[k]]();
    if (spare) spare->lend();
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (spare) spare->reset();
  return out;
}

/// f(0), ..., f(n - 1), on two threads (each taking the next index) when `spare` lends a core, else in order. f must
/// be safe to call from two threads at once and must not throw.
void parallel_for(std::size_t n, SpareCores* spare, const std::function<void(std::size_t)>& f);

/// What the forward- and central-difference costs share: one parameter block, the residuals u -> r (false when the model
/// fails), Ceres' step rule max(sqrt(eps), relative_step |u_j|) (ceres/internal/numeric_diff.h), and the Jacobian's
/// columns on two threads while `spare` lends a core (parallel_for). `residuals` must be safe to call from two threads
/// at once.
class DifferenceCost : public ceres::CostFunction {
 public:
  using Residuals = std::function<bool(const double* u, double* r)>;

 protected:
  DifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step, SpareCores* spare);
  /// Writes column j of the row-major Jacobian J from u, r(u) and the column's step; false: the model failed.
  using Column = std::function<bool(int j, double step, const double* u, const double* r, double* J)>;
  /// r(u) into `residuals`, then, when Ceres asks for the Jacobian, every column.
  bool evaluate(double const* const* parameters, double* residuals, double** jacobians, const Column& column) const;

  Residuals residuals_;
  int parameters_, n_residuals_;
  double relative_step_;
  SpareCores* spare_;
};

/// A Ceres cost of one parameter block whose Jacobian is the forward difference of `residuals`, with Ceres' own rule
/// (FORWARD: the step of DifferenceCost, column (r(u + step e_j) - r(u)) / step), so that a fit follows the same path as
/// with DynamicNumericDiffCostFunction<F, ceres::FORWARD>. A column whose forward point fails takes the backward
/// difference (r(u) - r(u - step e_j)) / step; only when both fail does the Jacobian fail (a fit whose model fails just
/// beyond a point, e.g. a power-law air flow whose free-stretch Newton stops converging, then stops there with Ceres'
/// FAILURE).
/// upper_bounds (empty: none; else one per parameter): a column whose forward point lies beyond its parameter's upper
/// bound takes the backward difference, and keeps it only when the cost falls inward (the gradient sum_i r_i J_ij > 0);
/// where it falls outward the bound is active and the column is zero, as a model that clamps its parameters gives it.
/// Without the backward difference bounded Levenberg-Marquardt could never move a parameter back off (or start it from)
/// its upper bound (stiffness_damping derivative_order, started at 1: docs/physics.md 5.4b); with it kept where the
/// bound is active, Ceres' step for the other parameters is the projection of one that leaves the box, and Mullins fits
/// with r at its bound ended worse (docs/physics.md 9.13).
///
/// jacobian_residuals (empty: `residuals`): the function the columns difference, (g(u + step e_j) - g(u)) / step, where
/// g is a cheaper model of the same residuals (diagnose: the dynamic tests at fewer time steps a cycle), run at u beside
/// the columns. The cost and the points Levenberg-Marquardt accepts stay those of `residuals`; only the search direction
/// is approximate. Where a residual is left at the minimum, Gauss-Newton steps with g's Jacobian J_g stop where
/// J_g^T r = 0: off the minimum by (J^T J)^-1 (J_g - J)^T r, the cost above it by the second order (docs/physics.md 9.36).
class ForwardDifferenceCost final : public DifferenceCost {
 public:
  ForwardDifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step, SpareCores* spare,
                        std::vector<double> upper_bounds = {}, Residuals jacobian_residuals = {});
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  std::vector<double> upper_;
  Residuals jacobian_residuals_;
};

/// A Ceres cost of one parameter block whose Jacobian is the central difference of `residuals` (false when the model
/// fails at either point: then the Jacobian fails), with Ceres' own rule (CENTRAL, the method
/// DynamicNumericDiffCostFunction takes by default: the step of DifferenceCost, column
/// (r(u + step e_j) - r(u - step e_j)) (1/step)/2), bit for bit, so that a fit follows the same path as with it.
class CentralDifferenceCost final : public DifferenceCost {
 public:
  CentralDifferenceCost(Residuals residuals, int parameters, int n_residuals, double relative_step, SpareCores* spare)
      : DifferenceCost(std::move(residuals), parameters, n_residuals, relative_step, spare) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
};

}  // namespace cushion::calibration
