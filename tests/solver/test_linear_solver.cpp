// Requirement: the direct solvers solve SPD, unsymmetric and complex systems, reuse their symbolic
// analysis while the pattern is unchanged, and report singular matrices with a clear message.
// Tolerance: max |x - x_exact| <= 1e-10 max |x_exact| on systems of 900 unknowns.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>

#include "solver/linear_solver.hpp"

namespace cushion::solver {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// 2D five-point operator on an m x m grid: diffusion (SPD, Dirichlet-like with `shift` on the
/// diagonal) plus `convection` (unsymmetric upwind part). shift = 0 and no boundary term: singular.
Sparse grid_operator(int m, double shift, double convection, bool dirichlet = true) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      double diag = shift;
      const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
      for (int k = 0; k < 4; ++k) {
        const int a = nb[k][0], b = nb[k][1];
        if (a < 0 || a >= m || b < 0 || b >= m) {
          if (dirichlet) diag += 1.0;
          continue;
        }
        diag += 1.0;
        t.emplace_back(id(i, j), id(a, b), -1.0 + (k == 0 ? -convection : 0.0));
      }
      t.emplace_back(id(i, j), id(i, j), diag + convection);
    }
  Sparse A(m * m, m * m);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x(i) = u(rng);
  return x;
}

double relative_error(const Eigen::VectorXd& x, const Eigen::VectorXd& exact) {
  return (x - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
}

TEST(LinearSolver, SolvesSpdSystemWithEveryKind) {
  const Sparse A = grid_operator(30, 0.0, 0.0);
  const Eigen::VectorXd x_exact = random_vector(900, 1);
  const Eigen::VectorXd b = A * x_exact;
  for (auto kind : {LinearSolverKind::cholesky, LinearSolverKind::cholesky_or_lu, LinearSolverKind::lu}) {
    auto solver = make_linear_solver(kind);
    solver->factorize(A);
    EXPECT_LE(relative_error(solver->solve(b), x_exact), 1e-10) << solver->method();
  }
  EXPECT_EQ(make_linear_solver(LinearSolverKind::cholesky_or_lu)->method(), "cholmod-llt");
}

TEST(LinearSolver, ReusesAnalysisWhileThePatternIsUnchanged) {
  const Sparse A = grid_operator(30, 0.0, 0.0);
  const Sparse A2 = 2.0 * A;
  const Sparse B = grid_operator(20, 0.5, 0.0);
  for (auto kind : {LinearSolverKind::cholesky, LinearSolverKind::lu}) {
    auto solver = make_linear_solver(kind);
    solver->factorize(A);
    solver->factorize(A2);
    EXPECT_EQ(solver->analyses(), 1);
    const Eigen::VectorXd x_exact = random_vector(900, 2);
    EXPECT_LE(relative_error(solver->solve(A2 * x_exact), x_exact), 1e-10);
    solver->factorize(B);
    EXPECT_EQ(solver->analyses(), 2);
    const Eigen::VectorXd y_exact = random_vector(400, 3);
    EXPECT_LE(relative_error(solver->solve(B * y_exact), y_exact), 1e-10);
  }
}

TEST(LinearSolver, SolvesUnsymmetricSystemWithLu) {
  const Sparse A = grid_operator(30, 0.1, 0.8);
  ASSERT_GT((A - Sparse(A.transpose())).norm(), 1.0);
  const Eigen::VectorXd x_exact = random_vector(900, 4);
  auto lu = make_linear_solver(LinearSolverKind::lu);
  lu->factorize(A);
  EXPECT_LE(relative_error(lu->solve(A * x_exact), x_exact), 1e-10);
  // Cholesky would read the lower triangle only: it refuses.
  EXPECT_THROW(make_linear_solver(LinearSolverKind::cholesky)->factorize(A), std::invalid_argument);
}

TEST(LinearSolver, SolvesComplexSystem) {
  // K + i omega C with K the SPD grid operator and C a diagonal damping: x = (1 + 2i) x_r + i x_i.
  const Sparse K = grid_operator(30, 0.0, 0.3);
  Eigen::SparseMatrix<std::complex<double>> A = K.cast<std::complex<double>>();
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<std::complex<double>>::InnerIterator it(A, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() += std::complex<double>(0.0, 0.5 + 0.001 * it.row());
  const Eigen::VectorXcd x_exact =
      random_vector(900, 5).cast<std::complex<double>>() * std::complex<double>(1, 2) +
      random_vector(900, 6).cast<std::complex<double>>() * std::complex<double>(0, 1);
  ComplexLuSolver lu;
  lu.factorize(A);
  lu.factorize(A);
  EXPECT_EQ(lu.analyses(), 1);
  const Eigen::VectorXcd x = lu.solve(A * x_exact);
  EXPECT_LE((x - x_exact).cwiseAbs().maxCoeff() / x_exact.cwiseAbs().maxCoeff(), 1e-10);
}

TEST(LinearSolver, SingularMatrixGivesTheMessage) {
  // Pure-Neumann operator: constants are in the null space (a free rigid-body mode).
  const Sparse A = grid_operator(30, 0.0, 0.0, false);
  for (auto kind : {LinearSolverKind::cholesky, LinearSolverKind::cholesky_or_lu, LinearSolverKind::lu}) {
    auto solver = make_linear_solver(kind);
    try {
      solver->factorize(A);
      ADD_FAILURE() << "no exception for a singular matrix";
    } catch (const SingularMatrixError& e) {
      EXPECT_STREQ(e.what(), "stiffness matrix is singular: rigid-body mode not constrained, or material unstable");
    }
  }
}

TEST(LinearSolver, IndefiniteMatrixFallsBackToLu) {
  // Symmetric, non-singular, indefinite (a softening material): Cholesky fails, LU solves it.
  Sparse A = grid_operator(30, -0.2, 0.0);
  const Eigen::VectorXd x_exact = random_vector(900, 7);
  EXPECT_THROW(make_linear_solver(LinearSolverKind::cholesky)->factorize(A), SingularMatrixError);
  auto solver = make_linear_solver(LinearSolverKind::cholesky_or_lu);
  solver->factorize(A);
  EXPECT_NE(solver->method().find("umfpack-lu"), std::string::npos);
  EXPECT_LE(relative_error(solver->solve(A * x_exact), x_exact), 1e-10);
}

TEST(LinearSolver, FactorDoesNotDependOnTheCallersMatrix) {
  // The caller's matrix changes and dies after factorize(): solve() still solves the factorized
  // system (UMFPACK's refinement must not read the caller's storage), for both kinds.
  const Sparse A = grid_operator(30, 0.1, 0.8);
  const Sparse S = grid_operator(30, 0.0, 0.0);
  const Eigen::VectorXd x_exact = random_vector(900, 8);
  auto lu = make_linear_solver(LinearSolverKind::lu);
  auto llt = make_linear_solver(LinearSolverKind::cholesky);
  {
    auto temporary = std::make_unique<Sparse>(A);
    lu->factorize(*temporary);
    *temporary *= 3.0;  // modified, then destroyed
    auto temporary_spd = std::make_unique<Sparse>(S);
    llt->factorize(*temporary_spd);
    *temporary_spd *= 3.0;
  }
  EXPECT_LE(relative_error(lu->solve(A * x_exact), x_exact), 1e-10);
  EXPECT_LE(relative_error(llt->solve(S * x_exact), x_exact), 1e-10);
}

TEST(LinearSolver, AnalysisReportNamesOrderingAndBlas) {
  auto llt = make_linear_solver(LinearSolverKind::cholesky);
  EXPECT_EQ(llt->analysis_report(), "");
  llt->factorize(grid_operator(30, 0.0, 0.0));
  const std::string report = llt->analysis_report();
  EXPECT_EQ(report.rfind("cholmod supernodal, ordering ", 0), 0u) << report;
  EXPECT_NE(report.find("nnz(L)"), std::string::npos) << report;
  EXPECT_NE(report.find("BLAS"), std::string::npos) << report;
  std::printf("%s\n", report.c_str());
}

}  // namespace
}  // namespace cushion::solver
