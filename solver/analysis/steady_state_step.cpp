// The steady-state sweep step: checks, linearisation about the carried state, frequencies on up to
// 2 threads (one SteadyStateSolver, i.e. one complex LU, per thread), then the sweep CSV and frames.
#include "solver/analysis/steady_state_step.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "material/input_error.hpp"
#include "solver/dynamics/sweep.hpp"

namespace cushion::solver {

namespace {

using namespace dynamics;

/// Nodes of a set named by a step entry; InputError "case: key.set: ..." if missing or empty.
const std::vector<int>& set_nodes(const AnalysisContext& ctx, const std::string& set, const std::string& key) {
  const auto it = ctx.mesh.node_sets.find(set);
  if (it == ctx.mesh.node_sets.end())
    throw InputError(ctx.spec.file.string() + ": " + key + ": set \"" + set + "\" does not exist in the mesh");
  if (it->second.empty())
    throw InputError(ctx.spec.file.string() + ": " + key + ": set \"" + set + "\" has no nodes");
  return it->second;
}

std::vector<int> component_dofs(const std::vector<int>& nodes, int c) {
  std::vector<int> d;
  for (int n : nodes) d.push_back(DofMap::dof(n, c));
  return d;
}

}  // namespace

void SteadyStateStep::run(AnalysisContext& ctx) {
  const SteadyStateSpec& s = spec_.steady_state;
  const std::string where = ctx.spec.file.string() + ": " + s.key;
  // --- input checks, before anything is computed or written ---
  if (!ctx.contributors.empty())
    throw InputError(where + ": the base state has contact (\"" + ctx.contributors.begin()->first +
                     "\"), which the steady-state step does not linearise yet; model the indenter as prescribed "
                     "displacements of the nodes under it (held in the sweep)");
  const System& system = ctx.system(ctx.constrained);
  const Assembler& assembler = *system.assembler;
  for (const Section& section : assembler.sections())
    if (!(section.density > 0.0))
      throw InputError(where + ": the material \"" + section.name + "\" has no mass density (give density_kg_m3 in " +
                       ctx.spec.material_file.string() + ")");
  const int c = s.excitation.dofs[0] ? 0 : s.excitation.dofs[1] ? 1 : 2;
  Excitation excitation;
  excitation.driven = component_dofs(set_nodes(ctx, s.excitation.set, s.excitation.key + ".set"), c);
  std::vector<bool> driven(3 * ctx.mesh.num_nodes(), false), held(driven.size(), false);
  for (int d : excitation.driven) driven[d] = true;
  std::vector<int> held_c;  // held DOFs in the excitation's component
  for (const SetDofs& h : s.held)
    for (int k = 0; k < 3; ++k)
      if (h.dofs[k])
        for (int d : component_dofs(set_nodes(ctx, h.set, h.key + ".set"), k))
          if (!driven[d] && !held[d]) {
            held[d] = true;
            excitation.held.push_back(d);
            if (k == c) held_c.push_back(d);
          }
  const bool measure_driven = s.measure == s.excitation.set;
  std::vector<int> measured = component_dofs(set_nodes(ctx, s.measure, s.key + ".measure"), c);
  if (!measure_driven)
    measured.erase(std::remove_if(measured.begin(), measured.end(), [&](int d) { return !held[d]; }), measured.end());
  const std::vector<DofGroup> groups{{"indenter", measured}, {"base", measure_driven ? held_c : excitation.driven}};
  const Measure measure = measure_driven ? Measure::indenter_driven : Measure::indenter_held;
  const NominalGeometry geometry{s.area, s.thickness};
  const Damping damping{s.alpha, s.beta, s.structural};

  // --- linearisation about the carried (committed) state ---
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  std::unique_ptr<LinearisedSystem> linearised;
  try {
    auto points = base_point_states(assembler, ctx.state, ctx.u,
                                    s.relaxed_base ? BaseStress::relaxed : BaseStress::as_left);
    linearised = std::make_unique<LinearisedSystem>(ctx.mesh, assembler.sections(), std::move(points), ctx.u);
  } catch (const std::runtime_error& e) {
    throw AnalysisError("step '" + spec_.name + "': cannot linearise the base state: " + e.what());
  }
  HarmonicModel model;
  model.system = linearised.get();
  const double setup = seconds();
  ctx.log << "step '" << spec_.name << "' (steady_state, " << s.frequencies.size() << " frequencies, "
          << (s.relaxed_base ? "relaxed" : "as-left") << " base stress, alpha = " << s.alpha
          << " 1/s, beta = " << s.beta << " s, structural = " << s.structural << ") about t = " << ctx.time
          << " s; linearisation " << setup << " s\n";

  // --- the sweep: frequency k on thread k % threads, each thread with its own complex LU ---
  const std::size_t nf = s.frequencies.size();
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>({2, nf, std::max(1u, std::thread::hardware_concurrency())}));
  std::vector<FrequencyResponse> responses(nf);
  std::vector<double> solve_time(nf, 0.0);
  std::mutex report;
  std::exception_ptr failure;
  auto work = [&](unsigned t) {
    try {
      SteadyStateSolver solver(model, damping, excitation, groups);
      for (std::size_t k = t; k < nf; k += threads) {
        {
          const std::lock_guard<std::mutex> lock(report);
          if (failure) return;
        }
        const double f = s.frequencies[k];
        const double U = s.from_acceleration
                             ? displacement_amplitude(s.acceleration,
                                                      s.peak_to_peak ? AccelerationReading::peak_to_peak
                                                                     : AccelerationReading::peak, f)
                             : s.displacement;
        const auto f0 = std::chrono::steady_clock::now();
        responses[k] = solver.solve(f, U);
        solve_time[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count();
        const SweepRow row = make_row(responses[k], measure, geometry);
        char line[256];
        std::snprintf(line, sizeof line, "%-10s f = %8.4g Hz  U = %.4e mm  |E*| = %.5g kPa  phase = %7.3f deg  (%.2f s)",
                      spec_.name.c_str(), f, U, 1e3 * std::abs(row.modulus), std::arg(row.stiffness) * 180.0 / M_PI,
                      solve_time[k]);
        const std::lock_guard<std::mutex> lock(report);
        ctx.log << "  " << line << "\n";
        if (ctx.progress) *ctx.progress << line << std::endl;
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(report);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const SingularMatrixError& e) {
      throw AnalysisError("step '" + spec_.name + "': singular dynamic matrix (undamped resonance or an "
                          "unsupported rigid motion: add damping or hold more DOFs): " + std::string(e.what()) +
                          "; no sweep file written");
    } catch (const std::invalid_argument& e) {
      throw InputError(where + ": " + e.what());
    }
  }

  // --- outputs, only after every frequency succeeded ---
  std::vector<SweepRow> rows;
  for (const auto& r : responses) rows.push_back(make_row(r, measure, geometry));
  const std::filesystem::path dir = ctx.output.pvd_file().parent_path();
  char comment[512];
  std::snprintf(comment, sizeof comment,
                "step %s: base state at t = %.6g s (%s stress); set %s excited in %c, %s; measured set %s (%s); "
                "E = (F / %.6g mm^2) / (U / %.6g mm); damping alpha = %.6g 1/s, beta = %.6g s, structural = %.6g",
                spec_.name.c_str(), ctx.time, s.relaxed_base ? "relaxed" : "as-left",
                s.excitation.set.c_str(), "xyz"[c],
                s.from_acceleration ? (s.peak_to_peak ? "acceleration read as peak-to-peak" : "acceleration read as peak")
                                    : "displacement amplitude",
                s.measure.c_str(), measure_driven ? "driven" : "held", s.area, s.thickness, s.alpha, s.beta,
                s.structural);
  write_sweep_csv(dir / (spec_.name + "_sweep.csv"), rows, {comment});
  if (s.vtk) {
    ResultSeries series(dir, spec_.name + "_sweep");
    for (const auto& r : responses) write_frequency_frame(series, ctx.mesh, r);
  }
  double total = 0.0;
  for (double t : solve_time) total += t;
  ctx.log << "step '" << spec_.name << "' done: " << nf << " frequencies on " << threads << " threads, "
          << linearised->num_dofs() << " DOFs, " << total / nf << " s per frequency (thread time), wall "
          << seconds() << " s\n";
}

std::unique_ptr<Step> make_steady_state_step(const StepSpec& spec) { return std::make_unique<SteadyStateStep>(spec); }

}  // namespace cushion::solver
