// The increment loop of dynamic steps: prescribed kinematics, Newmark predictor, Newton with the
// inertia/damping and contact terms, then commit with output and energy bookkeeping, or revert and
// cut back. Never accepts an unconverged increment.
#include "solver/analysis/dynamic_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "material/input_error.hpp"
#include "solver/analysis/boundary.hpp"
#include "solver/analysis/increment_control.hpp"
#include "solver/contact/contact_contributor.hpp"
#include "solver/dof_map.hpp"
#include "solver/dynamics/linearised_system.hpp"
#include "solver/dynamics/newmark.hpp"
#include "solver/output/history_csv.hpp"
#include "solver/output/interrupt.hpp"

namespace cushion::solver {

namespace {

using dynamics::Kinematics;

std::string fmt(const char* format, double x) {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

/// Velocities at the end of a dynamic step, kept in AnalysisContext::contributors under
/// kCarriedVelocity for a directly following dynamic step (it contributes no equilibrium term).
class CarriedVelocity final : public ResidualContributor {
 public:
  void begin_increment(const IncrementInfo&, EquilibriumProblem&) override {}
  Eigen::VectorXd v;  ///< full [mm/s]
};
const char* const kCarriedVelocity = "dynamic:velocity";

/// True if the last step before `step` that changes the state (not steady_state) is dynamic.
bool follows_dynamic_step(const CaseSpec& spec, const StepSpec& step) {
  const StepSpec* previous = nullptr;
  for (const StepSpec& s : spec.steps) {
    if (&s == &step) break;
    if (s.type != StepSpec::Type::steady_state) previous = &s;
  }
  return previous && previous->type == StepSpec::Type::dynamic;
}

/// Prescribed u, v, a of the step's conditions as functions of step time (later conditions win).
class PrescribedKinematics {
 public:
  PrescribedKinematics(const mesh::Mesh& mesh, const StepSpec& step, const std::map<std::string, Amplitude>& amplitudes,
                       double t_start, const Eigen::VectorXd& u_start)
      : step_(step), amplitudes_(amplitudes), t_start_(t_start), u_start_(u_start) {
    for (const BoundarySpec& bc : step.boundary) {
      std::vector<int> dofs;
      for (int node : mesh.node_sets.at(bc.set))
        for (int c = 0; c < 3; ++c)
          if (bc.dofs[c]) dofs.push_back(DofMap::dof(node, c));
      entries_.emplace_back(&bc, std::move(dofs));
    }
  }
  /// Full vectors at step time t [s]: constrained entries prescribed, free entries those of `base`.
  Kinematics at(double t, const Kinematics& base) const {
    Kinematics k = base;
    for (const auto& [bc, dofs] : entries_)
      for (int d : dofs) {
        const PrescribedMotion m = prescribed_motion(*bc, amplitudes_, u_start_(d), t, step_.period, t_start_);
        k.u(d) = m.u, k.v(d) = m.v, k.a(d) = m.a;
      }
    return k;
  }

 private:
  const StepSpec& step_;
  const std::map<std::string, Amplitude>& amplitudes_;
  double t_start_;
  Eigen::VectorXd u_start_;
  std::vector<std::pair<const BoundarySpec*, std::vector<int>>> entries_;
};

/// Forwards to an EquilibriumProblem and counts its element loops in SolverStats.
class CountedProblem final : public NonlinearProblem {
 public:
  CountedProblem(EquilibriumProblem& inner, SolverStats& stats) : inner_(inner), stats_(stats) {}
  std::size_t size() const override { return inner_.size(); }
  ProblemEvaluation evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) override {
    ++stats_.assemblies;
    return timed(stats_.assembly_time, [&] { return inner_.evaluate(x, r, want_tangent); });
  }
  const Eigen::SparseMatrix<double>& tangent() const override { return inner_.tangent(); }

 private:
  EquilibriumProblem& inner_;
  SolverStats& stats_;
};

/// Energies of the step since its start [mJ = N mm] (dynamic_step.hpp, <step>_energy.csv).
struct EnergyAccount {
  double kinetic_start = 0.0, kinetic = 0.0, internal = 0.0, damping = 0.0, external = 0.0;
  /// Adds the trapezoidal work of the forces over du = u_new - u_old.
  void add(const Eigen::VectorXd& du, const Eigen::VectorXd& f_old, const Eigen::VectorXd& f_new,
           const Eigen::VectorXd& c_old, const Eigen::VectorXd& c_new, const Eigen::VectorXd& g_old,
           const Eigen::VectorXd& g_new) {
    internal += 0.5 * du.dot(f_old + f_new);
    damping += 0.5 * du.dot(c_old + c_new);
    external += 0.5 * du.dot(g_old + g_new);
  }
  double balance() const { return kinetic + internal + damping - external - kinetic_start; }
  std::vector<double> row() const { return {kinetic, internal, damping, external, balance()}; }
};

}  // namespace

std::vector<std::string> energy_columns() {
  return {"kinetic_energy_mJ", "internal_work_mJ", "damping_work_mJ", "external_work_mJ", "energy_balance_mJ"};
}

void DynamicStep::run(AnalysisContext& ctx) {
  const DynamicSpec& dyn = spec_.dynamic;
  const std::vector<bool> mask = constrained_mask(ctx.mesh, spec_);
  System& system = ctx.system(mask);
  const Assembler& assembler = *system.assembler;
  const DofMap& dofs = assembler.dofs();
  for (const Section& section : assembler.sections())
    if (!(section.density > 0.0))
      throw InputError(ctx.spec.file.string() + ": " + dyn.key + ": a dynamic step needs the mass density of material \"" +
                       section.name + "\" (give density_kg_m3 in " + ctx.spec.material_file.string() + ")");
  const double t0 = ctx.time, period = spec_.period;
  const Eigen::Index n = ctx.u.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);

