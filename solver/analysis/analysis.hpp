#pragma once
/// The analysis driver behind `cushion run`: builds the model of a loaded case, runs its steps in
/// order with the state carried from step to step, and writes frames, history and a log.
///
/// Boundary conditions between steps. Each step lists all its conditions (nothing is inherited,
/// unlike ABAQUS where conditions persist until modified). The DOFs constrained in a step define its
/// DofMap; steps with the same constrained set share one assembler and linear solver (one symbolic
/// factorization), a step with a different set gets its own (built once, kept for later steps).
///  - A DOF constrained in both steps: its value continues from the end of the previous step (the
///    default linear ramp starts there).
///  - A DOF newly constrained: starts from its current displacement.
///  - A DOF released (constrained before, free now): its reaction at the end of the previous step
///    is applied as an external force that decreases linearly to zero over the step (ABAQUS's
///    treatment of a removed boundary condition), so releasing a loaded support is gradual.
///
/// Outputs in OUTDIR: results.pvd + results_NNNN.vtu (a frame at t = 0, at the steps' frame times
/// and at every step end), history.csv (every converged increment), solver.log (every iteration).
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "solver/analysis/step.hpp"
#include "solver/distribution.hpp"
#include "solver/case/case_file.hpp"

namespace cushion::solver {

/// How to run (the command-line options of `cushion run`).
struct RunOptions {
  std::filesystem::path output_dir = "out";
  int threads = -1;                  ///< element-loop threads; -1: the case's solver.threads (0: all cores)
  std::ostream* progress = nullptr;  ///< one line per increment and the summary; nullptr: silent
  /// Called after the input checks that need no solution and before the first file is written
  /// (`cushion run`: the output-folder policy, io/output_folder.hpp); may throw InputError.
  std::function<void()> prepare_output;
  /// A distributed run (solver/distribution.hpp; every process calls run_analysis with its own): only
  /// process 0 writes files; nullptr: one process.
  std::shared_ptr<const Distribution> distribution;
};

/// Figures of a finished run (times are wall-clock seconds).
struct RunSummary {
  std::size_t nodes = 0, elements = 0;
  std::size_t free_dofs = 0;         ///< of the largest system
  std::size_t nonzeros = 0;          ///< of its stiffness matrix (both triangles stored)
  int steps = 0;
  SolverStats stats;
  int symbolic_analyses = 0;         ///< over all systems
  std::string linear_method;         ///< e.g. "cholmod-llt"
  unsigned threads = 1;
  double wall_time = 0.0;
  double peak_memory_mb = 0.0;       ///< VmHWM of the process [MiB]
  std::size_t frames = 0;
  std::filesystem::path pvd_file, history_file, log_file;
};

/// The summary as printed at the end of `cushion run` (the benchmark script reads these lines).
std::string format_summary(const RunSummary& summary);

/// Runs every step of `loaded` (see the file comment). Throws InputError, before anything is written,
/// for a case the solver cannot build (e.g. cholmod with F-bar) and for contact input that fails
/// check_contacts_before_run; AnalysisError when a step cannot be completed,
/// Interrupted after Ctrl-C (call inside an InterruptGuard); the files written until then are complete.
RunSummary run_analysis(const LoadedCase& loaded, const RunOptions& options);

/// Peak resident memory of this process (VmHWM from /proc/self/status) [MiB]; 0 if unknown.
double peak_memory_mb();

}  // namespace cushion::solver
