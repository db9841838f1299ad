#pragma once
/// Sparse linear solvers behind one small interface: factorize(A) then solve(b). The symbolic
/// analysis (fill-reducing ordering) is done once and reused while the sparsity pattern of A is
/// unchanged (the assembler keeps one pattern for a whole analysis). Direct solvers here (CHOLMOD,
/// UMFPACK); the PETSc Krylov/AMG solver in solver/petsc/ implements the same interface.
#include <complex>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Sparse>

namespace cushion::solver {

class DofMap;  // dof_map.hpp

/// Thrown when a linear solve fails numerically without the matrix being known singular: an
/// iterative solver did not converge, or an external solver library reported a numerical failure.
/// Newton gives up the increment (the caller cuts back), as for SingularMatrixError.
class LinearSolveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown when a matrix cannot be factorized: singular (reciprocal condition estimate below 1e-13,
/// round-off level pivots), or not positive definite for Cholesky without fallback.
class SingularMatrixError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The message used for a singular stiffness matrix.
inline constexpr const char* singular_stiffness_message =
    "stiffness matrix is singular: rigid-body mode not constrained, or material unstable";

/// Remembers a sparsity pattern (outer and inner indices) to decide whether analysis can be reused.
template <class Scalar>
class PatternSignature {
 public:
  /// True if A has the stored pattern; otherwise stores A's pattern and returns false.
  bool matches_or_store(const Eigen::SparseMatrix<Scalar>& A);

 private:
  Eigen::Index rows_ = -1;
  std::vector<int> outer_, inner_;
};

/// A factorization (or preconditioner) of a real square sparse matrix (units of A and b are the caller's).
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Where the unknowns of A sit, before the first factorize(): A's row i is the free DOF i of
  /// `dofs`, at the reference node coordinates `nodes` [mm]. Algebraic multigrid builds its near-null
  /// space (the six rigid-body modes) from it (copying what it needs); direct solvers ignore it.
  virtual void set_geometry(const DofMap& dofs, const std::vector<Eigen::Vector3d>& nodes) {}
  /// Factorizes A (compressed); analysis reused while the pattern is unchanged. The factor does not
  /// refer to A afterwards (A may change or die before solve()). Throws SingularMatrixError or
  /// LinearSolveError.
  virtual void factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Solves A x = b with the last factorization. Throws SingularMatrixError on a non-finite result,
  /// LinearSolveError if an iterative solver does not converge.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  /// One line on the last solve for the run log, e.g. "ksp cg: 23 iterations, |r|/|b| 4.1e-09,
  /// preconditioner reused"; empty for direct solvers (nothing to report).
  virtual std::string last_solve_report() const { return {}; }
  /// Name of the method actually used by the last factorization (e.g. "cholmod-llt", "umfpack-lu").
  virtual std::string method() const = 0;
  /// Number of symbolic analyses performed so far (for checking the reuse).
  virtual int analyses() const = 0;
  /// One line on the last symbolic analysis and the BLAS in use, e.g. "cholmod supernodal, ordering
  /// metis (tried amd, metis), nnz(L) 1.2e+08, 3.4e+11 flop; BLAS openblas, 2 threads"; empty if none.
  virtual std::string analysis_report() const { return {}; }
};

/// Which solver to build (any consistent units).
enum class LinearSolverKind {
  cholesky,         ///< CHOLMOD supernodal LL^T, symmetric positive definite only (throws
                    ///< std::invalid_argument for an unsymmetric A)
  cholesky_or_lu,   ///< Cholesky, falling back to UMFPACK LU when symmetric A is not positive definite
  lu                ///< UMFPACK LU, any non-singular matrix (unsymmetric F-bar tangents)
};

/// A new solver of the given kind (no analysis done yet).
std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind);

/// UMFPACK LU for complex matrices (frequency-domain steps), with analysis reuse.
class ComplexLuSolver {
 public:
  ComplexLuSolver();
  ~ComplexLuSolver();
  /// Factorizes A. Throws SingularMatrixError.
  void factorize(const Eigen::SparseMatrix<std::complex<double>>& A);
  /// Solves A x = b.
  Eigen::VectorXcd solve(const Eigen::VectorXcd& b);
  /// Number of symbolic analyses performed so far.
  int analyses() const { return analyses_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int analyses_ = 0;
};

}  // namespace cushion::solver
