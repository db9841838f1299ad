// The increment loop of static and visco steps: prescribe, predict, Newton, then commit and write
// output, or revert and cut back. Never accepts an unconverged increment.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "solver/analysis/boundary.hpp"
#include "solver/analysis/dynamic_step.hpp"
#include "solver/analysis/increment_control.hpp"
#include "solver/analysis/steady_state_step.hpp"
#include "solver/analysis/step.hpp"
#include "solver/contact/contact_contributor.hpp"
#include "solver/output/interrupt.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* format, double x) {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

/// Forwards to an EquilibriumProblem and counts the time spent in its element loops.
class TimedProblem final : public NonlinearProblem {
 public:
  TimedProblem(EquilibriumProblem& inner, SolverStats& stats) : inner_(inner), stats_(stats) {}
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

/// Predictor then Newton for one attempt; x: free displacements (in: start, out: last iterate).
/// In the predictor the contacts extrapolate from the last converged indenter position.
NewtonResult solve_increment(EquilibriumProblem& problem, LinearSolver& linear, Eigen::VectorXd& x,
                             NewtonOptions options, double prescribed_increment, AnalysisContext& ctx,
                             const std::vector<std::shared_ptr<ResidualContributor>>& contributors) {
  NewtonResult result;
  const Eigen::VectorXd x_start = x;
  auto predicting = [&](bool on) {
    for (const auto& c : contributors)
      if (auto* contact = dynamic_cast<ContactContributor*>(c.get())) contact->set_predicting(on);
  };
  struct PredictorScope {
    std::function<void(bool)> set;
    ~PredictorScope() { set(false); }
  } scope{predicting};
  predicting(true);
  try {
    // Predictor: its element loop counts as assembly, its factorization as factorization.
    const double linear_before = ctx.stats.factorization_time + ctx.stats.solve_time;
    double total = 0.0;
    const ProblemEvaluation ev = timed(total, [&] { return problem.predict(x, linear); });
    predicting(false);
    ++ctx.stats.assemblies;
    ctx.stats.assembly_time += total - (ctx.stats.factorization_time + ctx.stats.solve_time - linear_before);
    if (ev.status == material::Status::failed) {
      result.outcome = NewtonOutcome::failed;
      result.message = "material failure in the predictor: " + ev.message;
      return result;
    }
  } catch (const SingularMatrixError& e) {
    result.outcome = NewtonOutcome::singular;
    result.message = e.what();
    return result;
  }
  options.prescribed_increment =
      prescribed_increment + (x.size() ? (x - x_start).cwiseAbs().maxCoeff() : 0.0);
  TimedProblem timed_problem(problem, ctx.stats);
  return solve_newton(timed_problem, linear, x, options,
                      [&](const NewtonIterate& it) { ctx.log << "    " << format_iterate(it) << "\n"; });
}

}  // namespace

