#include "solver/petsc/petsc_solver.hpp"

#include <petscksp.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "solver/dof_map.hpp"
#include "solver/petsc/petsc_session.hpp"
#include "solver/petsc/petsc_support.hpp"

namespace cushion::solver::petsc {

namespace {

/// Defaults under the caller's options: multigrid levels smoothed by symmetric SOR (Richardson). The
/// PETSc default, Chebyshev with estimated eigenvalues, gave an indefinite preconditioner (CG stopped
/// with DIVERGED_INDEFINITE_PC) on compressed foam tangents that CHOLMOD factorizes as SPD. On these
/// matrices (block size 3, rows of a node alike) PETSc's SOR inverts the 3 x 3 node blocks; it fails
/// (DIVERGED_PC_FAILED: SUBPC_ERROR, a zero pivot) where an aggregate of fewer nodes than rigid-body modes
/// leaves all-zero rows in a coarse operator (30^3 and 69^3 cubes, the graded 20 x 20 x 8 indentation, the
/// 40 x 40 x 16 one on two processes). switch_smoothers() then shifts the diagonal (sor_shift), which
/// smooths those rows to zero; PETSc then uses point SOR, which needs more iterations (measured on a
/// 30 x 30 x 12 indentation: 18.4 CG iterations per solve against 12.2), so it is not the default.
constexpr const char* default_options = "-mg_levels_ksp_type richardson -mg_levels_pc_type sor";

/// SOR's diagonal shift after a failure, relative to the mean |diagonal| of the fine matrix [-].
constexpr double sor_shift = 1e-12;

/// A Krylov solve that ended without converging (PETSc itself reported no error).
class NotConverged : public LinearSolveError {
 public:
  using LinearSolveError::LinearSolveError;
};

/// Owner of one PETSc object, destroyed with its XxxDestroy.
template <class T, PetscErrorCode (*Destroy)(T*)>
class Handle {
 public:
  Handle() = default;
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator T() const { return p_; }
  /// Destroys the object held, for a call that creates a new one into the returned slot.
  T* out() {
    reset();
    return &p_;
  }

