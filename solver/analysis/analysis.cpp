#include "solver/analysis/analysis.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "io/input_error.hpp"
#include "solver/analysis/boundary.hpp"
#include "solver/analysis/contact_contributor.hpp"
#include "solver/analysis/pressure_contributor.hpp"
#ifdef CUSHION_HAVE_PETSC
#include "solver/petsc/petsc_solver.hpp"
#endif

namespace cushion::solver {

namespace {

/// The PETSc solver with the case's options, checked now (before anything is written).
LinearSolverFactory petsc_solver_factory(const CaseSpec& spec, bool symmetric,
                                         std::shared_ptr<const Distribution> distribution) {
#ifdef CUSHION_HAVE_PETSC
  const std::string problem = petsc::options_problem(symmetric, spec.solver.petsc_options);
  if (!problem.empty()) throw InputError(spec.file.string() + ": solver.petsc_options: " + problem);
  return [symmetric, options = spec.solver.petsc_options, distribution] {
    return petsc::make_solver(symmetric, options, distribution);
  };
#else
  throw InputError(spec.file.string() +
                   ": solver.linear_solver: \"petsc\" is not available: this cushion was built without PETSc "
                   "(install libpetsc-real-dev, e.g. with tools/deps.sh, and configure again)");
#endif
}

/// The case's linear solver, checked against its tangent (and, for PETSc, the options and the build).
/// A distributed run needs PETSc (the direct solvers take whole matrices on one process).
LinearSolverFactory linear_solver_factory(const CaseSpec& spec, std::shared_ptr<const Distribution> distribution) {
  if (distribution && spec.solver.linear_solver != SolverSpec::LinearSolver::petsc)
    throw InputError(spec.file.string() + ": solver.linear_solver: a run on " + std::to_string(distribution->size()) +
                     " MPI processes needs \"petsc\" (CHOLMOD and UMFPACK run on one process)");
  // F-bar, frictional contact and follower pressure tangents are unsymmetric.
  const bool fbar = spec.mesh.formulation == HexFormulation::fbar || case_has_friction(spec) || case_has_pressure(spec);
  auto direct = [](LinearSolverKind kind) -> LinearSolverFactory { return [kind] { return make_linear_solver(kind); }; };
  switch (spec.solver.linear_solver) {
    case SolverSpec::LinearSolver::cholmod:
      if (fbar)
        throw InputError(spec.file.string() +
                         ": solver.linear_solver: \"cholmod\" needs a symmetric tangent; F-bar and frictional "
                         "contact tangents are unsymmetric (use \"auto\" or \"umfpack\")");
      return direct(LinearSolverKind::cholesky);
    case SolverSpec::LinearSolver::umfpack: return direct(LinearSolverKind::lu);
    case SolverSpec::LinearSolver::petsc: return petsc_solver_factory(spec, !fbar, std::move(distribution));
    case SolverSpec::LinearSolver::automatic: break;
  }
  return direct(fbar ? LinearSolverKind::lu : LinearSolverKind::cholesky_or_lu);
}

/// With PETSc, iterative sweeps precondition with the case's PETSc solver on each process alone (the
/// frequencies are divided between the processes); otherwise with CHOLMOD (empty).
LinearSolverFactory sweep_preconditioner_factory(const CaseSpec& spec) {
  if (spec.solver.linear_solver != SolverSpec::LinearSolver::petsc) return nullptr;
  return linear_solver_factory(spec, nullptr);
}

std::vector<Section> case_sections(const LoadedCase& loaded) {
  Section s;
  s.name = loaded.material.spec.name;
  s.material = loaded.material.model;
  s.formulation = loaded.spec.mesh.formulation == HexFormulation::fbar ? Formulation::fbar : Formulation::full;
  s.density = loaded.material.spec.density;
  for (std::size_t e = 0; e < loaded.mesh.num_elements(); ++e) s.elements.push_back(static_cast<int>(e));
  return {s};
}

/// Frame and history row of the undeformed state at t = 0, from the first step's system.
void write_initial_output(AnalysisContext& ctx, const System& system) {
  ModelState& model = ctx.model();
  std::vector<PointOutput> points;
  Eigen::VectorXd f;
  system.assembler->assemble(model.u, model.u, 0.0, model.material, f, nullptr, &points);
  ctx.output().write_frame(make_frame(0.0, *system.assembler, points, model.material, model.u, f));
  model.material.revert();
  ctx.output().write_history(0.0, model.u, f, system.assembler->dofs());
}

}  // namespace

double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return 0.0;
}