  // Mass and Rayleigh damping about the start state (long-term tangent, relaxed stress).
  std::unique_ptr<dynamics::LinearisedSystem> lin;
  try {
    lin = std::make_unique<dynamics::LinearisedSystem>(
        ctx.mesh, assembler.sections(),
        dynamics::base_point_states(assembler, ctx.state, ctx.u, dynamics::BaseStress::relaxed), ctx.u);
  } catch (const std::runtime_error& e) {
    throw AnalysisError("step '" + spec_.name + "': cannot build the mass and damping matrices: " + e.what());
  }
  SparseMatrix C = dyn.rayleigh_alpha * lin->mass();
  if (dyn.rayleigh_beta > 0.0) C += dyn.rayleigh_beta * lin->long_term_stiffness();
  dynamics::NewmarkIntegrator newmark(assembler, lin->mass(), C, {dyn.gamma, dyn.beta});
  lin.reset();

  std::vector<std::shared_ptr<ResidualContributor>> contributors;
  for (auto& c : step_contacts(ctx, spec_, dofs)) contributors.push_back(std::move(c));
  const PrescribedKinematics prescribed(ctx.mesh, spec_, ctx.spec.amplitudes, t0, ctx.u);
  auto& carried_slot = ctx.contributors[kCarriedVelocity];
  if (!carried_slot) carried_slot = std::make_shared<CarriedVelocity>();
  auto& carried = static_cast<CarriedVelocity&>(*carried_slot);

  // Start kinematics: velocity carried or zero, acceleration from equilibrium at the start.
  Kinematics k{ctx.u, follows_dynamic_step(ctx.spec, spec_) && carried.v.size() == n ? carried.v : zero, zero};
  k = prescribed.at(0.0, k);
  k.u = ctx.u;  // a jump of a prescribed value at the step start is applied by the first increment
  Eigen::VectorXd f_int_n;
  {
    EquilibriumProblem start(assembler, ctx.state, ctx.u, ctx.u, zero, 0.0);
    const IncrementInfo info{&spec_, t0, t0, 0.0};
    for (auto& c : contributors) c->begin_increment(info, start);
    Eigen::VectorXd r;
    ++ctx.stats.assemblies;
    const ProblemEvaluation ev = start.evaluate(dofs.gather_free(ctx.u), r, false);
    ctx.state.revert();
    for (auto& c : contributors) c->revert();
    if (ev.status == material::Status::failed)
      throw AnalysisError("step '" + spec_.name + "': material failure at the start state: " + ev.message);
    f_int_n = start.f_int();
    try {
      k.a = newmark.initial_acceleration(r, k.v, k.a);
    } catch (const std::runtime_error& e) {
      throw AnalysisError("step '" + spec_.name + "': " + e.what());
    }
  }
  Eigen::VectorXd c_n = newmark.damping_force(k.v), g_n = f_int_n + newmark.inertia_force(k.a) + c_n;
  EnergyAccount energy;
  energy.kinetic_start = energy.kinetic = 0.5 * k.v.dot(newmark.inertia_force(k.v));
  const std::filesystem::path dir = ctx.output.pvd_file().parent_path();
  HistoryWriter energy_file(dir / (spec_.name + "_energy.csv"), energy_columns(),
                            {"step " + spec_.name + ": energies since t = " + fmt("%.9g", t0) +
                             " s [mJ = N mm]; balance = kinetic + internal + damping - external - kinetic at start"});
  energy_file.write_row(t0, energy.row());

