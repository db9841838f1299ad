// Static and visco steps: prescribed displacements (and released reactions) at the end of each
// increment, the linearised predictor, then the shared increment loop (increment_loop.hpp).
#include <algorithm>
#include <cmath>

#include "solver/analysis/boundary.hpp"
#include "solver/analysis/dynamic_step.hpp"
#include "solver/analysis/increment_loop.hpp"
#include "solver/analysis/frequency_step.hpp"
#include "solver/analysis/steady_state_step.hpp"
#include "solver/analysis/step.hpp"
#include "solver/analysis/contact_contributor.hpp"
#include "solver/analysis/pressure_contributor.hpp"

namespace cushion::solver {

namespace {

/// Increments of a static or visco step.
class QuasiStaticStepper final : public IncrementStepper {
 public:
  QuasiStaticStepper(ModelState& model, const StepSpec& step, const StepBoundary& boundary, const DofMap& dofs,
                     const Assembler& assembler, const std::vector<bool>& mask)
      : model_(model), step_(step), boundary_(boundary), dofs_(dofs), assembler_(assembler),
        f_ext_(Eigen::VectorXd::Zero(model.u.size())) {
    // DOFs constrained in the previous step and free now: their reaction becomes an external force
    // ramped linearly to zero over the step (ABAQUS behaviour when a boundary condition is removed).
    for (std::size_t d = 0; d < mask.size(); ++d)
      if (model.constrained[d] && !mask[d]) released_.emplace_back(static_cast<int>(d), model.f_int(d));
  }

  IncrementAttempt begin_attempt(double t_begin, double t_end) override {
    const bool visco = step_.type == StepSpec::Type::visco;
    IncrementAttempt a;
    a.dt_material = visco ? t_end - t_begin : (step_.long_term ? long_term_dt : 0.0);
    Eigen::VectorXd u_new = model_.u;
    boundary_.apply(t_end, u_new);
    for (int d : dofs_.constrained_dofs())
      a.prescribed_increment = std::max(a.prescribed_increment, std::abs(u_new(d) - model_.u(d)));
    f_ext_ = boundary_.loads(t_end);
    for (const auto& [d, reaction] : released_) f_ext_(d) += reaction * (1.0 - t_end / step_.period);
    a.problem =
        std::make_unique<EquilibriumProblem>(assembler_, model_.material, model_.u, u_new, f_ext_, a.dt_material);
    a.x = dofs_.gather_free(model_.u);
    a.predict = true;
    return a;
  }
  Eigen::VectorXd converged(const EquilibriumProblem& problem) override { return problem.f_int(); }

 private:
  ModelState& model_;
  const StepSpec& step_;
  const StepBoundary& boundary_;
  const DofMap& dofs_;
  const Assembler& assembler_;
  Eigen::VectorXd f_ext_;
  std::vector<std::pair<int, double>> released_;
};

}  // namespace

void QuasiStaticStep::run(AnalysisContext& ctx) {
  const std::vector<bool> mask = constrained_mask(ctx.mesh(), spec_);
  System& system = ctx.system(mask);
  ModelState& model = ctx.model();
  const DofMap& dofs = system.assembler->dofs();
  const StepBoundary boundary(ctx.mesh(), spec_, ctx.spec().amplitudes, model.time, model.u, model.f_load);
  std::vector<std::shared_ptr<ResidualContributor>> contributors = contributors_;
  for (auto& c : step_contacts(ctx, spec_, dofs)) contributors.push_back(std::move(c));
  if (auto pressure = step_pressures(ctx, spec_, dofs)) contributors.push_back(std::move(pressure));
  const bool visco = spec_.type == StepSpec::Type::visco;
  ctx.log() << "step '" << spec_.name << "' (" << (visco ? "visco" : spec_.long_term ? "static, long term" : "static")
          << ", " << spec_.period << " s, " << dofs.num_free() << " free DOFs, "
          << (ctx.spec().solver.tangent_reuse ? "modified" : "full") << " Newton) from t = " << model.time << " s\n";

  QuasiStaticStepper stepper(model, spec_, boundary, dofs, *system.assembler, mask);
  const IncrementControl control = run_increment_loop(ctx, spec_, system, contributors, boundary.corner_times(), stepper);
  model.constrained = mask;
  model.f_load = boundary.loads(spec_.period);
  model.v.resize(0);  // a quasi-static step ends at rest
  ctx.log() << "step '" << spec_.name << "' done: " << control.increments() << " increments, " << control.cutbacks()
          << " cut-backs\n";
}

std::unique_ptr<Step> make_step(const StepSpec& spec) {
  if (spec.type == StepSpec::Type::steady_state) return make_steady_state_step(spec);
  if (spec.type == StepSpec::Type::frequency) return make_frequency_step(spec);
  if (spec.type == StepSpec::Type::dynamic) return make_dynamic_step(spec);
  return std::make_unique<QuasiStaticStep>(spec);
}

}  // namespace cushion::solver
