// The steady-state sweep step in four parts: resolve the excitation (checks, indenter roles, DOFs),
// linearise about the carried state, sweep the frequencies on up to 2 threads (one SteadyStateSolver,
// i.e. one complex LU, per thread), then write the sweep CSV and frames.
#include "solver/analysis/steady_state_step.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <mutex>
#include <thread>

#include "io/input_error.hpp"
#include "solver/analysis/contact_contributor.hpp"
#include "solver/analysis/frequency_step.hpp"
#include "io/text_support.hpp"
#include "solver/dynamics/contact_linearisation.hpp"
#include "solver/dynamics/modes.hpp"
#include "solver/dynamics/sweep.hpp"
#include "solver/distribution.hpp"

namespace cushion::solver {

namespace {

using namespace dynamics;

/// Nodes of a set named by a step entry; InputError "case: key.set: ..." if missing or empty.
const std::vector<int>& set_nodes(const AnalysisContext& ctx, const std::string& set, const std::string& key) {
  const auto it = ctx.mesh().node_sets.find(set);
  if (it == ctx.mesh().node_sets.end())
    throw InputError(ctx.spec().file.string() + ": " + key + ": set \"" + set + "\" does not exist in the mesh");
  if (it->second.empty())
    throw InputError(ctx.spec().file.string() + ": " + key + ": set \"" + set + "\" has no nodes");
  return it->second;
}

std::vector<int> component_dofs(const std::vector<int>& nodes, int c) {
  std::vector<int> d;
  for (int n : nodes) d.push_back(DofMap::dof(n, c));
  return d;
}

/// The damping as the log and the CSV header state it.
std::string describe_damping(const SteadyStateSpec& s) {
  char text[160];
  std::snprintf(text, sizeof text, "alpha = %.6g 1/s, beta = %.6g s, structural = %.6g", s.damping.rayleigh_alpha,
                s.damping.rayleigh_beta, s.damping.structural);
  return text;
}

/// A rigid indenter of the base state: its contact, appended DOF, role in the sweep.
struct Indenter {
  std::string name;
  const ContactSet* set = nullptr;
  int dof = -1;  ///< appended DOF (3 nodes + k)
  enum class Role { held, driven, free } role = Role::held;
  double mass = 0.0;  ///< [t], free only
  ContactLinearisation lin;
};

/// The contacts of the base state: those of the last static/visco step before `step` (in order).
std::vector<Indenter> base_state_indenters(const AnalysisContext& ctx, const StepSpec& step) {
  const StepSpec* previous = nullptr;
  for (const StepSpec& s : ctx.spec().steps) {
    if (&s == &step) break;
    if (!s.perturbation()) previous = &s;
  }
  std::vector<Indenter> out;
  if (!previous) return out;
  for (const ContactSpec& c : previous->contact) {
    const ContactContributor* contact = ctx.find_contact(c.name);
    if (!contact) continue;
    Indenter ind;
    ind.name = c.name;
    ind.set = &contact->set();
    ind.dof = static_cast<int>(3 * ctx.mesh().num_nodes() + out.size());
    out.push_back(std::move(ind));
  }
  return out;
}

/// Names of a list of indenters, for messages: "'a', 'b'" or "none".
std::string names(const std::vector<Indenter>& list) {
  std::string s;
  for (const auto& i : list) s += (s.empty() ? "'" : ", '") + i.name + "'";
  return s.empty() ? "none" : s;
}

/// What the step's keys resolve to against the base state (before anything is computed): the
/// excited component, the indenters with their roles and frozen contact, the driven, held and
/// measured DOFs (3 per node, then one per indenter) and the nominal geometry.
struct SweepSetup {
  std::string where;                ///< "<case file>: <step key>", for messages
  int component = 0;                ///< excited component (0, 1, 2: x, y, z)
  std::vector<Indenter> indenters;  ///< of the base state, in order
  int measured_indenter = -1;       ///< index in `indenters`, or -1 when a set is measured
  Excitation excitation;
  std::vector<bool> held;           ///< per DOF
  std::vector<int> held_component;  ///< held DOFs in the excited component
  HarmonicModel model;              ///< all but the linearised system
  Measure measure = Measure::indenter_held;
  std::vector<DofGroup> groups;     ///< {indenter, base} (empty with forces)
  NominalGeometry geometry;
  bool force_mode = false;          ///< excited by harmonic forces (decks), no measure
  std::vector<double> frequencies;  ///< [Hz] the step's, or placed around the resonances at run time

