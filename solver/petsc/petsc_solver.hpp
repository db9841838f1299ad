#pragma once
/// Linear solves with PETSc's Krylov solvers and preconditioners (KSP/PC), behind LinearSolver.
///
/// Defaults, overridden by the case's "petsc_options": symmetric tangents CG, unsymmetric ones
/// (F-bar, friction) GMRES; preconditioner GAMG (smoothed-aggregation algebraic multigrid) with the
/// six rigid-body modes from the nodal coordinates as near-null space (set_geometry), SOR level smoothers
/// (petsc_solver.cpp: where they fail); relative
/// tolerance 1e-8 on PETSc's residual norm, at most 1000 iterations. A direct solve is
/// "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps" (Debian's PETSc has MUMPS).
///
/// The matrix: with a geometry, all 3 DOFs of every node (block size 3), constrained DOFs as rows and
/// columns holding only a diagonal entry (the mean |diagonal| of A) and a zero right-hand side, so the
/// rigid-body modes live on whole nodes; without one, the free DOFs only (block size 1, no near-null
/// space). Entries are set by COO (MatSetValuesCOO) in the order of A's storage.
///
/// Preconditioner reuse (the multigrid analogue of modified Newton): factorize(A) updates the matrix
/// and keeps the preconditioner built for an earlier A while the last solve needed at most
/// max(2 k0, k0 + 10) iterations, k0 being the iterations of the first solve after the last setup;
/// the option "-cushion_pc_reuse_max_it N" sets that limit (0: a new setup at every factorize). A
/// solve with a reused preconditioner that does not converge is repeated once with a new one. No
/// reuse with "-ksp_type preonly" (an old LU would silently solve with an old tangent).
///
/// One process (PETSC_COMM_SELF), or distributed over PETSC_COMM_WORLD with a Distribution: each
/// process gives PETSc the rows of the nodes it owns (an MPIAIJ matrix, its nodes numbered
/// contiguously), and every process gets the whole solution. Needs a live petsc::Session.
#include <memory>
#include <string>

#include "solver/distribution.hpp"
#include "solver/linear_solver.hpp"

namespace cushion::solver::petsc {

/// A PETSc solver; `symmetric`: A is symmetric (CG by default, else GMRES). `options`: PETSc options
/// ("-ksp_type cg -pc_type gamg ...") over the defaults; check them first with options_problem().
/// Throws LinearSolveError if PETSc rejects them.
/// `distribution`: a distributed run (set_geometry() is then required), nullptr: one process.
std::unique_ptr<LinearSolver> make_solver(bool symmetric, const std::string& options,
                                          std::shared_ptr<const Distribution> distribution = nullptr);

/// Why `options` cannot be used, or "" if they can: a PETSc error while setting up and solving a
/// small elasticity-like problem with them (unknown KSP or PC type, bad value, missing package), or
/// options that nothing read ("unknown or unused PETSc option(s) -ksp_tpye"). Not converging is not
/// a problem here. Prints nothing.
std::string options_problem(bool symmetric, const std::string& options);

}  // namespace cushion::solver::petsc
