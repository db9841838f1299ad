#pragma once
/// What the steps of an analysis share and carry from one step to the next: the model state
/// (displacements, reactions, material state, total time), one assembler + linear solver per
/// distinct set of constrained DOFs, the output, the log and the cost counters.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <vector>

#include "solver/analysis/analysis_output.hpp"
#include "solver/assembler.hpp"
#include "solver/case/case_spec.hpp"
#include "solver/linear_solver.hpp"

namespace cushion::solver {

class ResidualContributor;  // step.hpp

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

/// A linear solver that forwards to another and adds its costs to SolverStats.
class TimedLinearSolver final : public LinearSolver {
 public:
  TimedLinearSolver(std::unique_ptr<LinearSolver> inner, SolverStats& stats) : inner_(std::move(inner)), stats_(stats) {}
  void factorize(const Eigen::SparseMatrix<double>& A) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  std::string method() const override { return inner_->method(); }
  int analyses() const override { return inner_->analyses(); }
  std::string analysis_report() const override { return inner_->analysis_report(); }

 private:
  std::unique_ptr<LinearSolver> inner_;
  SolverStats& stats_;
};

/// Assembler and linear solver for one set of constrained DOFs (the sparsity pattern and the
/// symbolic factorization depend on it). Steps with the same constraints share one System, so
/// the symbolic analysis is done once for all of them.
struct System {
  std::vector<bool> constrained;  ///< 3 per node
  std::unique_ptr<Assembler> assembler;
  std::unique_ptr<LinearSolver> linear;  ///< a TimedLinearSolver
};

/// Shared state of a running analysis. Owned by run_analysis; steps read and advance it.
class AnalysisContext {
 public:
  /// `mesh` and `spec` must outlive the context. Sections: one per material (here: the case's).
  AnalysisContext(const mesh::Mesh& mesh, const CaseSpec& spec, std::vector<Section> sections,
                  LinearSolverKind linear_kind, unsigned threads, AnalysisOutput& output, std::ostream& log,
                  std::ostream* progress);

  /// The System of a constraint set (built on first use; the material state is shared by all).
  System& system(const std::vector<bool>& constrained);
  /// All systems built so far (for the summary).
  const std::vector<std::unique_ptr<System>>& systems() const { return systems_; }

  const mesh::Mesh& mesh;
  const CaseSpec& spec;
  AnalysisOutput& output;
  std::ostream& log;        ///< per-iteration log (solver.log)
  std::ostream* progress;   ///< one line per increment, or nullptr (quiet)
  SolverStats stats;

  // --- the model state carried from step to step (end of the last converged increment) ---
  Eigen::VectorXd u;                 ///< full displacements [mm]
  Eigen::VectorXd f_int;             ///< full internal forces [N] = reactions at constrained DOFs
  std::vector<bool> constrained;     ///< constrained DOFs of the last step (all false before the first)
  StateStore state;                  ///< committed material state of every point
  double time = 0.0;                 ///< total time [s]
  /// Full velocities [mm/s] at the end of a dynamic step, for a directly following dynamic step
  /// (steady_state steps leave them; static and visco steps end at rest: empty).
  Eigen::VectorXd v;
  /// Extra equilibrium terms that persist from step to step (e.g. contact, by "contact:<name>").
  std::map<std::string, std::shared_ptr<ResidualContributor>> contributors;

  /// Seconds since the context was created.
  double elapsed() const;

 private:
  std::vector<Section> sections_;
  LinearSolverKind linear_kind_;
  unsigned threads_;
  std::vector<std::unique_ptr<System>> systems_;
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
