// Dynamic steps: prescribed kinematics, the Newmark predictor and the inertia/damping term per
// increment, energy bookkeeping, run by the shared increment loop (increment_loop.hpp).
#include "solver/analysis/dynamic_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "io/text_support.hpp"
#include "solver/analysis/boundary.hpp"
#include "solver/analysis/increment_loop.hpp"
#include "solver/analysis/contact_contributor.hpp"
#include "solver/analysis/pressure_contributor.hpp"
#include "solver/dof_map.hpp"
#include "solver/dynamics/linearised_system.hpp"
#include "solver/dynamics/newmark.hpp"
#include "solver/output/history_csv.hpp"

namespace cushion::solver {

namespace {

using dynamics::Kinematics;

std::string fmt(const char* format, double x) { return io::format_with(format, x); }

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

/// Increments of a dynamic step: Newmark kinematics, inertia and damping term, energies.
class DynamicStepper final : public IncrementStepper {
 public:
  DynamicStepper(ModelState& model, const StepSpec& step, const StepBoundary& boundary,
                 const dynamics::NewmarkIntegrator& newmark, const Assembler& assembler, Kinematics start,
                 const Eigen::VectorXd& f_int_start, const Eigen::VectorXd& hht_force_start, HistoryWriter& energy_file)
      : model_(model), step_(step), boundary_(boundary), newmark_(newmark), assembler_(assembler),
        k_(std::move(start)), f_int_n_(f_int_start), hht_force_(hht_force_start), energy_file_(energy_file) {
    c_n_ = newmark_.damping_force(k_.v);
    g_n_ = f_int_n_ + newmark_.inertia_force(k_.a) + c_n_;
    energy_.kinetic_start = energy_.kinetic = 0.5 * k_.v.dot(newmark_.inertia_force(k_.v));
  }

  IncrementAttempt begin_attempt(double t_begin, double t_end) override {
    const DofMap& dofs = assembler_.dofs();
    const double dt = t_end - t_begin;
    p_ = k_;
    boundary_.apply_motion(t_end, p_.u, p_.v, p_.a);
    update_.emplace(dofs, newmark_.parameters(), k_, p_, dt, &hht_force_);
    IncrementAttempt a;
    a.dt_material = dt;
    for (int d : dofs.constrained_dofs())
      a.prescribed_increment = std::max(a.prescribed_increment, std::abs(p_.u(d) - k_.u(d)));
    a.problem = std::make_unique<EquilibriumProblem>(assembler_, model_.material, k_.u, p_.u, boundary_.loads(t_end), dt);
    a.problem->add_term(newmark_.inertia_term(*update_));
    a.x = dofs.gather_free(update_->predictor());
    a.fallback_x = dofs.gather_free(p_.u);  // the last displacement with the prescribed motion applied
    return a;
  }

  Eigen::VectorXd converged(const EquilibriumProblem& problem) override {
    next_ = update_->at(problem.u());
    c_new_ = newmark_.damping_force(next_.v);
    g_new_ = problem.f_int() + newmark_.inertia_force(next_.a) + c_new_;  // = reactions at supports
    f_int_new_ = problem.f_int();
    return g_new_;
  }

  void add_frame_fields(FrameData& frame) const override {
    const Eigen::Index n = next_.v.size();
    frame.point_fields.push_back({"velocity_mm_s", 3, std::vector<double>(next_.v.data(), next_.v.data() + n)});
    frame.point_fields.push_back({"acceleration_mm_s2", 3, std::vector<double>(next_.a.data(), next_.a.data() + n)});
  }

  void committed() override {
    energy_.add(next_.u - k_.u, f_int_n_, f_int_new_, c_n_, c_new_, g_n_, g_new_);
    energy_.kinetic = 0.5 * next_.v.dot(newmark_.inertia_force(next_.v));
    energy_file_.write_row(model_.time, energy_.row());
    f_int_n_ = f_int_new_, c_n_ = c_new_, g_n_ = g_new_;
    update_.reset();  // refers to k_, p_ and hht_force_
    if (newmark_.parameters().alpha != 0.0) hht_force_ = newmark_.next_start_force(hht_force_, next_.a);
    k_ = std::move(next_);
    model_.v = k_.v;
  }

  std::string progress_note() const override { return "  KE " + fmt("%.3e", energy_.kinetic) + " mJ"; }
  const EnergyAccount& energy() const { return energy_; }

