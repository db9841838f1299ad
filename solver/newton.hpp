#pragma once
/// Newton-Raphson driver with backtracking line search. It sees only a NonlinearProblem: a residual
/// r(x) [N] and its tangent dr/dx [N/mm] on the free unknowns x [mm]. It never reports convergence
/// it has not reached: the outcome is converged, diverged, failed (material failure at every trial
/// point), singular (tangent not factorizable) or linear_solve_failed (an iterative linear solver did
/// not converge); x then holds the last iterate and the caller reverts its state.
///
/// Convergence (ABAQUS-like): after at least one correction, both
///   max|r| <= residual_tolerance * q, q = max(reference_force, current force scale, force_floor), and
///   max|c| <= correction_tolerance * max(max|x - x0| + prescribed_increment, displacement_floor),
/// or max|r| <= zero_residual_tolerance * q at any iteration (nothing left to correct), or, if
/// energy_tolerance > 0, |c_k . r_k-1| <= energy_tolerance * |c_1 . r_0|.
///
/// Tangent (default: full Newton): every correction factorizes the tangent at the current iterate,
/// and nothing is factorized when the start point already passes the tests. With
/// NewtonOptions::tangent_reuse (modified Newton) a factorization is kept across iterations and
/// increments while it contracts the residual well (||r_k||_2 <= max_contraction ||r_k-1||_2 with a
/// full step); after a slow or growing step, or any unconverged outcome (the caller then cuts back),
/// the next correction factorizes the current tangent again. A correction with a reused factorization
/// that the line search cannot take in full (a shorter step, no sufficient decrease, or material
/// failure such as J <= 0 at every trial point) is discarded and the iteration redone with the tangent
/// at the current iterate (the standard fallback; logged "K new (reused K failed the line search)").
/// Same convergence tests, linear instead of quadratic rate, far fewer factorizations when they
/// dominate the cost.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Sparse>

#include "material/material.hpp"
#include "solver/linear_solver.hpp"

namespace cushion::solver {

/// Result of evaluating the problem at one x.
struct ProblemEvaluation {
  material::Status status = material::Status::ok;  ///< failed: r is meaningless at this x
  double dt_factor = 1.0;                          ///< smallest proposal of the material points
  double force_scale = 0.0;                        ///< typical force magnitude at x [N] (ABAQUS q)
  std::string message;
};

/// A square nonlinear system r(x) = 0 on free unknowns.
class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  /// Number of unknowns.
  virtual std::size_t size() const = 0;
  /// Residual r(x) [N] into r (resized); if want_tangent, also the tangent returned by tangent().
  virtual ProblemEvaluation evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) = 0;
  /// dr/dx [N/mm] from the last evaluate() with want_tangent (compressed column-major).
  virtual const Eigen::SparseMatrix<double>& tangent() const = 0;
};

/// How a Newton solve ended (only `converged` means r(x) = 0 was reached). linear_solve_failed: an
/// iterative linear solver did not converge (LinearSolveError).
enum class NewtonOutcome { converged, diverged, failed, singular, linear_solve_failed };
/// "converged", "diverged", "failed", "singular" or "linear solve failed".
std::string to_string(NewtonOutcome outcome);

/// Modified Newton: when to keep the factorization of an earlier tangent.
struct TangentReuse {
  bool enabled = false;           ///< false: full Newton (a new factorization for every correction)
  double max_contraction = 0.5;   ///< reused factor kept while ||r_k||_2 / ||r_k-1||_2 <= this [-]
};

/// The factorization a LinearSolver holds between solves, for tangent reuse across increments.
/// Owned by the caller next to its LinearSolver and passed to every solve that uses that solver;
/// set `current = false` if anything else factorizes with the solver in between.
struct TangentFactor {
  bool current = false;  ///< the solver holds a usable factorization of an earlier tangent
  int uses = 0;          ///< corrections solved with it so far
};

/// Tolerances and limits (defaults after ABAQUS: R_n = 5e-3, C_n = 1e-2, 16 iterations).
struct NewtonOptions {
  int max_iterations = 16;                 ///< corrections before giving up (diverged)
  double residual_tolerance = 5e-3;        ///< R_n: max|r| relative to the force scale q [-]
  double force_floor = 1e-8;               ///< lower bound of q for zero-force problems [N]
  double reference_force = 0.0;            ///< time-averaged force of the step so far [N] (caller)
  double zero_residual_tolerance = 1e-10;  ///< max|r| <= this * q converges without correction check [-]
  double correction_tolerance = 1e-2;      ///< C_n: max|c| relative to the largest increment [-]
  double displacement_floor = 1e-12;       ///< lower bound of the increment scale [mm]
  double prescribed_increment = 0.0;       ///< increment Newton cannot see (prescribed DOFs, predictor) [mm]
  double energy_tolerance = 0.0;           ///< > 0 enables the energy criterion [-]
  bool line_search = true;                 ///< backtracking on ||r||_2 (false: full steps)
  int max_line_search = 6;                 ///< backtracking steps per iteration
  double min_step = 1.0 / 32.0;            ///< smallest line-search factor [-]
  int divergence_iterations = 2;           ///< residual growing this many iterations in a row with a new
                                           ///< tangent each: diverged (growth with a reused one refactorizes)
  TangentReuse tangent_reuse;              ///< modified Newton (off: full Newton)
};

/// One iteration of the log.
struct NewtonIterate {
  int iteration = 0;             ///< 0: initial residual, k: after the k-th correction
  double residual_max = 0.0;     ///< max|r| [N]
  double residual_norm = 0.0;    ///< ||r||_2 [N]
  double correction_max = 0.0;   ///< max|c| of the applied (scaled) correction [mm]
  double line_search = 1.0;      ///< accepted line-search factor [-]
  double force_scale = 0.0;      ///< q used in the residual test [N]
  bool new_tangent = false;      ///< the correction used a new factorization (false: reused, or k = 0)
  bool refreshed = false;        ///< ... because the reused one failed the line search (modified Newton)
};

/// One log line: "iter 3  |r|max 1.2e-04 N  |r|2 ...  |c|max ... mm  step 1.000  K new" (K: the
/// tangent of the correction, "new", "reused" or "new (reused K failed the line search)"; absent at
/// iteration 0).
std::string format_iterate(const NewtonIterate& it);

/// Outcome, iteration count and log of one solve.
struct NewtonResult {
  NewtonOutcome outcome = NewtonOutcome::diverged;
  int iterations = 0;      ///< corrections applied
  int tangent_refreshes = 0;  ///< modified Newton: iterations redone with a new tangent (reused one failed)
  double dt_factor = 1.0;  ///< smallest material proposal seen at accepted iterates
  std::string message;     ///< why, when not converged
  std::vector<NewtonIterate> history;
  /// True only if the convergence tests were met.
  bool converged() const { return outcome == NewtonOutcome::converged; }
};

/// Solves r(x) = 0 from x (in: start, out: last iterate) with the given linear solver (kept by the
/// caller so its symbolic analysis is reused across increments). `log` is called once per iterate.
/// `factor`: with tangent reuse, the record of what `linear` holds (kept across increments by the
/// caller; nullptr: reuse only within this solve). Ignored by full Newton.
NewtonResult solve_newton(NonlinearProblem& problem, LinearSolver& linear, Eigen::VectorXd& x,
                          const NewtonOptions& options = {},
                          const std::function<void(const NewtonIterate&)>& log = {},
                          TangentFactor* factor = nullptr);

}  // namespace cushion::solver
