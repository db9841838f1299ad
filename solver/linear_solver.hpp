#pragma once
/// Sparse direct solvers behind one small interface: factorize(A) then solve(b). The symbolic
/// analysis (fill-reducing ordering) is done once and reused while the sparsity pattern of A is
/// unchanged (the assembler keeps one pattern for a whole analysis).
#include <complex>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Sparse>

namespace cushion::solver {

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

/// A factorization of a real square sparse matrix (units of A and b are the caller's).
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Factorizes A (compressed); analysis reused while the pattern is unchanged. The factor does not
  /// refer to A afterwards (A may change or die before solve()). Throws SingularMatrixError.
  virtual void factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Solves A x = b with the last factorization. Throws SingularMatrixError on a non-finite result.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
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
