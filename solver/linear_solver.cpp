#include "solver/linear_solver.hpp"

#include <dlfcn.h>

#include <cstdio>

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

namespace cushion::solver {

template <class Scalar>
bool PatternSignature<Scalar>::matches_or_store(const Eigen::SparseMatrix<Scalar>& A) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const auto nnz = A.nonZeros();
  const bool same = rows_ == A.rows() && static_cast<Eigen::Index>(outer_.size()) == A.outerSize() + 1 &&
                    static_cast<Eigen::Index>(inner_.size()) == nnz &&
                    std::equal(outer_.begin(), outer_.end(), outer) && std::equal(inner_.begin(), inner_.end(), inner);
  if (!same) {
    rows_ = A.rows();
    outer_.assign(outer, outer + A.outerSize() + 1);
    inner_.assign(inner, inner + nnz);
  }
  return same;
}
template class PatternSignature<double>;
template class PatternSignature<std::complex<double>>;

namespace {

/// Reciprocal condition estimates below this are treated as singular (round-off level pivots).
constexpr double singular_rcond = 1e-13;

/// CHOLMOD LL^T exposing its reciprocal condition estimate (min diag L / max diag L)^2 (~ rcond of A).
/// Ordering: CHOLMOD's default strategy (AMD; METIS nested dissection too when AMD's fill is large,
/// keeping the better one); supernodal factorization on the system BLAS.
class CholmodLLT : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
 public:
  CholmodLLT() { cholmod().print = 0; }  // non-positive-definite matrices are reported by exception
  double rcond() { return cholmod_rcond(m_cholmodFactor, &cholmod()); }
  /// Ordering chosen by the last analysis, the orderings tried, nnz(L), flop count, supernodal or not.
  std::string report() {
    cholmod_common& c = cholmod();
    if (!m_cholmodFactor) return {};
    std::string tried;
    const int n_tried = c.nmethods > 0 ? c.nmethods : c.selected + 1;  // nmethods = 0: AMD, then maybe METIS
    for (int k = 0; k < n_tried && k <= CHOLMOD_MAXMETHODS; ++k)
      if (c.method[k].lnz > 0) tried += std::string(tried.empty() ? "" : ", ") + ordering_name(c.method[k].ordering);
    char text[300];
    std::snprintf(text, sizeof text, "cholmod %s, ordering %s (tried %s), nnz(L) %.3g, %.3g flop",
                  m_cholmodFactor->is_super ? "supernodal" : "simplicial",
                  ordering_name(m_cholmodFactor->ordering), tried.c_str(), c.lnz, c.fl);
    return text;
  }

 private:
  static const char* ordering_name(int ordering) {
    switch (ordering) {
      case CHOLMOD_NATURAL: return "natural";
      case CHOLMOD_GIVEN: return "given";
      case CHOLMOD_AMD: return "amd";
      case CHOLMOD_METIS: return "metis";
      case CHOLMOD_NESDIS: return "nesdis";
      case CHOLMOD_COLAMD: return "colamd";
      case CHOLMOD_POSTORDERED: return "postordered";
    }
    return "unknown";
  }
};