 private:
  void reset() {
    if (p_) Destroy(&p_);
    p_ = nullptr;
  }
  T p_ = nullptr;
};

/// Where the rows of A go in the PETSc system (PETSc rows without one of A are constrained DOFs). With
/// a geometry the PETSc nodes are numbered process by process (the nodes of process 0 first, each
/// process's in ascending order), so each process's rows are one contiguous range.
struct Layout {
  PetscInt size = 0;                    ///< PETSc rows (all processes)
  PetscInt begin = 0, local = 0;        ///< this process's PETSc rows [begin, begin + local)
  PetscInt block = 1;                   ///< 3 with a geometry (x, y, z of one node), else 1
  std::vector<PetscInt> row;            ///< PETSc row of each row of A
  std::vector<PetscInt> constrained;    ///< this process's PETSc rows with no row of A (diagonal only)
  std::vector<PetscScalar> coordinates; ///< x, y, z of this process's nodes [mm]; empty: no near-null space
  bool owns(PetscInt r) const { return r >= begin && r < begin + local; }
};

/// The layout of the nodes of `dofs`/`nodes` over the processes of `d` (one process if null).
Layout node_layout(const DofMap& dofs, const std::vector<Eigen::Vector3d>& nodes, const Distribution* d) {
  const std::size_t n = nodes.size();
  const int parts = d ? d->size() : 1, rank = d ? d->rank() : 0;
  auto owner = [d](std::size_t a) { return d ? d->node_owner(static_cast<int>(a)) : 0; };
  std::vector<PetscInt> first(static_cast<std::size_t>(parts) + 1, 0), petsc_node(n);
  for (std::size_t a = 0; a < n; ++a) ++first[owner(a) + 1];
  for (int p = 0; p < parts; ++p) first[p + 1] += first[p];
  std::vector<PetscInt> next(first.begin(), first.end() - 1);
  for (std::size_t a = 0; a < n; ++a) petsc_node[a] = next[owner(a)]++;
  Layout l;
  l.size = static_cast<PetscInt>(3 * n);
  l.begin = 3 * first[rank];
  l.local = 3 * (first[rank + 1] - first[rank]);
  l.block = 3;
  for (int dof : dofs.free_dofs()) l.row.push_back(3 * petsc_node[dof / 3] + dof % 3);
  for (int dof : dofs.constrained_dofs())
    if (owner(dof / 3) == rank) l.constrained.push_back(3 * petsc_node[dof / 3] + dof % 3);
  for (std::size_t a = 0; a < n; ++a)
    if (owner(a) == rank) l.coordinates.insert(l.coordinates.end(), {nodes[a](0), nodes[a](1), nodes[a](2)});
  return l;
}

class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(bool symmetric, const std::string& options, std::shared_ptr<const Distribution> distribution)
      : distribution_(std::move(distribution)), comm_(distribution_ ? PETSC_COMM_WORLD : PETSC_COMM_SELF) {
    if (!Session::active()) throw std::logic_error("a PETSc solver needs a live petsc::Session");
    check(PetscOptionsCreate(options_.out()), "PetscOptionsCreate");
    check(PetscOptionsInsertString(options_, default_options), "PetscOptionsInsertString");
    check(PetscOptionsInsertString(options_, options.c_str()), "PetscOptionsInsertString");
    std::istringstream words(options);
    for (std::string w; words >> w;)
      if (w.size() > 1 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1]))) given_.insert(w);
    const OptionsScope scope(options_);
    create_ksp(symmetric ? KSPCG : KSPGMRES);
    PetscInt limit = -1;
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsGetInt(options_, nullptr, "-cushion_pc_reuse_max_it", &limit, &set), "PetscOptionsGetInt");
    reuse_limit_ = set ? limit : -1;
    KSPType type = nullptr;
    check(KSPGetType(ksp_, &type), "KSPGetType");
    preonly_ = std::strcmp(type, KSPPREONLY) == 0;
  }

  void set_geometry(const DofMap& dofs, const std::vector<Eigen::Vector3d>& nodes) override {
    if (dofs.num_dofs() != 3 * nodes.size()) throw std::invalid_argument("PETSc solver: DOF map and nodes differ");
    layout_ = node_layout(dofs, nodes, distribution_.get());
    pattern_ = {};  // the next factorize builds the matrix in this layout
  }

  void factorize(const Eigen::SparseMatrix<double>& A) override {
    const OptionsScope scope(options_);
    if (!pattern_.matches_or_store(A)) build_matrix(A);
    set_values(A);
    if (!pc_ready_ || !reuse_next_) setup_preconditioner();
    else check(KSPSetReusePreconditioner(ksp_, PETSC_TRUE), "KSPSetReusePreconditioner");
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    if (!pc_ready_) throw std::logic_error("PETSc solver: solve() before factorize()");
    const OptionsScope scope(options_);
    set_rhs(b);
    const bool reused = !fresh_;
    run_ksp();
    const bool retried = reason_ < 0 && reused;
    if (retried) {
      setup_preconditioner();
      run_ksp();
    }
    const std::string failed_setup = pc_failure();
    const bool smoothed_again = reason_ == KSP_DIVERGED_PC_FAILED && switch_smoothers();
    if (smoothed_again) {
      setup_preconditioner();
      run_ksp();
    }
    const bool switched = reason_ == KSP_DIVERGED_INDEFINITE_PC && switch_to_gmres();
    if (switched) run_ksp();
    last_report_ = "ksp " + ksp_type() + ": " + std::to_string(iterations_) + " iterations (" +
                   KSPConvergedReasons[reason_] + pc_failure() + "), " +
                   (retried  ? "new preconditioner (the reused one did not converge)"
                    : reused ? "preconditioner reused"
                             : "new preconditioner") +
                   (smoothed_again ? "; SOR smoothing failed (" + failed_setup.substr(2) +
                                         "): SOR on a shifted diagonal from here on"
                                   : "") +
                   (switched ? "; CG met an indefinite preconditioner: GMRES from here on" : "");
    if (reason_ < 0) throw NotConverged(method() + " did not converge: " + last_report_);
    total_iterations_ += iterations_;
    ++solves_;
    if (fresh_) fresh_iterations_ = iterations_;
    fresh_ = false;
    reuse_next_ = !preonly_ && reuse_limit_ != 0 && iterations_ <= reuse_limit();
    return solution();
  }

  std::string method() const override {
    PC pc = nullptr;
    PCType type = nullptr;
    MatSolverType package = nullptr;
    KSPGetPC(ksp_, &pc);
    PCGetType(pc, &type);
    std::string name = "petsc " + ksp_type() + " + " + (type ? type : "?");
    if (type && (!std::strcmp(type, PCLU) || !std::strcmp(type, PCCHOLESKY)) &&
        !PCFactorGetMatSolverType(pc, &package) && package)
      name += std::string(" (") + package + ")";
    return name;
  }
  int analyses() const override { return analyses_; }
  std::string analysis_report() const override {
    if (!analyses_) return {};
    char text[300];
    std::snprintf(text, sizeof text,
                  "%s, %d preconditioner setups, %ld iterations in %d solves (%.1f each); near-null space: %s",
                  method().c_str(), setups_, total_iterations_, solves_,
                  solves_ ? double(total_iterations_) / solves_ : 0.0,
                  layout_.coordinates.empty() ? "none (no geometry)" : "6 rigid-body modes");
    return text;
  }
  std::string last_solve_report() const override { return last_report_; }

  /// The caller's options nothing has read so far, "-name" each, space separated (defaults not read
  /// because the caller chose another method are not listed).
  std::string unused_options() const {
    PetscInt n = 0;
    char** names = nullptr;
    char** values = nullptr;
    check(PetscOptionsLeftGet(options_, &n, &names, &values), "PetscOptionsLeftGet");
    std::string list;
    for (PetscInt i = 0; i < n; ++i)
      if (given_.count(std::string("-") + names[i])) list += std::string(list.empty() ? "" : " ") + "-" + names[i];
    PetscOptionsLeftRestore(options_, &n, &names, &values);
    return list;
  }

 private:
  /// CG stopped by an indefinite preconditioner (the multigrid cycle of a stiff, strongly compressed foam
  /// tangent is not exactly SPD in floating point): GMRES, which does not need it, for this and every later
  /// solve, unless the case chose the Krylov method. True if switched.
  bool switch_to_gmres() {
    if (given_.count("-ksp_type") || ksp_type() != KSPCG) return false;
    check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
    return true;
  }

  /// The default SOR level smoothers failed the multigrid setup or cycle (a zero pivot: see default_options):
  /// the multigrid is rebuilt with SOR on a diagonal shifted by sor_shift times the mean |diagonal|, for this
  /// and every later solve, unless the case chose the smoothers. True if switched.
  bool switch_smoothers() {
    if (smoothers_switched_ || given_.count("-mg_levels_ksp_type") || given_.count("-mg_levels_pc_type") ||
        given_.count("-mg_levels_pc_sor_diagonal_shift"))
      return false;
    PC pc = nullptr;
    PCType type = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    check(PCGetType(pc, &type), "PCGetType");
    if (!type || std::strcmp(type, PCGAMG) != 0) return false;
    char shift[80];
    std::snprintf(shift, sizeof shift, "-mg_levels_pc_sor_diagonal_shift %.17g", sor_shift * mean_diagonal_);
    check(PetscOptionsInsertString(options_, shift), "PetscOptionsInsertString");
    create_ksp(ksp_type() == KSPCG ? KSPCG : KSPGMRES);  // a new multigrid reads the new options
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    smoothers_switched_ = true;
    return true;
  }

  /// A new KSP of `type` (the caller's -ksp_type wins) with GAMG, relative tolerance 1e-8, at most 1000
  /// iterations, then the options; inside an OptionsScope.
  void create_ksp(const char* type) {
    check(KSPCreate(comm_, ksp_.out()), "KSPCreate");
    check(KSPSetType(ksp_, type), "KSPSetType");
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    check(PCSetType(pc, PCGAMG), "PCSetType");
    check(KSPSetTolerances(ksp_, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 1000), "KSPSetTolerances");
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  }

  /// ": <why the preconditioner failed>" after a DIVERGED_PC_FAILED, else "".
  std::string pc_failure() const {
    if (reason_ != KSP_DIVERGED_PC_FAILED) return {};
    PC pc = nullptr;
    PCFailedReason why = PC_NOERROR;
    KSPGetPC(ksp_, &pc);
    PCGetFailedReasonRank(pc, &why);
    return std::string(": ") + PCFailedReasons[why];
  }

  std::string ksp_type() const {
    KSPType type = nullptr;
    KSPGetType(ksp_, &type);
    return type ? type : "?";
  }

  /// Largest iteration count of a solve after which the preconditioner is kept.
  long reuse_limit() const {
    return reuse_limit_ >= 0 ? reuse_limit_ : std::max(2 * fresh_iterations_, fresh_iterations_ + 10);
  }

  /// A new matrix for A's pattern (COO: this process's rows in A's storage order, then its constrained
  /// diagonal).
  void build_matrix(const Eigen::SparseMatrix<double>& A) {
    if (layout_.size == 0 || static_cast<Eigen::Index>(layout_.row.size()) != A.rows()) {
      if (!layout_.coordinates.empty()) throw std::invalid_argument("PETSc solver: matrix size differs from the DOF map");
      if (distribution_) throw std::logic_error("PETSc solver: a distributed solve needs set_geometry()");
      layout_ = Layout{static_cast<PetscInt>(A.rows()), 0, static_cast<PetscInt>(A.rows()), 1, {}, {}, {}};
      for (PetscInt i = 0; i < layout_.size; ++i) layout_.row.push_back(i);
    }
    std::vector<PetscInt> rows, cols;
    picked_.clear();
    Eigen::Index position = 0;
    for (Eigen::Index k = 0; k < A.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it, ++position)
        if (layout_.owns(layout_.row[it.row()])) {
          rows.push_back(layout_.row[it.row()]);
          cols.push_back(layout_.row[it.col()]);
          picked_.push_back(position);
        }
    rows.insert(rows.end(), layout_.constrained.begin(), layout_.constrained.end());
    cols.insert(cols.end(), layout_.constrained.begin(), layout_.constrained.end());
    values_.resize(rows.size());
    check(MatCreate(comm_, matrix_.out()), "MatCreate");
    check(MatSetSizes(matrix_, layout_.local, layout_.local, layout_.size, layout_.size), "MatSetSizes");
    check(MatSetType(matrix_, MATAIJ), "MatSetType");
    check(MatSetBlockSize(matrix_, layout_.block), "MatSetBlockSize");
    check(MatSetPreallocationCOO(matrix_, static_cast<PetscCount>(rows.size()), rows.data(), cols.data()),
          "MatSetPreallocationCOO");
    if (!layout_.coordinates.empty()) set_near_null_space();
    check(MatCreateVecs(matrix_, x_.out(), b_.out()), "MatCreateVecs");
    if (distribution_) check(VecScatterCreateToAll(x_, gather_.out(), x_all_.out()), "VecScatterCreateToAll");
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    pc_ready_ = false;
    ++analyses_;
  }

  /// The six rigid-body modes of the nodes as GAMG's near-null space.
  void set_near_null_space() {
    Handle<Vec, VecDestroy> coordinates;
    check(VecCreateMPIWithArray(comm_, 3, layout_.local, layout_.size, layout_.coordinates.data(), coordinates.out()),
          "VecCreateMPIWithArray");
    Handle<MatNullSpace, MatNullSpaceDestroy> modes;
    check(MatNullSpaceCreateRigidBody(coordinates, modes.out()), "MatNullSpaceCreateRigidBody");
    check(MatSetNearNullSpace(matrix_, modes), "MatSetNearNullSpace");
  }

  /// A's values (this process's rows), then the constrained diagonal: the mean |diagonal| of A over all
  /// processes (1 if that is 0).
  void set_values(const Eigen::SparseMatrix<double>& A) {
    for (std::size_t j = 0; j < picked_.size(); ++j) values_[j] = A.valuePtr()[picked_[j]];
    const Eigen::VectorXd diagonal = A.diagonal();
    double sum_count[2] = {0.0, 0.0};
    for (Eigen::Index i = 0; i < diagonal.size(); ++i)
      if (layout_.owns(layout_.row[i])) sum_count[0] += std::abs(diagonal(i)), sum_count[1] += 1.0;
    if (distribution_) distribution_->sum(sum_count);
    const double mean = sum_count[1] > 0.0 ? sum_count[0] / sum_count[1] : 0.0;
    mean_diagonal_ = mean > 0.0 ? mean : 1.0;
    std::fill(values_.begin() + static_cast<std::ptrdiff_t>(picked_.size()), values_.end(), mean_diagonal_);
    check(MatSetValuesCOO(matrix_, values_.data(), INSERT_VALUES), "MatSetValuesCOO");
  }

  void setup_preconditioner() {
    check(KSPSetReusePreconditioner(ksp_, PETSC_FALSE), "KSPSetReusePreconditioner");
    check(KSPSetUp(ksp_), "KSPSetUp");
    ++setups_;
    pc_ready_ = fresh_ = true;
  }

  void set_rhs(const Eigen::VectorXd& b) {
    check(VecZeroEntries(b_), "VecZeroEntries");
    PetscScalar* v = nullptr;
    check(VecGetArray(b_, &v), "VecGetArray");
    for (Eigen::Index i = 0; i < b.size(); ++i)
      if (layout_.owns(layout_.row[i])) v[layout_.row[i] - layout_.begin] = b(i);
    check(VecRestoreArray(b_, &v), "VecRestoreArray");
  }

  void run_ksp() {
    check(KSPSolve(ksp_, b_, x_), "KSPSolve");
    PetscInt iterations = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    check(KSPGetConvergedReason(ksp_, &reason_), "KSPGetConvergedReason");
    iterations_ = iterations;
  }

  /// The solution on every process (gathered from all of them in a distributed solve).
  Eigen::VectorXd solution() const {
    Vec whole = x_;
    if (distribution_) {
      check(VecScatterBegin(gather_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
      check(VecScatterEnd(gather_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
      whole = x_all_;
    }
    Eigen::VectorXd x(static_cast<Eigen::Index>(layout_.row.size()));
    const PetscScalar* v = nullptr;
    check(VecGetArrayRead(whole, &v), "VecGetArrayRead");
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = v[layout_.row[i]];
    check(VecRestoreArrayRead(whole, &v), "VecRestoreArrayRead");
    if (!x.allFinite()) throw LinearSolveError(method() + ": the solution is not finite");
    return x;
  }

  std::shared_ptr<const Distribution> distribution_;  ///< null: one process
  MPI_Comm comm_;
  Handle<PetscOptions, PetscOptionsDestroy> options_;
  std::set<std::string> given_;  ///< option names in the caller's string
  Handle<KSP, KSPDestroy> ksp_;
  Handle<Mat, MatDestroy> matrix_;
  Handle<Vec, VecDestroy> x_, b_;
  Handle<VecScatter, VecScatterDestroy> gather_;  ///< distributed: x_ to x_all_ on every process
  Handle<Vec, VecDestroy> x_all_;
  Layout layout_;
  PatternSignature<double> pattern_;
  std::vector<Eigen::Index> picked_;  ///< positions in A's value array of this process's rows
  std::vector<PetscScalar> values_;  ///< COO values, in the order given to MatSetPreallocationCOO
  double mean_diagonal_ = 1.0;       ///< mean |diagonal| of the matrix (units of A)
  bool smoothers_switched_ = false;  ///< switch_smoothers() done
  bool preonly_ = false;             ///< -ksp_type preonly: the preconditioner is the solve (never reused)
  long reuse_limit_ = -1;            ///< -cushion_pc_reuse_max_it, -1: automatic
  bool pc_ready_ = false;            ///< a preconditioner was set up for the current matrix object
  bool fresh_ = false;               ///< ... and no solve has used it yet
  bool reuse_next_ = false;          ///< the last solve was cheap enough to keep the preconditioner
  long fresh_iterations_ = 0;        ///< iterations of the first solve after the last setup
  long iterations_ = 0;              ///< of the last solve
  KSPConvergedReason reason_ = KSP_CONVERGED_ITERATING;
  long total_iterations_ = 0;
  int solves_ = 0, setups_ = 0, analyses_ = 0;
  std::string last_report_;
};

/// A vector Laplacian on an 8 x 8 x 8 node grid (unit spacing), bottom layer constrained: small, SPD,
/// with enough nodes for a multigrid hierarchy of more than one level.
struct ProbeProblem {
  static constexpr int m = 8;
  std::vector<Eigen::Vector3d> nodes;
  std::vector<bool> constrained;
  Eigen::SparseMatrix<double> A;

  ProbeProblem() {
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          nodes.emplace_back(i, j, k);
          constrained.insert(constrained.end(), 3, k == 0);
        }
  }
  void assemble(const DofMap& dofs) {
    std::vector<Eigen::Triplet<double>> t;
    auto add = [&](int a, int b, double v) {
      for (int c = 0; c < 3; ++c) {
        const int ra = dofs.equation(DofMap::dof(a, c)), rb = dofs.equation(DofMap::dof(b, c));
        if (ra >= 0 && rb >= 0) t.emplace_back(ra, rb, v);
      }
    };
    for (int a = 0; a < m * m * m; ++a)
      for (int step : {1, m, m * m}) {
        const int b = a + step;
        if (b >= m * m * m || (step == 1 && a % m == m - 1) || (step == m && (a / m) % m == m - 1)) continue;
        add(a, a, 1.0), add(b, b, 1.0), add(a, b, -1.0), add(b, a, -1.0);
      }
    A.resize(static_cast<Eigen::Index>(dofs.num_free()), static_cast<Eigen::Index>(dofs.num_free()));
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
  }
};

}  // namespace

std::unique_ptr<LinearSolver> make_solver(bool symmetric, const std::string& options,
                                          std::shared_ptr<const Distribution> distribution) {
  return std::make_unique<PetscSolver>(symmetric, options, std::move(distribution));
}

std::string options_problem(bool symmetric, const std::string& options) {
  const SilenceScope quiet;
  try {
    ProbeProblem probe;
    const DofMap dofs(probe.nodes.size(), probe.constrained);
    probe.assemble(dofs);
    PetscSolver solver(symmetric, options, nullptr);
    solver.set_geometry(dofs, probe.nodes);
    solver.factorize(probe.A);
    try {
      solver.solve(Eigen::VectorXd::Ones(probe.A.rows()));
    } catch (const NotConverged&) {
      // the options may be meant for the real problem (-ksp_max_it); only errors matter here
    }
    const std::string unused = solver.unused_options();
    if (!unused.empty())
      return "unknown or unused PETSc option(s) " + unused +
             " (misspelled, or not read by the chosen Krylov method and preconditioner)";
  } catch (const LinearSolveError& e) {
    return e.what();
  }
  return {};
}

}  // namespace cushion::solver::petsc