RunSummary run_analysis(const LoadedCase& loaded, const RunOptions& options) {
  const CaseSpec& spec = loaded.spec;
  LinearSolverFactory make_linear = linear_solver_factory(spec, options.distribution);
  check_contacts_before_run(loaded);
  if (options.prepare_output) options.prepare_output();
  const int threads_wanted = options.threads >= 0 ? options.threads : spec.solver.threads;
  const unsigned threads = threads_wanted > 0 ? static_cast<unsigned>(threads_wanted)
                                              : std::max(1u, std::thread::hardware_concurrency());

  const bool writes = !options.distribution || options.distribution->rank() == 0;
  AnalysisOutput output(spec, loaded.mesh, options.output_dir, writes);
  const std::filesystem::path log_file = options.output_dir / "solver.log";
  std::ofstream log;  // left closed on the processes that write nothing: what they log is dropped
  if (writes) log.open(log_file);
  if (writes && !log) throw std::runtime_error("cannot write " + log_file.string());
  log << "cushion run " << spec.file.string() << "\nmaterial: " << loaded.material.model->describe() << "\n";
  AnalysisContext ctx(loaded.mesh, spec, case_sections(loaded), std::move(make_linear), threads, output, log,
                      options.progress, options.distribution, sweep_preconditioner_factory(spec));
  if (options.distribution)
    log << "distributed over " << options.distribution->size() << " processes (this log: process 0)\n";

  std::vector<std::unique_ptr<Step>> steps;
  for (const StepSpec& s : spec.steps) steps.push_back(make_step(s));
  write_initial_output(ctx, ctx.system(constrained_mask(loaded.mesh, spec.steps.front())));
  for (auto& step : steps) {
    ctx.report_progress("step '" + step->spec().name + "'");
    step->run(ctx);
    log.flush();
  }

  RunSummary summary;
  summary.nodes = loaded.mesh.num_nodes();
  summary.elements = loaded.mesh.num_elements();
  for (const auto& s : ctx.systems()) {
    if (s->assembler->dofs().num_free() >= summary.free_dofs) {
      summary.free_dofs = s->assembler->dofs().num_free();
      summary.nonzeros = static_cast<std::size_t>(s->assembler->make_matrix().nonZeros());
    }
    summary.symbolic_analyses += s->linear->analyses();
    if (!s->linear->analysis_report().empty())
      log << "linear solver (" << s->assembler->dofs().num_free() << " free dofs): " << s->linear->analysis_report()
          << "\n";
    if (!s->linear->method().empty()) summary.linear_method = s->linear->method();
  }
  summary.steps = static_cast<int>(steps.size());
  summary.stats = ctx.stats();
  summary.threads = threads;
  summary.wall_time = ctx.elapsed();
  summary.peak_memory_mb = peak_memory_mb();
  summary.frames = output.frame_count();
  summary.pvd_file = output.pvd_file();
  summary.history_file = output.history_file();
  summary.log_file = log_file;
  log << format_summary(summary);
  return summary;
}

std::string format_summary(const RunSummary& s) {
  const SolverStats& st = s.stats;
  char text[1600];
  const double per_element = st.assemblies ? st.assembly_time / (double(st.assemblies) * double(s.elements)) : 0.0;
  std::snprintf(text, sizeof text,
                "summary: %d steps, %d increments, %d cut-backs, %d Newton iterations, wall time %.3f s\n"
                "  model: %zu nodes, %zu elements, %zu free dofs, %zu nonzeros, %u threads\n"
                "  assembly: %d element loops, %.3f s, %.3g us per element\n"
                "  linear solver: %s, %d factorizations, %.3f s (%.3g s each), %d symbolic analyses, solves %.3f s\n"
                "  peak memory: %.1f MiB\n"
                "  output: %s (%zu frames), %s, %s\n",
                s.steps, st.increments, st.cutbacks, st.iterations, s.wall_time, s.nodes, s.elements, s.free_dofs,
                s.nonzeros, s.threads, st.assemblies, st.assembly_time, 1e6 * per_element,
                s.linear_method.empty() ? "none" : s.linear_method.c_str(), st.factorizations,
                st.factorization_time, st.factorizations ? st.factorization_time / st.factorizations : 0.0,
                s.symbolic_analyses, st.solve_time, s.peak_memory_mb, s.pvd_file.string().c_str(), s.frames,
                s.history_file.string().c_str(), s.log_file.string().c_str());
  return text;
}

}  // namespace cushion::solver