  std::vector<double> frame_times;
  if (spec_.output.frames_every)
    for (int i = 1; i * *spec_.output.frames_every < period * (1.0 - 1e-12); ++i)
      frame_times.push_back(i * *spec_.output.frames_every);
  std::vector<double> targets = StepBoundary(ctx.mesh, spec_, ctx.spec.amplitudes, t0, ctx.u).corner_times();
  targets.insert(targets.end(), frame_times.begin(), frame_times.end());
  IncrementLimits limits = increment_limits(spec_, ctx.spec.solver);
  if (spec_.increment.fixed) limits.growth_factor = 1.0, limits.max_cutbacks = 0, limits.min = limits.initial;
  IncrementControl control(limits, targets);
  auto frame_due = [&](double t_step, int increment) {
    if (t_step >= period) return true;
    if (!spec_.output.frames_every) return increment % spec_.output.frame_every_increments == 0;
    return std::any_of(frame_times.begin(), frame_times.end(),
                       [&](double t) { return std::abs(t - t_step) <= 1e-12 * period; });
  };

  NewtonOptions options;
  options.residual_tolerance = ctx.spec.solver.residual_tolerance;
  options.correction_tolerance = ctx.spec.solver.correction_tolerance;
  options.max_iterations = ctx.spec.solver.max_iterations;
  double q_sum = 0.0;
  std::vector<PointOutput> points;
  Eigen::VectorXd f_scratch;
  ctx.log << "step '" << spec_.name << "' (dynamic, Newmark gamma = " << dyn.gamma << ", beta = " << dyn.beta
          << ", Rayleigh alpha = " << dyn.rayleigh_alpha << " 1/s, beta = " << dyn.rayleigh_beta << " s, " << period
          << " s, " << dofs.num_free() << " free DOFs, " << (spec_.increment.fixed ? "fixed" : "automatic")
          << " increments) from t = " << t0 << " s, start kinetic energy " << energy.kinetic << " mJ\n";

