#pragma once
/// The increment loop shared by the time-stepping steps (static and visco: QuasiStaticStep,
/// dynamic: DynamicStep). Per attempt the step builds its EquilibriumProblem (IncrementStepper);
/// the loop runs the optional linearised predictor and Newton, the augmented-Lagrangian re-solves
/// of the contributors (contact), then either writes the frame, commits the material state and the
/// contributors and advances the AnalysisContext, or reverts them and cuts the increment back.
/// It never accepts an unconverged increment: after the allowed cut-backs it throws AnalysisError.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/analysis/increment_control.hpp"
#include "solver/analysis/step.hpp"

namespace cushion::solver {

/// One attempt of an increment, built by the step.
struct IncrementAttempt {
  std::unique_ptr<EquilibriumProblem> problem;  ///< residual and tangent over the increment
  Eigen::VectorXd x;                 ///< start iterate on the free DOFs [mm]
  double prescribed_increment = 0.0; ///< largest change of a constrained DOF over the increment [mm]
  double dt_material = 0.0;          ///< time increment the materials see [s]
  bool predict = false;              ///< run EquilibriumProblem::predict before Newton
  /// A second start iterate [mm], tried once when a material point fails at x before any correction (e.g.
  /// the Newmark predictor of a sudden load overshooting; dynamic steps retry from the last displacement).
  std::optional<Eigen::VectorXd> fallback_x;
};

/// What a time-stepping step adds to the shared loop.
class IncrementStepper {
 public:
  virtual ~IncrementStepper() = default;
  /// The attempt over step times [t_begin, t_end] [s] from the committed state of the context.
  virtual IncrementAttempt begin_attempt(double t_begin, double t_end) = 0;
  /// A converged attempt (trial state still current, nothing committed): the full vector of support
  /// forces [N] recorded in the history and the frame (reactions at the constrained DOFs).
  virtual Eigen::VectorXd converged(const EquilibriumProblem& problem) = 0;
  /// Extra point fields of the frame of the converged attempt (after converged()).
  virtual void add_frame_fields(FrameData& frame) const {}
  /// After the commit: the context holds the new state (u, f_int, time).
  virtual void committed() {}
  /// Appended to the progress line of a converged increment.
  virtual std::string progress_note() const { return {}; }
};

/// Forwards to an EquilibriumProblem and counts its element loops in SolverStats.
class TimedProblem final : public NonlinearProblem {
 public:
  TimedProblem(EquilibriumProblem& inner, SolverStats& stats) : inner_(inner), stats_(stats) {}
  std::size_t size() const override { return inner_.size(); }
  ProblemEvaluation evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) override;
  const Eigen::SparseMatrix<double>& tangent() const override { return inner_.tangent(); }

 private:
  EquilibriumProblem& inner_;
  SolverStats& stats_;
};

/// The steps' increments from step time 0 to the step period: `system` is the step's assembler and
/// linear solver, `contributors` its extra equilibrium terms, `corner_times` step times [s] the
/// increments must hit (amplitude corners; frame times are added here). Newton options come from the
/// case's solver block (full or modified Newton, solver.newton). Returns the increment control for
/// the step's closing log line. Throws AnalysisError (no convergence, too many increments, a
/// contributor that cannot be satisfied) and Interrupted (Ctrl-C, after a complete frame).
IncrementControl run_increment_loop(AnalysisContext& ctx, const StepSpec& step, System& system,
                                    const std::vector<std::shared_ptr<ResidualContributor>>& contributors,
                                    const std::vector<double>& corner_times, IncrementStepper& stepper);

}  // namespace cushion::solver
