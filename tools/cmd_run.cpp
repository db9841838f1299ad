// `cushion run CASE.json|DECK.inp -o OUTDIR`: runs the steps of a case file or an ABAQUS/CalculiX deck
// (solver/deck/deck_reader.hpp) and writes frames for ParaView (OUTDIR/results.pvd), the history table
// (OUTDIR/history.csv), the deck's print tables and the iteration log (OUTDIR/solver.log).
#include <iostream>
#include <memory>
#include <optional>

#include "io/input_error.hpp"
#include "solver/analysis/analysis.hpp"
#include "solver/deck/deck_reader.hpp"
#include "solver/output/interrupt.hpp"
#ifdef CUSHION_HAVE_PETSC
#include "solver/petsc/mpi_distribution.hpp"
#include "solver/petsc/petsc_session.hpp"
#endif
#include "tools/command.hpp"
#include "tools/mpi_launch.hpp"

namespace cushion::tools {

namespace {

struct RunCommandOptions {
  std::string case_file;
  io::OutputFolder out;
  int threads = -1;
  bool quiet = false;
  std::string units;  ///< decks only; empty: mm-N-MPa
};

/// The case of a case file, or of a deck (.inp) in its unit system.
solver::LoadedCase load(const RunCommandOptions& o) {
  if (!solver::is_deck_file(o.case_file)) {
    if (!o.units.empty())
      throw InputError(o.case_file + ": --units: only for ABAQUS/CalculiX decks (.inp); a case file carries its units");
    return solver::load_case(o.case_file);
  }
  return solver::load_deck(o.case_file, solver::deck_units(o.units.empty() ? "mm-N-MPa" : o.units));
}

/// Refuses an mpirun launch that cannot run distributed (the same message on every process).
void check_launch(const solver::LoadedCase& loaded) {
  const int processes = launched_processes();
  if (processes <= 1) return;
#ifndef CUSHION_HAVE_PETSC
  throw InputError("started by mpirun on " + std::to_string(processes) +
                   " processes, but this cushion was built without PETSc and MPI (install libpetsc-real-dev, "
                   "e.g. with tools/deps.sh, and configure again), or run it without mpirun");
#endif
  if (loaded.spec.solver.linear_solver != solver::SolverSpec::LinearSolver::petsc)
    throw InputError(loaded.spec.file.string() + ": solver.linear_solver: a run on " + std::to_string(processes) +
                     " MPI processes needs \"petsc\" (CHOLMOD and UMFPACK run on one process)");
}

/// Runs the analysis; in a distributed run, an error that only this process met (so the others would
/// wait for it forever) stops every process.
solver::RunSummary run_everywhere(const solver::LoadedCase& loaded, const solver::RunOptions& options) {
  if (!options.distribution) return solver::run_analysis(loaded, options);
  try {
    return solver::run_analysis(loaded, options);
  } catch (const InputError&) {
    throw;  // the same on every process (checks of the replicated input)
  } catch (const solver::AnalysisError&) {
    throw;  // decided from reduced, replicated values: the same on every process
  } catch (const solver::Interrupted&) {
    throw;
  } catch (const std::exception& e) {
#ifdef CUSHION_HAVE_PETSC
    std::cerr << "cushion: error on MPI process " << options.distribution->rank() << ": " << e.what()
              << "; stopping every process (frames written so far are complete)" << std::endl;
    solver::petsc::abort_all(1);
#endif
    throw;
  }
}

void run_command(RunCommandOptions o) {
  o.out.inputs = {o.case_file};
  // Before the mesh is built; under mpirun by process 0 only, which alone creates the folder (if the check
  // fails there, mpirun ends the other processes).
  if (launched_rank() == 0) io::check_output_folder(o.out);
  const solver::LoadedCase loaded = load(o);
  check_launch(loaded);
  const bool first = launched_rank() == 0;  // prints and writes
  o.out.inputs.insert(o.out.inputs.end(), {loaded.spec.material_file, loaded.spec.mesh.inp_file, loaded.spec.mesh.stl.file});
  if (first)
    for (const std::string& warning : loaded.warnings) std::cerr << "cushion: warning: " << warning << "\n";
  solver::RunOptions options;
  options.output_dir = o.out.dir;
  options.threads = o.threads;
  options.progress = o.quiet || !first ? nullptr : &std::cout;
  // After every input check, so that bad input prints its one line and nothing else.
  options.prepare_output = [&o, &loaded, first] {
    if (!first) return;
    io::prepare_output_folder(o.out);
    if (!o.quiet)
      std::cout << "cushion run " << o.case_file << ": " << loaded.mesh.num_nodes() << " nodes, "
                << loaded.mesh.num_elements() << " elements, " << loaded.spec.steps.size() << " steps -> "
                << o.out.dir.string() << std::endl;
  };
#ifdef CUSHION_HAVE_PETSC
  // PETSc and MPI live from here to the end of the run, and only for a case that chooses them.
  std::optional<solver::petsc::Session> petsc;
  if (loaded.spec.solver.linear_solver == solver::SolverSpec::LinearSolver::petsc) petsc.emplace();
  if (petsc && solver::petsc::world_size() > 1) options.distribution = solver::petsc::make_distribution(loaded.mesh);
#endif
  const solver::InterruptGuard guard;
  const solver::RunSummary summary = run_everywhere(loaded, options);
  // The summary is printed even with --quiet: it is the result of the run.
  if (first) std::cout << solver::format_summary(summary) << std::flush;
}

const Registrar reg{"run", [](CLI::App& app) {
  auto o = std::make_shared<RunCommandOptions>();
  CLI::App* sub = app.add_subcommand("run", "run the steps of a case file (frames for ParaView, history CSV, log)");
  sub->add_option("case", o->case_file,
                  "case file (JSON, see cases/cube_compression/case.json) or ABAQUS/CalculiX deck (.inp)")
      ->required();
  sub->add_option("--units", o->units,
                  "unit system of a deck (decks carry none): " + solver::deck_unit_names() + " (default mm-N-MPa)");
  add_output_folder_options(sub, o->out, "output folder (created; results.pvd, history.csv, solver.log)");
  o->out.markers = {"solver.log", "results.pvd"};
  sub->add_option("--threads", o->threads, "threads of the element loop (default: the case's solver.threads, 0 = all)")
      ->check(CLI::Range(0, 1024));
  sub->add_flag("--quiet", o->quiet, "no progress lines (the summary is still printed)");
  sub->callback([o] { run_command(*o); });
}};

}  // namespace

}  // namespace cushion::tools
