#pragma once
// Test helper: a LinearSolver that forwards to a real one and counts factorizations and solves.
#include "solver/linear_solver.hpp"

namespace cushion::solver::test {

class CountingLinearSolver final : public LinearSolver {
 public:
  explicit CountingLinearSolver(LinearSolverKind kind) : inner_(make_linear_solver(kind)) {}
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    ++factorizations;
    inner_->factorize(A);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    ++solves;
    return inner_->solve(b);
  }
  std::string method() const override { return inner_->method(); }
  int analyses() const override { return inner_->analyses(); }
  int factorizations = 0;
  int solves = 0;

 private:
  std::unique_ptr<LinearSolver> inner_;
};

}  // namespace cushion::solver::test