void QuasiStaticStep::run(AnalysisContext& ctx) {
  const std::vector<bool> mask = constrained_mask(ctx.mesh, spec_);
  System& system = ctx.system(mask);
  const Assembler& assembler = *system.assembler;
  const DofMap& dofs = assembler.dofs();
  const double t0 = ctx.time, period = spec_.period;
  const StepBoundary boundary(ctx.mesh, spec_, ctx.spec.amplitudes, t0, ctx.u);
  std::vector<std::shared_ptr<ResidualContributor>> contributors = contributors_;
  for (auto& c : step_contacts(ctx, spec_, dofs)) contributors.push_back(std::move(c));

  // DOFs constrained in the previous step and free now: their reaction becomes an external force
  // ramped linearly to zero over the step (ABAQUS behaviour when a boundary condition is removed).
  std::vector<std::pair<int, double>> released;
  for (std::size_t d = 0; d < mask.size(); ++d)
    if (ctx.constrained[d] && !mask[d]) released.emplace_back(static_cast<int>(d), ctx.f_int(d));

  // Increments end exactly on amplitude corners and frame times.
  std::vector<double> frame_times;
  if (spec_.output.frames_every)
    for (int k = 1; k * *spec_.output.frames_every < period * (1.0 - 1e-12); ++k)
      frame_times.push_back(k * *spec_.output.frames_every);
  std::vector<double> targets = boundary.corner_times();
  targets.insert(targets.end(), frame_times.begin(), frame_times.end());
  IncrementControl control(increment_limits(spec_, ctx.spec.solver), targets);
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
  double q_sum = 0.0;  // time-averaged force of the step (ABAQUS q~): mean q of converged increments
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(ctx.u.size()), f_scratch;
  std::vector<PointOutput> points;
  const bool visco = spec_.type == StepSpec::Type::visco;
  ctx.log << "step '" << spec_.name << "' (" << (visco ? "visco" : spec_.long_term ? "static, long term" : "static")
          << ", " << period << " s, " << dofs.num_free() << " free DOFs) from t = " << t0 << " s\n";

  NewtonResult last;
  while (!control.finished()) {
    const double t_begin = control.time(), t_end = control.next_end(), dt = t_end - t_begin;
    const double dt_material = visco ? dt : (spec_.long_term ? long_term_dt : 0.0);
    Eigen::VectorXd u_new = ctx.u;
    boundary.apply(t_end, u_new);
    double prescribed = 0.0;
    for (int d : dofs.constrained_dofs()) prescribed = std::max(prescribed, std::abs(u_new(d) - ctx.u(d)));
    for (const auto& [d, reaction] : released) f_ext(d) = reaction * (1.0 - t_end / period);

    EquilibriumProblem problem(assembler, ctx.state, ctx.u, u_new, f_ext, dt_material);
    const IncrementInfo info{&spec_, t0 + t_begin, t0 + t_end, dt_material};
    for (auto& c : contributors) c->begin_increment(info, problem);
    ctx.log << "  increment " << control.increments() + 1 << ": t = " << t0 + t_end << " s, dt = " << dt << " s\n";
    options.reference_force = control.increments() ? q_sum / control.increments() : 0.0;
    Eigen::VectorXd x = dofs.gather_free(ctx.u);
    last = solve_increment(problem, *system.linear, x, options, prescribed, ctx, contributors);
    // Augmented-Lagrangian (Uzawa) updates of the contributors: solve again until none changes.
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
      TimedProblem timed_problem(problem, ctx.stats);
      last = solve_newton(timed_problem, *system.linear, x, options,
                          [&](const NewtonIterate& it) { ctx.log << "    " << format_iterate(it) << "\n"; });
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
      if (!retry) {
        const IncrementLimits& l = control.limits();
        const bool too_small = control.increment() < l.min * (1.0 - 1e-12);
        const std::string why =
            "no convergence after " + std::to_string(control.cutbacks_in_row()) + " cut-backs in a row (" +
            (too_small ? "increment " + fmt("%.4g", control.increment()) + " s < minimum " + fmt("%.4g", l.min) + " s"
                       : "max_cutbacks = " + std::to_string(l.max_cutbacks)) +
            ")";
        throw AnalysisError("step '" + spec_.name + "' at t = " + fmt("%.6g", t0 + t_begin) + " s: " + why +
                            "; last attempt " + reason +
                            (std::isnan(residual) ? std::string() : "; last residual " + fmt("%.3e", residual) + " N") +
                            "; frames written so far are complete (up to t = " +
                            fmt("%.6g", ctx.output.last_frame_time()) + " s)");
      }
      continue;
    }

    // Converged: output from the trial state (before commit), then commit.
    const bool interrupted = interrupt_requested();
    if (frame_due(t_end, control.increments() + 1) || interrupted) {
      ++ctx.stats.assemblies;
      timed(ctx.stats.assembly_time,
            [&] { assembler.assemble(ctx.u, problem.u(), dt_material, ctx.state, f_scratch, nullptr, &points); });
      FrameData frame = make_frame(t0 + t_end, assembler, points, problem.u(), problem.f_int());
      for (auto& c : contributors) c->add_frame_fields(frame);
      ctx.output.write_frame(std::move(frame));
    }
    ctx.state.commit();
    for (auto& c : contributors) c->commit();
    ctx.u = problem.u();
    ctx.f_int = problem.f_int();
    ctx.time = t0 + t_end;
    ctx.output.write_history(ctx.time, ctx.u, ctx.f_int, dofs);
    ++ctx.stats.increments;
    ctx.stats.iterations += last.iterations;
    q_sum += last.history.back().force_scale;
    if (ctx.progress) {
      char line[256];
      std::snprintf(line, sizeof line, "%-10s inc %4d  t = %-10.6g s  dt = %-9.4g s  iter %2d  |r|max %.2e N",
                    spec_.name.c_str(), control.increments() + 1, ctx.time, dt, last.iterations, residual);
      *ctx.progress << line << std::endl;
    }
    if (!control.accept(t_end, last.iterations, last.dt_factor))
      throw AnalysisError("step '" + spec_.name + "' at t = " + fmt("%.6g", ctx.time) + " s: more than " +
                          std::to_string(control.limits().max_increments) +
                          " increments needed (increment.max_increments); frames written so far are complete");
    if (interrupted) throw Interrupted(ctx.output.last_frame_time());
  }
  ctx.constrained = mask;
  ctx.log << "step '" << spec_.name << "' done: " << control.increments() << " increments, " << control.cutbacks()
          << " cut-backs\n";
}

std::unique_ptr<Step> make_step(const StepSpec& spec) {
  if (spec.type == StepSpec::Type::steady_state) return make_steady_state_step(spec);
  if (spec.type == StepSpec::Type::dynamic) return make_dynamic_step(spec);
  return std::make_unique<QuasiStaticStep>(spec);
}

}  // namespace cushion::solver
