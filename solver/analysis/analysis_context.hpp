#pragma once
/// What the steps of an analysis share and carry from one step to the next: the model state
/// (displacements, reactions, material state, total time), one assembler + linear solver per
/// distinct set of constrained DOFs, the contacts, the output, the log and the cost counters.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "solver/analysis/analysis_output.hpp"
#include "solver/assembler.hpp"
#include "solver/case/case_spec.hpp"  // also ContactSpec
#include "solver/linear_solver.hpp"

namespace cushion::solver {

class ContactContributor;  // contact_contributor.hpp

/// Cost counters of a run (times are wall-clock seconds).
struct SolverStats {
  int increments = 0;            ///< converged increments
  int cutbacks = 0;              ///< failed attempts
  int iterations = 0;            ///< Newton corrections of converged increments
  int assemblies = 0;            ///< global element loops (residual, tangent, output)
  double assembly_time = 0.0;    ///< [s] in element loops (incl. extra terms)
  int factorizations = 0;        ///< numeric factorizations
  double factorization_time = 0.0;  ///< [s]
  double solve_time = 0.0;       ///< [s] forward/back substitutions
};

/// A linear solver that forwards to another, adds its costs to SolverStats and writes the report of
/// every solve that has one (iterative solvers: the iterations) to the run log.
class TimedLinearSolver final : public LinearSolver {
 public:
  TimedLinearSolver(std::unique_ptr<LinearSolver> inner, SolverStats& stats, std::ostream& log)
      : inner_(std::move(inner)), stats_(stats), log_(log) {}
  void set_geometry(const DofMap& dofs, const std::vector<Eigen::Vector3d>& nodes) override {
    inner_->set_geometry(dofs, nodes);
  }
  void factorize(const Eigen::SparseMatrix<double>& A) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  std::string last_solve_report() const override { return inner_->last_solve_report(); }
  std::string method() const override { return inner_->method(); }
  int analyses() const override { return inner_->analyses(); }
  std::string analysis_report() const override { return inner_->analysis_report(); }

 private:
  std::unique_ptr<LinearSolver> inner_;
  SolverStats& stats_;
  std::ostream& log_;
};

/// Makes the linear solver of a new System (no analysis done yet).
using LinearSolverFactory = std::function<std::unique_ptr<LinearSolver>()>;

/// Assembler and linear solver for one set of constrained DOFs (the sparsity pattern and the
/// symbolic factorization depend on it). Steps with the same constraints share one System, so
/// the symbolic analysis is done once for all of them.
struct System {
  std::vector<bool> constrained;  ///< 3 per node
  std::unique_ptr<Assembler> assembler;
  std::unique_ptr<LinearSolver> linear;  ///< a TimedLinearSolver, its geometry set
};

/// The model state carried from step to step: the end of the last converged increment. Steps read
/// it at their start and advance it; a steady_state step (a linear perturbation) leaves it unchanged.
struct ModelState {
  Eigen::VectorXd u;              ///< full displacements [mm]
  Eigen::VectorXd f_int;          ///< full internal forces [N] = reactions at constrained DOFs
  std::vector<bool> constrained;  ///< constrained DOFs of the last step (all false before the first)
  StateStore material;            ///< committed material state of every point
  double time = 0.0;              ///< total time [s]
  Eigen::VectorXd f_load;         ///< concentrated loads at the end of the last static/visco step [N] (empty: none)
  /// Full velocities [mm/s] at the end of a dynamic step, for a directly following dynamic step
  /// (steady_state steps leave them; static and visco steps end at rest: empty).
  Eigen::VectorXd v;
};

/// Shared state of a running analysis. Owned by run_analysis; steps read and advance it.
///  - inputs and sinks fixed for the run: mesh(), spec(), output(), log(), progress();
///  - the carried model state: model();
///  - what persists across steps besides it: the Systems (system()), the contacts (contact()), the
///    cost counters (stats()).
class AnalysisContext {
 public:
  /// `mesh`, `spec`, `output`, `log` and `*progress` must outlive the context. Sections: one per
  /// material (here: the case's).
  AnalysisContext(const mesh::Mesh& mesh, const CaseSpec& spec, std::vector<Section> sections,
                  LinearSolverFactory make_linear, unsigned threads, AnalysisOutput& output, std::ostream& log,
                  std::ostream* progress, std::shared_ptr<const Distribution> distribution = nullptr,
                  LinearSolverFactory make_sweep_preconditioner = nullptr);

  const mesh::Mesh& mesh() const { return mesh_; }  ///< the model's mesh (reference, mm)
  const CaseSpec& spec() const { return spec_; }     ///< the case being run
  AnalysisOutput& output() { return output_; }       ///< frames and history.csv
  std::ostream& log() { return log_; }               ///< per-iteration log (solver.log)
  std::ostream* progress() { return progress_; }     ///< one line per increment, or nullptr (quiet)
  /// Writes one line to the progress stream, if any (flushed).
  void report_progress(const std::string& line);

  ModelState& model() { return model_; }              ///< the carried model state
  const ModelState& model() const { return model_; }  ///< the carried model state

  SolverStats& stats() { return stats_; }              ///< cost counters of the run
  const SolverStats& stats() const { return stats_; }  ///< cost counters of the run

  /// The System of a constraint set (built on first use; the material state is shared by all).
  System& system(const std::vector<bool>& constrained);
  /// All systems built so far (for the summary).
  const std::vector<std::unique_ptr<System>>& systems() const { return systems_; }

  /// The contact spec.name, created from `spec` (its first step) on first use and kept for the
  /// later steps, so its multipliers and stick points carry over.
  std::shared_ptr<ContactContributor> contact(const ContactSpec& spec);
  /// The contact `name` if a step has used it, else nullptr.
  const ContactContributor* find_contact(const std::string& name) const;

  /// The solver of the real preconditioner of iterative steady-state sweeps on this process alone (the
  /// case's PETSc options), or empty: CHOLMOD (SolveMethod::preconditioner).
  const LinearSolverFactory& sweep_preconditioner() const { return make_sweep_preconditioner_; }
  /// The distribution of a distributed run (its assemblers evaluate this process's elements), or nullptr.
  const Distribution* distribution() const { return distribution_.get(); }

  /// Seconds since the context was created.
  double elapsed() const;

 private:
  const mesh::Mesh& mesh_;
  const CaseSpec& spec_;
  AnalysisOutput& output_;
  std::ostream& log_;
  std::ostream* progress_;
  ModelState model_;
  SolverStats stats_;
  std::vector<Section> sections_;
  LinearSolverFactory make_linear_, make_sweep_preconditioner_;
  unsigned threads_;
  std::shared_ptr<const Distribution> distribution_;
  std::vector<std::unique_ptr<System>> systems_;
  std::map<std::string, std::shared_ptr<ContactContributor>> contacts_;  ///< by contact name
  std::chrono::steady_clock::time_point start_;
};

/// Wall-clock seconds of a callable's execution added to `total`.
template <class F>
auto timed(double& total, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  struct Add {
    double& total;
    std::chrono::steady_clock::time_point t0;
    ~Add() { total += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
  } add{total, t0};
  return f();
}

}  // namespace cushion::solver