  const Indenter* measured() const { return measured_indenter < 0 ? nullptr : &indenters[measured_indenter]; }
  /// The indenter of a contact named by the key `key` (InputError if not of the base state).
  Indenter& indenter(const std::string& name, const std::string& key) {
    for (Indenter& i : indenters)
      if (i.name == name) return i;
    throw InputError(where + key + ": \"" + name + "\" is not a contact of the base state (contacts of the previous "
                     "step: " + names(indenters) + ")");
  }
};

/// The roles of the indenters (driven, free with a mass, else held) and the measured one.
void assign_roles(const SteadyStateSpec& s, SweepSetup& setup) {
  if (!s.excitation_contact.empty())
    setup.indenter(s.excitation_contact, ".excitation.contact").role = Indenter::Role::driven;
  for (const IndenterMotion& m : s.indenters) {
    Indenter& i = setup.indenter(m.contact, m.key.substr(s.key.size()) + ".contact");
    if (m.free) i.role = Indenter::Role::free, i.mass = m.mass;
  }
  if (!s.measure_contact.empty())
    setup.measured_indenter = static_cast<int>(&setup.indenter(s.measure_contact, ".measure.contact") -
                                               setup.indenters.data());
}

/// Freezes each indenter's contact at the base state along the excited component; a named indenter
/// without closed node is an InputError, a held one only a warning.
void linearise_indenters(AnalysisContext& ctx, const StepSpec& step, SweepSetup& setup) {
  Vec3 e = Vec3::Zero();
  e(setup.component) = 1.0;
  for (Indenter& i : setup.indenters) {
    try {
      i.lin = linearise_contact(ctx.mesh(), *i.set, ctx.model().u, i.dof, e);
    } catch (const std::runtime_error& err) {
      throw AnalysisError("step '" + step.name + "': cannot linearise the contact: " + err.what());
    }
    if (!i.lin.closed.empty()) continue;
    const bool named = i.role != Indenter::Role::held || &i == setup.measured();
    const std::string msg = "contact '" + i.name + "' has no closed node at the base state (t = " +
                            std::to_string(ctx.model().time) + " s, smallest gap " +
                            std::to_string(*std::min_element(i.set->gaps().begin(), i.set->gaps().end())) +
                            " mm): the indenter does not touch the foam";
    if (named)
      throw InputError(setup.where + ": " + msg + ", so the sweep would measure nothing; press it into the foam in "
                       "the previous step");
    ctx.log() << "  warning: step '" << step.name << "': " << msg << " (held, no effect)\n";
  }
}

/// The driven and held DOFs, and the indenters' part of the harmonic model (DOFs, masses, springs).
void resolve_supports(const AnalysisContext& ctx, const SteadyStateSpec& s, SweepSetup& setup) {
  const std::size_t n_all = 3 * ctx.mesh().num_nodes() + setup.indenters.size();
  Excitation& excitation = setup.excitation;
  if (setup.force_mode)
    for (const HarmonicLoad& load : s.loads)
      for (int n : set_nodes(ctx, load.set, load.key)) excitation.force.emplace_back(DofMap::dof(n, load.component), load.force);
  else if (s.excitation_contact.empty())
    excitation.driven = component_dofs(set_nodes(ctx, s.excitation.set, s.excitation.key + ".set"), setup.component);
  else
    excitation.driven = {setup.indenter(s.excitation_contact, "").dof};
  std::vector<bool> driven(n_all, false);
  setup.held.assign(n_all, false);
  for (int d : excitation.driven) driven[d] = true;
  for (const SetDofs& h : s.held)
    for (int k = 0; k < 3; ++k)
      if (h.dofs[k])
        for (int d : component_dofs(set_nodes(ctx, h.set, h.key + ".set"), k))
          if (!driven[d] && !setup.held[d]) {
            setup.held[d] = true;
            excitation.held.push_back(d);
            if (k == setup.component) setup.held_component.push_back(d);
          }
  std::vector<Eigen::Triplet<double>> contact_triplets;
  for (const Indenter& i : setup.indenters) {
    if (i.role == Indenter::Role::held) excitation.held.push_back(i.dof), setup.held[i.dof] = true;
    if (i.role == Indenter::Role::free) setup.model.lumped_mass.emplace_back(i.dof, i.mass);
    contact_triplets.insert(contact_triplets.end(), i.lin.stiffness.begin(), i.lin.stiffness.end());
  }
  setup.model.extra_dofs = static_cast<int>(setup.indenters.size());
  if (!setup.indenters.empty()) {
    setup.model.extra_stiffness.resize(static_cast<Eigen::Index>(n_all), static_cast<Eigen::Index>(n_all));
    setup.model.extra_stiffness.setFromTriplets(contact_triplets.begin(), contact_triplets.end());
  }
}

/// The measured DOFs (an indenter, or a driven or held set), the kind of measure, the DOF groups
/// {indenter, base} and the nominal geometry.
void resolve_measure(const AnalysisContext& ctx, const SteadyStateSpec& s, SweepSetup& setup) {
  if (setup.force_mode) return;
  std::vector<int> measured;
  bool measure_driven = false;
  if (const Indenter* m = setup.measured()) {
    measured = {m->dof};
    measure_driven = m->role == Indenter::Role::driven;
    setup.measure = measure_driven                    ? Measure::indenter_driven
                    : m->role == Indenter::Role::free ? Measure::indenter_free
                                                      : Measure::indenter_held;
  } else {
    measure_driven = s.measure == s.excitation.set && s.excitation_contact.empty();
    measured = component_dofs(set_nodes(ctx, s.measure, s.key + ".measure"), setup.component);
    if (!measure_driven)
      measured.erase(std::remove_if(measured.begin(), measured.end(), [&](int d) { return !setup.held[d]; }),
                     measured.end());
    if (measured.empty())
      throw InputError(setup.where + ".measure: set \"" + s.measure +
                       "\" is neither driven nor held in the excitation's dof");
    setup.measure = measure_driven ? Measure::indenter_driven : Measure::indenter_held;
  }
  setup.groups = {{"indenter", measured}, {"base", measure_driven ? setup.held_component : setup.excitation.driven}};
  setup.geometry = {s.area_from_contact ? setup.measured()->lin.closed_area : s.area, s.thickness};
}

/// Resolves the step's excitation, indenters and measure against the base state; throws InputError
/// (or AnalysisError for a contact that cannot be linearised) before anything is written.
SweepSetup resolve_excitation(AnalysisContext& ctx, const StepSpec& step, const Assembler& assembler) {
  const SteadyStateSpec& s = step.steady_state;
  SweepSetup setup;
  setup.where = ctx.spec().file.string() + ": " + s.key;
  setup.component = s.excitation.dofs[0] ? 0 : s.excitation.dofs[1] ? 1 : 2;
  setup.force_mode = !s.loads.empty();
  setup.frequencies = s.frequencies;
  setup.indenters = base_state_indenters(ctx, step);
  assign_roles(s, setup);
  linearise_indenters(ctx, step, setup);
  resolve_supports(ctx, s, setup);
  resolve_measure(ctx, s, setup);
  return setup;
}

/// The frequencies of resonance_points: the natural frequencies of the free DOFs (neither driven nor held)
/// place them (dynamics::frequency_points).
std::vector<double> resonance_frequencies(const StepSpec& step, const SweepSetup& setup) {
  const ResonancePoints& p = *step.steady_state.resonance_points;
  const LinearisedSystem& system = *setup.model.system;
  std::vector<bool> prescribed = setup.held;
  for (int d : setup.excitation.driven) prescribed[d] = true;
  return frequency_points(p.low, p.high, p.points, p.bias, natural_frequencies_with_held(system, prescribed, step));
}

/// Logs the step's set-up: base state, damping, linearisation time [s] and the indenters.
void log_setup(AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup, double seconds) {
  const SteadyStateSpec& s = step.steady_state;
  ctx.log() << "step '" << step.name << "' (steady_state, " << setup.frequencies.size() << " frequencies, "
            << (s.base_stress == BaseStress::relaxed ? "relaxed" : "as-left") << " base stress, " << describe_damping(s) << ") about t = "
            << ctx.model().time << " s; linearisation " << seconds << " s\n";
  for (const Indenter& i : setup.indenters)
    ctx.log() << "  indenter '" << i.name << "': "
              << (i.role == Indenter::Role::held ? "held" : i.role == Indenter::Role::driven ? "driven" : "free")
              << (i.role == Indenter::Role::free ? ", mass " + std::to_string(1e3 * i.mass) + " kg" : std::string())
              << ", " << i.lin.closed.size() << " closed nodes (frozen normal springs"
              << (i.set->parameters().friction > 0.0 ? ", sticking" : ", sliding freely")
              << " tangentially), closed area " << i.lin.closed_area << " mm^2\n";
}

/// Results of the sweep.
struct SweepResult {
  std::vector<FrequencyResponse> responses;  ///< per frequency
  std::vector<double> solve_time;            ///< per frequency [s] (thread time)
  SolveStats cost;                           ///< summed over the threads
  unsigned threads = 1;
};

/// What the sweep's threads share; `lock` guards the log, `cost` and `failure`.
struct SharedSweep {
  SweepResult result;
  std::mutex lock;
  std::exception_ptr failure;  ///< the first exception of any thread
};

/// Driven displacement amplitude U [mm] at frequency f [Hz].
double drive_amplitude(const SteadyStateSpec& s, double f) {
  if (!s.from_acceleration) return s.displacement;
  return displacement_amplitude(s.acceleration, s.reading, f);
}

/// Process of a distributed run that solves frequency k (0 on one process).
int frequency_owner(const AnalysisContext& ctx, std::size_t k) {
  return ctx.distribution() ? static_cast<int>(k % static_cast<std::size_t>(ctx.distribution()->size())) : 0;
}

/// Solves this process's frequencies (frequency_owner) numbered t, t + threads, ... among them with one
/// SteadyStateSolver (one complex LU) of its own; logs one line per frequency, stops after any
/// thread's failure.
void solve_share(unsigned t, AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup,
                 SharedSweep& shared) {
  const SteadyStateSpec& s = step.steady_state;
  SweepResult& out = shared.result;
  const int rank = ctx.distribution() ? ctx.distribution()->rank() : 0;
  try {
    SteadyStateSolver solver(setup.model, s.damping, setup.excitation, setup.groups,
                             SolveMethod{s.iterative, s.gmres_tolerance, 60, ctx.sweep_preconditioner(), &ctx.mesh().nodes});
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < setup.frequencies.size(); ++k)
      if (frequency_owner(ctx, k) == rank) mine.push_back(k);
    for (std::size_t j = t; j < mine.size(); j += out.threads) {
      const std::size_t k = mine[j];
      {
        const std::lock_guard<std::mutex> lock(shared.lock);
        if (shared.failure) return;
      }
      const double f = setup.frequencies[k], U = setup.force_mode ? 1.0 : drive_amplitude(s, f);
      const auto f0 = std::chrono::steady_clock::now();
      const int iterations = solver.stats().iterations;
      out.responses[k] = solver.solve(f, U);
      out.solve_time[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count();
      char line[256];
      if (setup.force_mode) {
        std::snprintf(line, sizeof line, "%-10s f = %10.6g Hz  max |u| = %.5e mm  (%.2f s, %d iterations)",
                      step.name.c_str(), f, out.responses[k].u.cwiseAbs().maxCoeff(), out.solve_time[k],
                      solver.stats().iterations - iterations);
      } else {
        const SweepRow row = make_row(out.responses[k], setup.measure, setup.geometry);
        std::snprintf(line, sizeof line,
                      "%-10s f = %8.4g Hz  U = %.4e mm  |E*| = %.5g kPa  phase = %7.3f deg  (%.2f s, %d iterations)",
                      step.name.c_str(), f, U, 1e3 * std::abs(row.modulus), std::arg(row.stiffness) * 180.0 / M_PI,
                      out.solve_time[k], solver.stats().iterations - iterations);
      }
      const std::lock_guard<std::mutex> lock(shared.lock);
      ctx.log() << "  " << line << "\n";
      ctx.report_progress(line);
    }
    const SolveStats& c = solver.stats();
    const std::lock_guard<std::mutex> lock(shared.lock);
    out.cost.complex_factorisations += c.complex_factorisations;
    out.cost.real_factorisations += c.real_factorisations;
    out.cost.iterations += c.iterations;
    out.cost.assembly_time += c.assembly_time;
    out.cost.factorisation_time += c.factorisation_time;
    out.cost.solve_time += c.solve_time;
  } catch (...) {
    const std::lock_guard<std::mutex> lock(shared.lock);
    if (!shared.failure) shared.failure = std::current_exception();
  }
}

/// A failure of the sweep as the error the user sees.
[[noreturn]] void rethrow_sweep_failure(const StepSpec& step, const SweepSetup& setup, std::exception_ptr failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const SingularMatrixError& e) {
    throw AnalysisError("step '" + step.name + "': singular dynamic matrix (undamped resonance or an "
                        "unsupported rigid motion: add damping or hold more DOFs): " + std::string(e.what()) +
                        "; no sweep file written");
  } catch (const std::invalid_argument& e) {
    throw InputError(setup.where + ": " + e.what());
  }
}

/// Distributed: if any process failed, every process throws the failure of the first one that did.
void agree_on_failure(const AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup,
                      std::exception_ptr failure, const Distribution& d) {
  std::string message;
  int kind = 0;  // 1: analysis error, 2: input error
  if (failure) {
    try {
      rethrow_sweep_failure(step, setup, failure);
    } catch (const InputError& e) {
      message = e.what(), kind = 2;
    } catch (const std::exception& e) {
      message = e.what(), kind = 1;
    }
  }
  const int root = static_cast<int>(d.min(kind ? d.rank() : d.size()));
  if (root == d.size()) return;
  message = d.broadcast(message, root);
  if (static_cast<int>(d.max(d.rank() == root ? kind : 0)) == 2) throw InputError(message);
  throw AnalysisError(message);
}

/// The sweep: frequency k on process k % processes (frequency_owner) and there on one of up to 2 threads
/// (one with a PETSc preconditioner). A singular dynamic matrix is an
/// AnalysisError, an invalid excitation an InputError (nothing is written then).
SweepResult sweep(AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup) {
  const std::size_t nf = setup.frequencies.size();
  SharedSweep shared;
  // PETSc is not thread-safe: a PETSc preconditioner keeps the sweep on one thread per process.
  const bool petsc = step.steady_state.iterative && ctx.sweep_preconditioner();
  shared.result.threads = petsc ? 1u
                                : static_cast<unsigned>(std::min<std::size_t>(
                                      {2, nf, std::max(1u, std::thread::hardware_concurrency())}));
  shared.result.responses.resize(nf);
  shared.result.solve_time.assign(nf, 0.0);
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < shared.result.threads; ++t)
    pool.emplace_back([&, t] { solve_share(t, ctx, step, setup, shared); });
  solve_share(0, ctx, step, setup, shared);
  for (auto& th : pool) th.join();
  if (const Distribution* d = ctx.distribution()) {
    agree_on_failure(ctx, step, setup, shared.failure, *d);
    share_responses(shared.result.responses, shared.result.solve_time,
                    [&](std::size_t k) { return frequency_owner(ctx, k); }, *d);
  } else if (shared.failure) {
    rethrow_sweep_failure(step, setup, shared.failure);
  }
  return std::move(shared.result);
}

