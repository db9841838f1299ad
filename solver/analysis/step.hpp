#pragma once
/// Steps of an analysis. A Step advances the AnalysisContext (displacements, reactions, material
/// state, total time) from the end of the previous step to its own end and writes its output.
/// New step types (e.g. a steady-state frequency step) implement Step and are created in
/// make_step; extra equilibrium terms (contact, pressure) implement ResidualContributor and are
/// attached to a QuasiStaticStep (contact also to a DynamicStep).
#include <memory>
#include <string>
#include <vector>

#include "solver/analysis/analysis_context.hpp"
#include "solver/equilibrium.hpp"

namespace cushion::solver {

/// One increment attempt, as seen by a ResidualContributor.
struct IncrementInfo {
  const StepSpec* step = nullptr;
  double t_begin = 0.0;  ///< total time at the start of the increment [s]
  double t_end = 0.0;    ///< total time at its end [s]
  double dt = 0.0;       ///< time increment the materials see [s] (0 or long-term in static steps)
};

/// An extra term of the equilibrium of every increment of a step (contact against a rigid
/// platen, pressure loads ...). Per attempt the step calls begin_increment (which adds its
/// ExtraTerm with EquilibriumProblem::add_term; the term may only touch entries inside the
/// assembler's sparsity pattern), runs Newton, then commit() on convergence or revert().
class ResidualContributor {
 public:
  virtual ~ResidualContributor() = default;
  virtual void begin_increment(const IncrementInfo& increment, EquilibriumProblem& problem) = 0;
  /// After a converged Newton solve: true if the term was updated (e.g. augmented-Lagrangian
  /// multipliers) and the increment must be solved again; sets `failure` if it cannot be satisfied.
  virtual bool update_after_solve(std::string& failure) { return false; }
  virtual void commit() {}  ///< accept the trial state of the attempt (e.g. stick points)
  virtual void revert() {}  ///< drop it
  /// Extra arrays for a frame (e.g. contact pressure per node, FrameData::point_fields).
  virtual void add_frame_fields(FrameData& frame) const {}
  /// Set by the increment loop around its predictor evaluation: while true, the term may give its
  /// linear extrapolation from the last converged state (contact: from the last indenter position).
  virtual void set_predicting(bool on) {}
};

/// A step of the analysis.
class Step {
 public:
  virtual ~Step() = default;
  virtual const StepSpec& spec() const = 0;
  /// Runs the step from ctx's state; on return ctx holds the state at the end of the step.
  /// Throws AnalysisError when an increment cannot converge, Interrupted after Ctrl-C.
  virtual void run(AnalysisContext& ctx) = 0;
};

/// A Step that runs one step of the case file: holds its spec (which outlives the step).
class CaseStep : public Step {
 public:
  explicit CaseStep(const StepSpec& spec) : spec_(spec) {}
  const StepSpec& spec() const final { return spec_; }

 protected:
  const StepSpec& spec_;
};

/// Time [s] the materials see in a "static" step with long_term: much longer than any relaxation
/// time, so a Prony series relaxes completely within the increment (H_i -> 0, S = S_inf).
inline constexpr double long_term_dt = 1e20;

/// Quasi-static equilibrium with automatic incrementation: both "static" and "visco" steps.
///  - visco: the materials integrate over the increment's dt (Prony relaxation, ABAQUS *VISCO).
///  - static: rate-independent (ABAQUS *STATIC): the materials see dt = 0, i.e. the instantaneous
///    response with the viscous stresses frozen at their values from the previous step; with
///    long_term they see long_term_dt, i.e. the fully relaxed (long-term) response
///    (*STATIC, LONG TERM). Step time then only drives the amplitudes.
class QuasiStaticStep final : public CaseStep {
 public:
  using CaseStep::CaseStep;
  void run(AnalysisContext& ctx) override;

  /// Adds an extra equilibrium term for every increment of this step.
  void add_contributor(std::shared_ptr<ResidualContributor> c) { contributors_.push_back(std::move(c)); }

 private:
  std::vector<std::shared_ptr<ResidualContributor>> contributors_;
};

/// The Step for a case-file step (static and visco: QuasiStaticStep; dynamic: DynamicStep,
/// dynamic_step.hpp; steady_state: SteadyStateStep, steady_state_step.hpp). The time-stepping steps
/// share one increment loop (increment_loop.hpp).
std::unique_ptr<Step> make_step(const StepSpec& spec);

/// A step could not be completed (no convergence within the allowed cut-backs, too many
/// increments). The message names the step, the time and the reason; frames so far are complete.
class AnalysisError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cushion::solver
