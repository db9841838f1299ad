#pragma once
/// Quasi-static equilibrium over one increment as a NonlinearProblem on the free DOFs:
///   r(x) = f_int(u) + sum of extra terms - f_ext  [N],  u = x on free DOFs, prescribed on constrained.
/// Extra terms (contact, pressure, inertia ...) add their residual and tangent on the full/free DOFs.
#include <functional>

#include "solver/assembler.hpp"
#include "solver/newton.hpp"

namespace cushion::solver {

/// An additional term: adds to r_full (full DOF vector [N]) and, if K is non-null, to the free-DOF
/// tangent K [N/mm] (within the assembler's pattern), evaluated at the full displacement u [mm].
using ExtraTerm = std::function<void(const Eigen::VectorXd& u, Eigen::VectorXd& r_full, SparseMatrix* K)>;

class EquilibriumProblem final : public NonlinearProblem {
 public:
  /// u_old: full displacements at the start of the increment [mm]; u_new: full vector whose
  /// constrained entries hold the prescribed values at the end [mm]; f_ext: full external forces at
  /// the end [N]; dt [s] (vectors are copied). `assembler` and `state` must outlive the problem.
  EquilibriumProblem(const Assembler& assembler, StateStore& state, const Eigen::VectorXd& u_old,
                     const Eigen::VectorXd& u_new, const Eigen::VectorXd& f_ext, double dt);

  void add_term(ExtraTerm term) { terms_.push_back(std::move(term)); }

  std::size_t size() const override { return assembler_.dofs().num_free(); }
  /// Residual at free displacements x [mm]; the force scale is the mean |f| over the DOFs carrying
  /// external load or reaction (non-zero entries).
  ProblemEvaluation evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) override;
  const SparseMatrix& tangent() const override { return K_; }

  /// Linearised predictor of the prescribed-displacement increment: at u_start (free entries x,
  /// constrained entries at u_old) solves K_ff dx = -(r_free + K_fc du_c), du_c = prescribed
  /// increment [mm], and adds dx to x [mm]. Keeps elements from inverting when a large boundary
  /// increment is imposed on one layer. Nothing is factorized or solved when the right-hand side is
  /// negligible: max|rhs| <= negligible_predictor_residual * q_p, q_p = max(force scale at u_start,
  /// mean of the non-zero entries of |K_fc| |du_c|) [N] (e.g. a homogeneous deformation the
  /// boundary already imposes exactly). `reuse`: with tangent reuse (modified Newton), solve with
  /// the held factorization if current, else factorize K_ff and record it; nullptr: always factorize.
  /// Throws SingularMatrixError; on material failure returns the failed evaluation and leaves x
  /// unchanged.
  ProblemEvaluation predict(Eigen::VectorXd& x, LinearSolver& linear, TangentFactor* reuse = nullptr);

  /// Relative size of a predictor right-hand side treated as zero [-] (as NewtonOptions'
  /// zero_residual_tolerance: Newton would accept such a start point without correction).
  static constexpr double negligible_predictor_residual = 1e-10;
  /// True if the last predict() factorized or solved (false: right-hand side negligible).
  bool predictor_solved() const { return predictor_solved_; }

  /// Full displacement vector of the last evaluation [mm].
  const Eigen::VectorXd& u() const { return u_; }
  /// Full internal force vector of the last evaluation [N] (reactions at constrained DOFs).
  const Eigen::VectorXd& f_int() const { return f_int_; }
  /// Status of the last assembly (failed element, message).
  const AssemblyStatus& last_status() const { return status_; }

 private:
  const Assembler& assembler_;
  StateStore& state_;
  Eigen::VectorXd u_old_;
  Eigen::VectorXd f_ext_;
  double dt_;
  std::vector<ExtraTerm> terms_;
  ProblemEvaluation summarize() const;

  Eigen::VectorXd u_, f_int_, r_full_;
  SparseMatrix K_, K_fc_;
  AssemblyStatus status_;
  bool predictor_solved_ = false;
};

}  // namespace cushion::solver