/// The comment lines of <step>_sweep.csv: base state, excitation, measure, modulus, damping.
std::vector<std::string> sweep_comments(const AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup) {
  const SteadyStateSpec& s = step.steady_state;
  const Indenter* measured = setup.measured();
  const std::string measured_name = measured ? "indenter '" + measured->name + "'" : "set " + s.measure;
  const std::string excited_name =
      s.excitation_contact.empty() ? "set " + s.excitation.set : "indenter '" + s.excitation_contact + "'";
  const Measure m = setup.measure;
  const char* amplitude = !s.from_acceleration ? "displacement amplitude"
                          : s.reading == AccelerationReading::peak_to_peak ? "acceleration read as peak-to-peak"
                                               : "acceleration read as peak";
  char comment[768];
  std::snprintf(comment, sizeof comment,
                "step %s: base state at t = %.6g s (%s stress); %s excited in %c, %s; measured %s (%s); "
                "E = (F / %.6g mm^2) / (U / %.6g mm); damping %s",
                step.name.c_str(), ctx.model().time, s.base_stress == BaseStress::relaxed ? "relaxed" : "as-left", excited_name.c_str(),
                "xyz"[setup.component], amplitude, measured_name.c_str(),
                m == Measure::indenter_driven ? "driven" : m == Measure::indenter_free ? "free" : "held",
                setup.geometry.area, s.thickness, describe_damping(s).c_str());
  std::vector<std::string> comments{comment};
  if (!setup.indenters.empty())
    comments.push_back("indenters: rigid, contact frozen at the base state (closed nodes keep a normal penalty "
                       "spring; frictionless: free tangential sliding; with friction: sticking); forces are those "
                       "of the model (not multiplied by the contact's force_factor)");
  return comments;
}

