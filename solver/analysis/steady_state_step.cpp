// The steady-state sweep step: checks, linearisation about the carried state, frequencies on up to
// 2 threads (one SteadyStateSolver, i.e. one complex LU, per thread), then the sweep CSV and frames.
#include "solver/analysis/steady_state_step.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "io/input_error.hpp"
#include "solver/analysis/contact_contributor.hpp"
#include "solver/dynamics/contact_linearisation.hpp"
#include "solver/dynamics/sweep.hpp"

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
    if (s.type != StepSpec::Type::steady_state) previous = &s;
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

}  // namespace

void SteadyStateStep::run(AnalysisContext& ctx) {
  const SteadyStateSpec& s = spec_.steady_state;
  const std::string where = ctx.spec().file.string() + ": " + s.key;
  // --- input checks, before anything is computed or written ---
  const System& system = ctx.system(ctx.model().constrained);
  const Assembler& assembler = *system.assembler;
  for (const Section& section : assembler.sections())
    if (!(section.density > 0.0))
      throw InputError(where + ": the material \"" + section.name + "\" has no mass density (give density_kg_m3 in " +
                       ctx.spec().material_file.string() + ")");
  const int c = s.excitation.dofs[0] ? 0 : s.excitation.dofs[1] ? 1 : 2;
  Vec3 e = Vec3::Zero();
  e(c) = 1.0;

  // Indenters: one appended DOF each along the excitation's component; their roles.
  std::vector<Indenter> indenters = base_state_indenters(ctx, spec_);
  auto indenter = [&](const std::string& name, const std::string& key) -> Indenter& {
    for (Indenter& i : indenters)
      if (i.name == name) return i;
    throw InputError(where + key + ": \"" + name + "\" is not a contact of the base state (contacts of the previous "
                     "step: " + names(indenters) + ")");
  };
  if (!s.excitation_contact.empty()) indenter(s.excitation_contact, ".excitation.contact").role = Indenter::Role::driven;
  for (const IndenterMotion& m : s.indenters) {
    Indenter& i = indenter(m.contact, m.key.substr(s.key.size()) + ".contact");
    if (m.free) i.role = Indenter::Role::free, i.mass = m.mass;
  }
  Indenter* measured_indenter = s.measure_contact.empty() ? nullptr : &indenter(s.measure_contact, ".measure.contact");
  const std::size_t n_nodes_dofs = 3 * ctx.mesh().num_nodes();
  const std::size_t n_all = n_nodes_dofs + indenters.size();
  std::vector<Eigen::Triplet<double>> contact_triplets;
  for (Indenter& i : indenters) {
    try {
      i.lin = linearise_contact(ctx.mesh(), *i.set, ctx.model().u, i.dof, e);
    } catch (const std::runtime_error& err) {
      throw AnalysisError("step '" + spec_.name + "': cannot linearise the contact: " + err.what());
    }
    const bool named = i.role != Indenter::Role::held || &i == measured_indenter;
    if (i.lin.closed.empty()) {
      const std::string msg = "contact '" + i.name + "' has no closed node at the base state (t = " +
                              std::to_string(ctx.model().time) + " s, smallest gap " +
                              std::to_string(*std::min_element(i.set->gaps().begin(), i.set->gaps().end())) +
                              " mm): the indenter does not touch the foam";
      if (named) throw InputError(where + ": " + msg + ", so the sweep would measure nothing; press it into the foam in "
                                  "the previous step");
      ctx.log() << "  warning: step '" << spec_.name << "': " << msg << " (held, no effect)\n";
    }
    contact_triplets.insert(contact_triplets.end(), i.lin.stiffness.begin(), i.lin.stiffness.end());
  }

  Excitation excitation;
  if (s.excitation_contact.empty())
    excitation.driven = component_dofs(set_nodes(ctx, s.excitation.set, s.excitation.key + ".set"), c);
  else
    excitation.driven = {indenter(s.excitation_contact, "").dof};
  std::vector<bool> driven(n_all, false), held(n_all, false);
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
  HarmonicModel model;
  for (const Indenter& i : indenters) {
    if (i.role == Indenter::Role::held) excitation.held.push_back(i.dof), held[i.dof] = true;
    if (i.role == Indenter::Role::free) model.lumped_mass.emplace_back(i.dof, i.mass);
  }
  model.extra_dofs = static_cast<int>(indenters.size());
  if (!indenters.empty()) {
    model.extra_stiffness.resize(static_cast<Eigen::Index>(n_all), static_cast<Eigen::Index>(n_all));
    model.extra_stiffness.setFromTriplets(contact_triplets.begin(), contact_triplets.end());
  }

  std::vector<int> measured;
  Measure measure = Measure::indenter_held;
  bool measure_driven = false;
  if (measured_indenter) {
    measured = {measured_indenter->dof};
    measure_driven = measured_indenter->role == Indenter::Role::driven;
    measure = measure_driven ? Measure::indenter_driven
              : measured_indenter->role == Indenter::Role::free ? Measure::indenter_free : Measure::indenter_held;
  } else {
    measure_driven = s.measure == s.excitation.set && s.excitation_contact.empty();
    measured = component_dofs(set_nodes(ctx, s.measure, s.key + ".measure"), c);
    if (!measure_driven)
      measured.erase(std::remove_if(measured.begin(), measured.end(), [&](int d) { return !held[d]; }), measured.end());
    if (measured.empty())
      throw InputError(where + ".measure: set \"" + s.measure + "\" is neither driven nor held in the excitation's dof");
    measure = measure_driven ? Measure::indenter_driven : Measure::indenter_held;
  }
  const std::vector<DofGroup> groups{{"indenter", measured}, {"base", measure_driven ? held_c : excitation.driven}};
  const double area = s.area_from_contact ? measured_indenter->lin.closed_area : s.area;
  const NominalGeometry geometry{area, s.thickness};
  const Damping damping{s.alpha, s.beta, s.structural};

  // --- linearisation about the carried (committed) state ---
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  std::unique_ptr<LinearisedSystem> linearised;
  try {
    auto points = base_point_states(assembler, ctx.model().material, ctx.model().u,
                                    s.relaxed_base ? BaseStress::relaxed : BaseStress::as_left);
    linearised = std::make_unique<LinearisedSystem>(ctx.mesh(), assembler.sections(), std::move(points), ctx.model().u);
  } catch (const std::runtime_error& e) {
    throw AnalysisError("step '" + spec_.name + "': cannot linearise the base state: " + e.what());
  }
  model.system = linearised.get();
  const double setup = seconds();
  ctx.log() << "step '" << spec_.name << "' (steady_state, " << s.frequencies.size() << " frequencies, "
          << (s.relaxed_base ? "relaxed" : "as-left") << " base stress, alpha = " << s.alpha
          << " 1/s, beta = " << s.beta << " s, structural = " << s.structural << ") about t = " << ctx.model().time
          << " s; linearisation " << setup << " s\n";
  for (const Indenter& i : indenters)
    ctx.log() << "  indenter '" << i.name << "': "
            << (i.role == Indenter::Role::held ? "held" : i.role == Indenter::Role::driven ? "driven" : "free")
            << (i.role == Indenter::Role::free ? ", mass " + std::to_string(1e3 * i.mass) + " kg" : std::string())
            << ", " << i.lin.closed.size() << " closed nodes (frozen normal springs" << (i.set->parameters().friction > 0.0 ? ", sticking" : ", sliding freely")
            << " tangentially), closed area " << i.lin.closed_area << " mm^2\n";

  // --- the sweep: frequency k on thread k % threads, each thread with its own complex LU ---
  const std::size_t nf = s.frequencies.size();
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>({2, nf, std::max(1u, std::thread::hardware_concurrency())}));
  std::vector<FrequencyResponse> responses(nf);
  std::vector<double> solve_time(nf, 0.0);
  std::mutex report;
  std::exception_ptr failure;
  SolveStats cost;  // summed over the threads
  auto work = [&](unsigned t) {
    try {
      SteadyStateSolver solver(model, damping, excitation, groups, SolveMethod{s.iterative, s.gmres_tolerance});
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
        const int iterations = solver.stats().iterations;
        responses[k] = solver.solve(f, U);
        solve_time[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count();
        const SweepRow row = make_row(responses[k], measure, geometry);
        char line[256];
        std::snprintf(line, sizeof line,
                      "%-10s f = %8.4g Hz  U = %.4e mm  |E*| = %.5g kPa  phase = %7.3f deg  (%.2f s, %d iterations)",
                      spec_.name.c_str(), f, U, 1e3 * std::abs(row.modulus), std::arg(row.stiffness) * 180.0 / M_PI,
                      solve_time[k], solver.stats().iterations - iterations);
        const std::lock_guard<std::mutex> lock(report);
        ctx.log() << "  " << line << "\n";
        ctx.report_progress(line);
      }
      const SolveStats& c = solver.stats();
      const std::lock_guard<std::mutex> lock(report);
      cost.complex_factorisations += c.complex_factorisations;
      cost.real_factorisations += c.real_factorisations;
      cost.iterations += c.iterations;
      cost.assembly_time += c.assembly_time;
      cost.factorisation_time += c.factorisation_time;
      cost.solve_time += c.solve_time;
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
  const std::filesystem::path dir = ctx.output().pvd_file().parent_path();
  const std::string measured_name =
      measured_indenter ? "indenter '" + measured_indenter->name + "'" : "set " + s.measure;
  const std::string excited_name =
      s.excitation_contact.empty() ? "set " + s.excitation.set : "indenter '" + s.excitation_contact + "'";
  char comment[768];
  std::snprintf(comment, sizeof comment,
                "step %s: base state at t = %.6g s (%s stress); %s excited in %c, %s; measured %s (%s); "
                "E = (F / %.6g mm^2) / (U / %.6g mm); damping alpha = %.6g 1/s, beta = %.6g s, structural = %.6g",
                spec_.name.c_str(), ctx.model().time, s.relaxed_base ? "relaxed" : "as-left",
                excited_name.c_str(), "xyz"[c],
                s.from_acceleration ? (s.peak_to_peak ? "acceleration read as peak-to-peak" : "acceleration read as peak")
                                    : "displacement amplitude",
                measured_name.c_str(),
                measure == Measure::indenter_driven ? "driven" : measure == Measure::indenter_free ? "free" : "held",
                area, s.thickness, s.alpha, s.beta,
                s.structural);
  std::vector<std::string> comments{comment};
  if (!indenters.empty())
    comments.push_back("indenters: rigid, contact frozen at the base state (closed nodes keep a normal penalty "
                       "spring; frictionless: free tangential sliding; with friction: sticking); forces are those "
                       "of the model (not multiplied by the contact's force_factor)");
  write_sweep_csv(dir / (spec_.name + "_sweep.csv"), rows, comments);
  if (s.vtk) {
    ResultSeries series(dir, spec_.name + "_sweep");
    for (const auto& r : responses) write_frequency_frame(series, ctx.mesh(), r);
  }
  double total = 0.0;
  for (double t : solve_time) total += t;
  ctx.log() << "step '" << spec_.name << "' done: " << nf << " frequencies on " << threads << " threads, "
          << linearised->num_dofs() << " DOFs, " << total / nf << " s per frequency (thread time), wall "
          << seconds() << " s; " << (s.iterative ? "GMRES + real Cholesky" : "complex LU") << ": "
          << cost.real_factorisations << " real and " << cost.complex_factorisations << " complex factorisations ("
          << cost.factorisation_time << " s), " << cost.iterations << " GMRES iterations, solves " << cost.solve_time
          << " s, assembly " << cost.assembly_time << " s (thread times)\n";
}

std::unique_ptr<Step> make_steady_state_step(const StepSpec& spec) { return std::make_unique<SteadyStateStep>(spec); }

}  // namespace cushion::solver
