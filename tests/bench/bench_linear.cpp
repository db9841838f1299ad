// Benchmark (not a test, not run by ctest; tools/bench_linear.sh runs it under /usr/bin/time -v).
//   bench_linear SOLVER n [PETSC_OPTIONS]      SOLVER: cholmod | gamg | mumps
// One solve with the tangent of the quarter cube (n^3 hex8, 20 % compressed, quarter_cube.hpp): CHOLMOD
// LL^T, PETSc CG + GAMG with the rigid-body near-null space (the default of "linear_solver": "petsc"),
// or PETSc + MUMPS Cholesky. Prints one line of key=value: free dofs, nonzeros, assembly, setup
// (analysis + factorization, or preconditioner setup) and solve wall times [s], the relative residual
// |K x - b| / |b| and the solver's report of the solve (Krylov iterations). PETSC_OPTIONS are added
// to the PETSc solvers' options (e.g. "-mg_levels_ksp_type chebyshev -mg_levels_pc_type jacobi").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "quarter_cube.hpp"
#include "solver/petsc/petsc_session.hpp"
#include "solver/petsc/petsc_solver.hpp"

using namespace cushion;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::unique_ptr<solver::LinearSolver> make(const std::string& name, const std::string& options) {
  if (name == "cholmod") return solver::make_linear_solver(solver::LinearSolverKind::cholesky);
  if (name == "gamg") return solver::petsc::make_solver(true, options);
  if (name == "mumps")
    return solver::petsc::make_solver(
        true, "-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps " + options);
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "";
  const int n = argc > 2 ? std::atoi(argv[2]) : 0;
  const solver::petsc::Session petsc;
  auto linear = make(name, argc > 3 ? argv[3] : "");
  if (!linear || n < 1) {
    std::fprintf(stderr, "usage: bench_linear cholmod|gamg|mumps n [petsc_options]\n");
    return 2;
  }
  const bench::CubeTangent tangent = bench::compressed_cube_tangent(n);
  const solver::SparseMatrix& K = tangent.K;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  linear->set_geometry(tangent.assembler->dofs(), tangent.c.m.nodes);
  auto t0 = std::chrono::steady_clock::now();
  linear->factorize(K);
  const double setup = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd x = linear->solve(b);
  const double solve = seconds_since(t0);
  std::printf("solver=%s n=%d dofs=%ld nnz=%ld assembly_s=%.3f setup_s=%.3f solve_s=%.3f residual=%.2e method=\"%s\" "
              "report=\"%s\"\n",
              name.c_str(), n, static_cast<long>(K.rows()), static_cast<long>(K.nonZeros()), tangent.assembly_s, setup,
              solve, (K * x - b).norm() / b.norm(), linear->method().c_str(), linear->last_solve_report().c_str());
  return 0;
}