/// Writes <step>_sweep.csv and, if output.vtk, the frames of <step>_sweep.pvd (time = frequency [Hz], on
/// the deformed base state: write_frequency_frame).
/// <step>_node_print_<set>.csv of a deck's *NODE PRINT: the complex displacement amplitudes of the set's
/// nodes at every frequency.
void write_prints(const AnalysisContext& ctx, const StepSpec& step, const SweepResult& result,
                  const std::filesystem::path& dir) {
  const mesh::Mesh& mesh = ctx.mesh();
  for (const std::string& set : step.steady_state.prints) {
    const std::filesystem::path file = dir / (step.name + "_node_print_" + io::file_safe_name(set) + ".csv");
    std::ofstream out(file);
    out << "# cushion run " << ctx.spec().file.string() << ": *NODE PRINT of set " << set << " in steady-state step "
        << step.name << ": displacement amplitude u^ [mm], u(t) = Re(u^ exp(i 2 pi f t))\n"
        << "frequency_Hz,node,U1_re_mm,U1_im_mm,U2_re_mm,U2_im_mm,U3_re_mm,U3_im_mm\n";
    for (const FrequencyResponse& r : result.responses)
      for (int n : mesh.node_sets.at(set)) {
        out << io::format_double(r.frequency) << "," << (mesh.node_labels.empty() ? n + 1 : mesh.node_labels[n]);
        for (int c = 0; c < 3; ++c) {
          const std::complex<double> u = r.u(3 * n + c);
          out << "," << io::format_double(u.real()) << "," << io::format_double(u.imag());
        }
        out << "\n";
      }
    if (!out) throw std::runtime_error(file.string() + ": cannot write");
  }
}