  while (!control.finished()) {
    const double t_begin = control.time(), t_end = control.next_end(), dt = t_end - t_begin;
    const Kinematics p = prescribed.at(t_end, k);
    const dynamics::NewmarkUpdate update(dofs, newmark.parameters(), k, p, dt);
    double prescribed_increment = 0.0;
    for (int d : dofs.constrained_dofs()) prescribed_increment = std::max(prescribed_increment, std::abs(p.u(d) - k.u(d)));

    EquilibriumProblem problem(assembler, ctx.state, k.u, p.u, zero, dt);
    const IncrementInfo info{&spec_, t0 + t_begin, t0 + t_end, dt};
    for (auto& c : contributors) c->begin_increment(info, problem);
    problem.add_term(newmark.inertia_term(update));
    ctx.log << "  increment " << control.increments() + 1 << ": t = " << t0 + t_end << " s, dt = " << dt << " s\n";
    options.reference_force = control.increments() ? q_sum / control.increments() : 0.0;
    Eigen::VectorXd x = dofs.gather_free(update.predictor());
    const Eigen::VectorXd x_start = dofs.gather_free(k.u);
    options.prescribed_increment = prescribed_increment + (x.size() ? (x - x_start).cwiseAbs().maxCoeff() : 0.0);
    CountedProblem counted(problem, ctx.stats);
    auto log = [&](const NewtonIterate& it) { ctx.log << "    " << format_iterate(it) << "\n"; };
    NewtonResult last;
    try {
      last = solve_newton(counted, *system.linear, x, options, log);
    } catch (const SingularMatrixError& e) {
      last.outcome = NewtonOutcome::singular;
      last.message = e.what();
    }
    // Augmented-Lagrangian (Uzawa) updates of the contacts: solve again until none changes.
    for (bool again = true; last.converged() && again;) {
      again = false;
      std::string failure;
      for (auto& c : contributors) again = c->update_after_solve(failure) || again;
      if (!failure.empty()) {
        ctx.state.revert();
        for (auto& c : contributors) c->revert();
        throw AnalysisError("step '" + spec_.name + "' at t = " + fmt("%.6g", t0 + t_end) + " s: " + failure +
                            "; frames written so far are complete (up to t = " +
                            fmt("%.6g", ctx.output.last_frame_time()) + " s)");
      }
      if (!again) break;
      const int before = last.iterations;
      last = solve_newton(counted, *system.linear, x, options, log);
      last.iterations += before;
    }
    const double residual = last.history.empty() ? NAN : last.history.back().residual_max;

    if (!last.converged()) {
      ctx.state.revert();
      for (auto& c : contributors) c->revert();
      ++ctx.stats.cutbacks;
      const std::string reason = to_string(last.outcome) + (last.message.empty() ? "" : ": " + last.message);
      const bool retry = control.cut_back(last.dt_factor);
      const std::string line = "  " + spec_.name + ": attempt t = " + fmt("%.6g", t0 + t_end) + " s, dt = " +
                               fmt("%.4g", dt) + " s failed (" + reason + ")" +
                               (retry ? "; cut back to dt = " + fmt("%.4g", control.increment()) + " s" : "");
      ctx.log << line << "\n";
      if (ctx.progress) *ctx.progress << line << std::endl;
      if (!retry)
        throw AnalysisError("step '" + spec_.name + "' at t = " + fmt("%.6g", t0 + t_begin) + " s: " +
                            (spec_.increment.fixed ? std::string("no convergence with the fixed increment (increment.fixed)")
                                                   : "no convergence after " + std::to_string(control.cutbacks_in_row()) +
                                                         " cut-backs in a row") +
                            "; last attempt " + reason +
                            (std::isnan(residual) ? std::string() : "; last residual " + fmt("%.3e", residual) + " N") +
                            "; frames written so far are complete (up to t = " +
                            fmt("%.6g", ctx.output.last_frame_time()) + " s)");
      continue;
    }

    // Converged: kinematics, support forces and energies, output from the trial state, then commit.
    Kinematics next = update.at(problem.u());
    const Eigen::VectorXd c_new = newmark.damping_force(next.v);
    const Eigen::VectorXd g_new = problem.f_int() + newmark.inertia_force(next.a) + c_new;  // = reactions at supports
    energy.add(next.u - k.u, f_int_n, problem.f_int(), c_n, c_new, g_n, g_new);
    energy.kinetic = 0.5 * next.v.dot(newmark.inertia_force(next.v));
    const bool interrupted = interrupt_requested();
    if (frame_due(t_end, control.increments() + 1) || interrupted) {
      ++ctx.stats.assemblies;
      timed(ctx.stats.assembly_time,
            [&] { assembler.assemble(k.u, problem.u(), dt, ctx.state, f_scratch, nullptr, &points); });
      FrameData frame = make_frame(t0 + t_end, assembler, points, problem.u(), g_new);
      for (auto& c : contributors) c->add_frame_fields(frame);
      frame.point_fields.push_back({"velocity_mm_s", 3, std::vector<double>(next.v.data(), next.v.data() + n)});
      frame.point_fields.push_back({"acceleration_mm_s2", 3, std::vector<double>(next.a.data(), next.a.data() + n)});
      ctx.output.write_frame(std::move(frame));
    }
    ctx.state.commit();
    for (auto& c : contributors) c->commit();
    ctx.u = problem.u();
    ctx.f_int = problem.f_int();
    ctx.time = t0 + t_end;
    ctx.output.write_history(ctx.time, ctx.u, g_new, dofs);
    energy_file.write_row(ctx.time, energy.row());
    f_int_n = problem.f_int(), c_n = c_new, g_n = g_new;
    k = std::move(next);
    ++ctx.stats.increments;
    ctx.stats.iterations += last.iterations;
    q_sum += last.history.back().force_scale;
    if (ctx.progress) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-10s inc %4d  t = %-10.6g s  dt = %-9.4g s  iter %2d  |r|max %.2e N  KE %.3e mJ",
                    spec_.name.c_str(), control.increments() + 1, ctx.time, dt, last.iterations, residual,
                    energy.kinetic);
      *ctx.progress << line << std::endl;
    }
    if (!control.accept(t_end, last.iterations, last.dt_factor))
      throw AnalysisError("step '" + spec_.name + "' at t = " + fmt("%.6g", ctx.time) + " s: more than " +
                          std::to_string(control.limits().max_increments) +
                          " increments needed (increment.max_increments); frames written so far are complete");
    if (interrupted) throw Interrupted(ctx.output.last_frame_time());
  }
  carried.v = k.v;
  ctx.constrained = mask;
  ctx.log << "step '" << spec_.name << "' done: " << control.increments() << " increments, " << control.cutbacks()
          << " cut-backs, kinetic energy " << energy.kinetic << " mJ, energy balance " << energy.balance() << " mJ\n";
}

std::unique_ptr<Step> make_dynamic_step(const StepSpec& spec) { return std::make_unique<DynamicStep>(spec); }

}  // namespace cushion::solver
