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
#include "solver/petsc/petsc_session.hpp"
#endif
#include "tools/command.hpp"

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

void run_command(RunCommandOptions o) {
  o.out.inputs = {o.case_file};
  io::check_output_folder(o.out);  // before the mesh is built
  const solver::LoadedCase loaded = load(o);
  o.out.inputs.insert(o.out.inputs.end(), {loaded.spec.material_file, loaded.spec.mesh.inp_file, loaded.spec.mesh.stl.file});
  for (const std::string& warning : loaded.warnings) std::cerr << "cushion: warning: " << warning << "\n";
  solver::RunOptions options;
  options.output_dir = o.out.dir;
  options.threads = o.threads;
  options.progress = o.quiet ? nullptr : &std::cout;
  // After every input check, so that bad input prints its one line and nothing else.
  options.prepare_output = [&o, &loaded] {
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
#endif
  const solver::InterruptGuard guard;
  const solver::RunSummary summary = solver::run_analysis(loaded, options);
  // The summary is printed even with --quiet: it is the result of the run.
  std::cout << solver::format_summary(summary) << std::flush;
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