void write_sweep(AnalysisContext& ctx, const StepSpec& step, const SweepSetup& setup, const SweepResult& result) {
  if (!ctx.output().writes()) return;  // another process of a distributed run writes
  const std::filesystem::path dir = ctx.output().pvd_file().parent_path();
  write_prints(ctx, step, result, dir);
  if (!setup.force_mode) {
    std::vector<SweepRow> rows;
    for (const auto& r : result.responses) rows.push_back(make_row(r, setup.measure, setup.geometry));
    write_sweep_csv(dir / (step.name + "_sweep.csv"), rows, sweep_comments(ctx, step, setup));
  }
  if (step.steady_state.vtk) {
    ResultSeries series(dir, step.name + "_sweep");
    const LinearisedSystem& system = *setup.model.system;
    const LinearisedSystem::ElementBase base = system.element_base();
    for (const auto& r : result.responses)
      write_frequency_frame(series, ctx.mesh(), system, base, r, setup.component);
  }
}

/// Logs the sweep's costs: per frequency and summed over the threads [s], wall time `wall` [s].
void log_done(AnalysisContext& ctx, const StepSpec& step, const SweepResult& result, std::size_t dofs, double wall) {
  const SolveStats& cost = result.cost;
  const std::size_t nf = result.responses.size();
  double total = 0.0;
  for (double t : result.solve_time) total += t;
  ctx.log() << "step '" << step.name << "' done: " << nf << " frequencies on " << result.threads << " threads, "
            << dofs << " DOFs, " << total / nf << " s per frequency (thread time), wall " << wall << " s; "
            << (!step.steady_state.iterative ? "complex LU"
                : ctx.sweep_preconditioner() ? "GMRES + PETSc preconditioner of Re D"
                                             : "GMRES + real Cholesky")
            << ": "
            << cost.real_factorisations << " real and " << cost.complex_factorisations
            << " complex factorisations (" << cost.factorisation_time << " s), " << cost.iterations
            << " GMRES iterations, solves " << cost.solve_time << " s, assembly " << cost.assembly_time
            << " s (thread times)\n";
}

}  // namespace

void SteadyStateStep::run(AnalysisContext& ctx) {
  const Assembler& assembler = *ctx.system(ctx.model().constrained).assembler;
  SweepSetup setup = resolve_excitation(ctx, spec_, assembler);
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const std::unique_ptr<LinearisedSystem> linearised =
      linearise_base_state(ctx, spec_, assembler, spec_.steady_state.base_stress);
  setup.model.system = linearised.get();
  if (spec_.steady_state.resonance_points) setup.frequencies = resonance_frequencies(spec_, setup);
  log_setup(ctx, spec_, setup, seconds());
  const SweepResult result = sweep(ctx, spec_, setup);
  write_sweep(ctx, spec_, setup, result);
  log_done(ctx, spec_, result, linearised->num_dofs(), seconds());
}

std::unique_ptr<Step> make_steady_state_step(const StepSpec& spec) { return std::make_unique<SteadyStateStep>(spec); }

}  // namespace cushion::solver