 private:
  ModelState& model_;
  const StepSpec& step_;
  const StepBoundary& boundary_;
  const dynamics::NewmarkIntegrator& newmark_;
  const Assembler& assembler_;
  Kinematics k_, p_, next_;
  std::optional<dynamics::NewmarkUpdate> update_;
  Eigen::VectorXd f_int_n_, c_n_, g_n_, f_int_new_, c_new_, g_new_;
  Eigen::VectorXd hht_force_;  ///< HHT: G_n = f_int + contact - f_ext + C v at the free DOFs [N]
  EnergyAccount energy_;
  HistoryWriter& energy_file_;
};

}  // namespace

std::vector<std::string> energy_columns() {
  return {"kinetic_energy_mJ", "internal_work_mJ", "damping_work_mJ", "external_work_mJ", "energy_balance_mJ"};
}

void DynamicStep::run(AnalysisContext& ctx) {
  const DynamicSpec& dyn = spec_.dynamic;
  const std::vector<bool> mask = constrained_mask(ctx.mesh(), spec_);
  System& system = ctx.system(mask);
  ModelState& model = ctx.model();
  const Assembler& assembler = *system.assembler;
  const DofMap& dofs = assembler.dofs();
  const double t0 = model.time, period = spec_.period;
  const Eigen::Index n = model.u.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);

  // Mass and Rayleigh damping about the start state (long-term tangent, relaxed stress).
  std::unique_ptr<dynamics::LinearisedSystem> lin;
  try {
    lin = std::make_unique<dynamics::LinearisedSystem>(
        ctx.mesh(), assembler.sections(),
        dynamics::base_point_states(assembler, model.material, model.u, BaseStress::relaxed), model.u);
  } catch (const std::runtime_error& e) {
    throw AnalysisError("step '" + spec_.name + "': cannot build the mass and damping matrices: " + e.what());
  }
  const SparseMatrix C = dynamics::damping_matrix(dyn.damping, lin->mass(), lin->long_term_stiffness());
  dynamics::NewmarkIntegrator newmark(assembler, lin->mass(), C, {dyn.gamma, dyn.beta, dyn.hht_alpha});
  lin.reset();

  std::vector<std::shared_ptr<ResidualContributor>> contributors;
  for (auto& c : step_contacts(ctx, spec_, dofs)) contributors.push_back(std::move(c));
  if (auto pressure = step_pressures(ctx, spec_, dofs)) contributors.push_back(std::move(pressure));
  const StepBoundary boundary(ctx.mesh(), spec_, ctx.spec().amplitudes, t0, model.u, model.f_load);

  // Start kinematics: velocity carried from a preceding dynamic step or zero, acceleration from
  // equilibrium at the start.
  Kinematics k{model.u, model.v.size() == n ? model.v : zero, zero};
  boundary.apply_motion(0.0, k.u, k.v, k.a);
  k.u = model.u;  // a jump of a prescribed value at the step start is applied by the first increment
  Eigen::VectorXd f_int_n, hht_force;
  {
    EquilibriumProblem start(assembler, model.material, model.u, model.u, boundary.loads(0.0), 0.0);
    const IncrementInfo info{&spec_, t0, t0, 0.0};
    for (auto& c : contributors) c->begin_increment(info, start);
    Eigen::VectorXd r;
    ++ctx.stats().assemblies;
    const ProblemEvaluation ev = start.evaluate(dofs.gather_free(model.u), r, false);
    model.material.revert();
    for (auto& c : contributors) c->revert();
    if (ev.status == material::Status::failed)
      throw AnalysisError("step '" + spec_.name + "': material failure at the start state: " + ev.message);
    f_int_n = start.f_int();
    hht_force = newmark.start_force(r, k.v);
    try {
      k.a = newmark.initial_acceleration(r, k.v, k.a);
    } catch (const std::runtime_error& e) {
      throw AnalysisError("step '" + spec_.name + "': " + e.what());
    }
  }
  HistoryWriter energy_file = ctx.output().table(spec_.name + "_energy.csv", energy_columns(),
                            {"step " + spec_.name + ": energies since t = " + fmt("%.9g", t0) +
                             " s [mJ = N mm]; balance = kinetic + internal + damping - external - kinetic at start"});
  DynamicStepper stepper(model, spec_, boundary, newmark, assembler, std::move(k), f_int_n, hht_force, energy_file);
  energy_file.write_row(t0, stepper.energy().row());
  ctx.log() << "step '" << spec_.name << "' (dynamic, Newmark gamma = " << dyn.gamma << ", beta = " << dyn.beta
            << ", HHT alpha = " << dyn.hht_alpha << ", Rayleigh alpha = " << dyn.damping.rayleigh_alpha
            << " 1/s, beta = " << dyn.damping.rayleigh_beta << " s, " << period << " s, " << dofs.num_free()
            << " free DOFs, " << (spec_.increment.fixed ? "fixed" : "automatic")
          << " increments) from t = " << t0 << " s, start kinetic energy " << stepper.energy().kinetic << " mJ\n";

  const IncrementControl control =
      run_increment_loop(ctx, spec_, system, contributors, boundary.corner_times(), stepper);
  model.constrained = mask;
  model.f_load = boundary.loads(period);
  ctx.log() << "step '" << spec_.name << "' done: " << control.increments() << " increments, " << control.cutbacks()
          << " cut-backs, kinetic energy " << stepper.energy().kinetic << " mJ, energy balance "
          << stepper.energy().balance() << " mJ\n";
}

std::unique_ptr<Step> make_dynamic_step(const StepSpec& spec) { return std::make_unique<DynamicStep>(spec); }

}  // namespace cushion::solver