/// The BLAS behind CHOLMOD's supernodal kernels: OpenBLAS and its thread count, or "other".
std::string blas_report() {
  using GetThreads = int (*)();
  if (auto f = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads")))
    return "BLAS openblas, " + std::to_string(f()) + " threads";
  return "BLAS not openblas (reference BLAS is slow for supernodal Cholesky)";
}

/// UMFPACK LU exposing its reciprocal condition estimate min |diag U| / max |diag U|.
template <class Scalar>
class UmfpackLU : public Eigen::UmfPackLU<Eigen::SparseMatrix<Scalar>> {
 public:
  double rcond() const { return this->m_umfpackInfo(UMFPACK_RCOND); }
};

template <class Vector>
void require_finite(const Vector& x) {
  if (!x.allFinite()) throw SingularMatrixError(singular_stiffness_message);
}

/// UMFPACK LU with analysis reuse (real or complex). Keeps its own copy of A: UMFPACK's iterative
/// refinement in solve() reads A, which must match the factor even if the caller's A has changed.
template <class Scalar>
class UmfpackFactor {
 public:
  /// Returns false if the matrix is singular.
  bool factorize(const Eigen::SparseMatrix<Scalar>& A, int& analyses) {
    A_ = A;
    if (!signature_.matches_or_store(A_)) {
      lu_.analyzePattern(A_);
      ++analyses;
    }
    lu_.factorize(A_);
    return lu_.info() == Eigen::Success && lu_.rcond() > singular_rcond;
  }
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> solve(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b) {
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> x = lu_.solve(b);
    require_finite(x);
    return x;
  }

 private:
  Eigen::SparseMatrix<Scalar> A_;
  UmfpackLU<Scalar> lu_;
  PatternSignature<Scalar> signature_;
};

class LuSolver final : public LinearSolver {
 public:
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    if (!lu_.factorize(A, analyses_)) throw SingularMatrixError(singular_stiffness_message);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override { return lu_.solve(b); }
  std::string method() const override { return "umfpack-lu"; }
  int analyses() const override { return analyses_; }
  std::string analysis_report() const override { return analyses_ ? "umfpack; " + blas_report() : ""; }

 private:
  UmfpackFactor<double> lu_;
  int analyses_ = 0;
};

class CholeskySolver final : public LinearSolver {
 public:
  explicit CholeskySolver(bool fallback_to_lu) : fallback_to_lu_(fallback_to_lu) {}

  void factorize(const Eigen::SparseMatrix<double>& A) override {
    // CHOLMOD reads the lower triangle only: an unsymmetric A would be solved silently wrong.
    const Eigen::SparseMatrix<double> asymmetry = A - Eigen::SparseMatrix<double>(A.transpose());
    if (asymmetry.nonZeros() && asymmetry.coeffs().cwiseAbs().maxCoeff() > 1e-10 * A.coeffs().cwiseAbs().maxCoeff())
      throw std::invalid_argument("Cholesky needs a symmetric matrix (use LU for F-bar / unsymmetric tangents)");
    if (!signature_.matches_or_store(A)) {
      llt_.analyzePattern(A);
      ++analyses_;
      report_ = llt_.report() + "; " + blas_report();
    }
    llt_.factorize(A);
    used_lu_ = llt_.info() != Eigen::Success || !(llt_.rcond() > singular_rcond);
    if (!used_lu_) return;
    // Not positive definite: singular, or indefinite (unstable/softening material).
    if (!fallback_to_lu_ || !lu_.factorize(A, analyses_)) throw SingularMatrixError(singular_stiffness_message);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    if (used_lu_) return lu_.solve(b);
    Eigen::VectorXd x = llt_.solve(b);
    require_finite(x);
    return x;
  }
  std::string method() const override { return used_lu_ ? "umfpack-lu (cholmod: not positive definite)" : "cholmod-llt"; }
  int analyses() const override { return analyses_; }
  std::string analysis_report() const override { return report_; }

 private:
  bool fallback_to_lu_;
  std::string report_;
  bool used_lu_ = false;
  CholmodLLT llt_;
  PatternSignature<double> signature_;
  UmfpackFactor<double> lu_;
  int analyses_ = 0;
};

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::cholesky: return std::make_unique<CholeskySolver>(false);
    case LinearSolverKind::cholesky_or_lu: return std::make_unique<CholeskySolver>(true);
    case LinearSolverKind::lu: return std::make_unique<LuSolver>();
  }
  throw std::invalid_argument("make_linear_solver: unknown kind");
}

struct ComplexLuSolver::Impl {
  UmfpackFactor<std::complex<double>> lu;
};

ComplexLuSolver::ComplexLuSolver() : impl_(std::make_unique<Impl>()) {}
ComplexLuSolver::~ComplexLuSolver() = default;

void ComplexLuSolver::factorize(const Eigen::SparseMatrix<std::complex<double>>& A) {
  if (!impl_->lu.factorize(A, analyses_)) throw SingularMatrixError("complex system matrix is singular");
}

Eigen::VectorXcd ComplexLuSolver::solve(const Eigen::VectorXcd& b) { return impl_->lu.solve(b); }

}  // namespace cushion::solver
