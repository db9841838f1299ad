#include "io/text_support.hpp"
#include "solver/analysis/increment_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "solver/output/interrupt.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* format, double x) { return io::format_with(format, x); }

/// Output frame times of a step [s of step time] (frames_every or frame_times), excluding the step end.
std::vector<double> frame_times(const StepSpec& step) {
  std::vector<double> times;
  for (double t : step.output.frame_times)
    if (t > 0.0 && t < step.period * (1.0 - 1e-12)) times.push_back(t);
  if (step.output.frames_every)
    for (int k = 1; k * *step.output.frames_every < step.period * (1.0 - 1e-12); ++k)
      times.push_back(k * *step.output.frames_every);
  return times;
}

/// Switches every contributor's predictor mode (ResidualContributor::set_predicting).
void set_predicting(const std::vector<std::shared_ptr<ResidualContributor>>& contributors, bool on) {
  for (const auto& c : contributors) c->set_predicting(on);
}

/// Predictor (optional) then Newton for one attempt; x: in: start iterate, out: last iterate.
/// `contributor_failure`: set when a contributor cannot be satisfied (no cut-back helps).
NewtonResult solve_attempt(IncrementAttempt& attempt, LinearSolver& linear, NewtonOptions options,
                           TangentFactor& factor, AnalysisContext& ctx,
                           const std::vector<std::shared_ptr<ResidualContributor>>& contributors,
                           std::string& contributor_failure) {
  NewtonResult result;
  EquilibriumProblem& problem = *attempt.problem;
  Eigen::VectorXd& x = attempt.x;
  const Eigen::VectorXd x_start = x;
  TangentFactor* reuse = options.tangent_reuse.enabled ? &factor : nullptr;
  auto fail = [&](NewtonOutcome outcome, std::string message) {
    factor.current = false;
    result.outcome = outcome;
    result.message = std::move(message);
    return result;
  };
  if (attempt.predict) {
    struct Scope {
      const std::vector<std::shared_ptr<ResidualContributor>>& c;
      ~Scope() { set_predicting(c, false); }
    } scope{contributors};
    set_predicting(contributors, true);
    try {
      // The predictor's element loop counts as assembly, its factorization as factorization.
      SolverStats& stats = ctx.stats();
      const double linear_before = stats.factorization_time + stats.solve_time;
      double total = 0.0;
      const ProblemEvaluation ev = timed(total, [&] { return problem.predict(x, linear, reuse); });
      ++stats.assemblies;
      stats.assembly_time += total - (stats.factorization_time + stats.solve_time - linear_before);
      if (ev.status == material::Status::failed)
        return fail(NewtonOutcome::failed, "material failure in the predictor: " + ev.message);
    } catch (const SingularMatrixError& e) {
      return fail(NewtonOutcome::singular, e.what());
    } catch (const LinearSolveError& e) {
      return fail(NewtonOutcome::linear_solve_failed, e.what());
    }
  }
  options.prescribed_increment =
      attempt.prescribed_increment + (x.size() ? (x - x_start).cwiseAbs().maxCoeff() : 0.0);
  TimedProblem timed_problem(problem, ctx.stats());
  auto log = [&](const NewtonIterate& it) { ctx.log() << "    " << format_iterate(it) << "\n"; };
  // solve_newton reports a singular tangent as an outcome and drops `factor` on any failure.
  result = solve_newton(timed_problem, linear, x, options, log, &factor);
  if (!result.converged() && result.outcome == NewtonOutcome::failed && result.iterations == 0 && attempt.fallback_x) {
    ctx.log() << "    " << result.message << "; again from the fallback start\n";
    x = *attempt.fallback_x;
    options.prescribed_increment = attempt.prescribed_increment + (x.size() ? (x - x_start).cwiseAbs().maxCoeff() : 0.0);
    result = solve_newton(timed_problem, linear, x, options, log, &factor);
  }
  // Augmented-Lagrangian (Uzawa) updates of the contributors: solve again until none changes.
  for (bool again = result.converged(); again;) {
    again = false;
    for (auto& c : contributors) again = c->update_after_solve(contributor_failure) || again;
    if (!contributor_failure.empty()) return fail(NewtonOutcome::failed, contributor_failure);
    if (!again) break;
    const int before = result.iterations;
    result = solve_newton(timed_problem, linear, x, options, log, &factor);
    result.iterations += before;
    again = result.converged();
  }
  return result;
}

}  // namespace

ProblemEvaluation TimedProblem::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) {
  ++stats_.assemblies;
  return timed(stats_.assembly_time, [&] { return inner_.evaluate(x, r, want_tangent); });
}

IncrementControl run_increment_loop(AnalysisContext& ctx, const StepSpec& step, System& system,
                                    const std::vector<std::shared_ptr<ResidualContributor>>& contributors,
                                    const std::vector<double>& corner_times, IncrementStepper& stepper) {
  const Assembler& assembler = *system.assembler;
  const DofMap& dofs = assembler.dofs();
  ModelState& model = ctx.model();
  SolverStats& stats = ctx.stats();
  const SolverSpec& settings = ctx.spec().solver;
  const double t0 = model.time, period = step.period;
  const std::string& name = step.name;
  auto where = [&](double t) { return "step '" + name + "' at t = " + fmt("%.6g", t0 + t) + " s: "; };
  auto frames_so_far = [&] {
    return "; frames written so far are complete (up to t = " + fmt("%.6g", ctx.output().last_frame_time()) + " s)";
  };

  // Increments end exactly on amplitude corners and frame times.
  const std::vector<double> frames = frame_times(step);
  std::vector<double> targets = corner_times;
  targets.insert(targets.end(), frames.begin(), frames.end());
  IncrementControl control(increment_limits(step, settings), targets);
  auto frame_due = [&](double t_step, int increment) {
    if (t_step >= period) return true;
    if (!step.output.frames_every && step.output.frame_times.empty())
      return increment % step.output.frame_every_increments == 0;
    return std::any_of(frames.begin(), frames.end(), [&](double t) { return std::abs(t - t_step) <= 1e-12 * period; });
  };

  NewtonOptions options;
  options.residual_tolerance = settings.residual_tolerance;
  options.correction_tolerance = settings.correction_tolerance;
  options.max_iterations = settings.max_iterations;
  options.tangent_reuse = {settings.tangent_reuse, settings.max_contraction};
  TangentFactor factor;  // what system.linear holds, kept across the increments of this step
  double q_sum = 0.0;    // time-averaged force of the step (ABAQUS q~): mean q of converged increments
  std::vector<PointOutput> points;
  Eigen::VectorXd f_scratch;

  while (!control.finished()) {
    const double t_begin = control.time(), t_end = control.next_end(), dt = t_end - t_begin;
    IncrementAttempt attempt = stepper.begin_attempt(t_begin, t_end);
    EquilibriumProblem& problem = *attempt.problem;
    const IncrementInfo info{&step, t0 + t_begin, t0 + t_end, attempt.dt_material};
    for (auto& c : contributors) c->begin_increment(info, problem);
    ctx.log() << "  increment " << control.increments() + 1 << ": t = " << t0 + t_end << " s, dt = " << dt << " s\n";
    options.reference_force = control.increments() ? q_sum / control.increments() : 0.0;
    std::string contributor_failure;
    const NewtonResult last =
        solve_attempt(attempt, *system.linear, options, factor, ctx, contributors, contributor_failure);
    const double residual = last.history.empty() ? NAN : last.history.back().residual_max;

    if (!last.converged()) {
      model.material.revert();
      for (auto& c : contributors) c->revert();
      if (!contributor_failure.empty()) throw AnalysisError(where(t_end) + contributor_failure + frames_so_far());
      ++stats.cutbacks;
      const std::string reason = to_string(last.outcome) + (last.message.empty() ? "" : ": " + last.message);
      const bool retry = control.cut_back(last.dt_factor);
      const std::string line = "  " + name + ": attempt t = " + fmt("%.6g", t0 + t_end) + " s, dt = " +
                               fmt("%.4g", dt) + " s failed (" + reason + ")" +
                               (retry ? "; cut back to dt = " + fmt("%.4g", control.increment()) + " s" : "");
      ctx.log() << line << "\n";
      ctx.report_progress(line);
      if (retry) continue;
      const IncrementLimits& l = control.limits();
      const bool too_small = control.increment() < l.min * (1.0 - 1e-12);
      const std::string why =
          step.increment.fixed
              ? std::string("no convergence with the fixed increment (increment.fixed)")
              : "no convergence after " + std::to_string(control.cutbacks_in_row()) + " cut-backs in a row (" +
                    (too_small ? "increment " + fmt("%.4g", control.increment()) + " s < minimum " + fmt("%.4g", l.min) + " s"
                               : "max_cutbacks = " + std::to_string(l.max_cutbacks)) +
                    ")";
      throw AnalysisError(where(t_begin) + why + "; last attempt " + reason +
                          (std::isnan(residual) ? std::string() : "; last residual " + fmt("%.3e", residual) + " N") +
                          frames_so_far());
    }

    // Converged: output from the trial state (before commit), then commit.
    const Eigen::VectorXd support = stepper.converged(problem);
    // Ctrl-C reaches the processes of a distributed run at different moments: they stop together.
    const Distribution* d = ctx.distribution();
    const bool interrupted = d ? d->max(interrupt_requested() ? 1.0 : 0.0) > 0.0 : interrupt_requested();
    if (frame_due(t_end, control.increments() + 1) || interrupted) {
      ++stats.assemblies;
      timed(stats.assembly_time, [&] {
        assembler.assemble(model.u, problem.u(), attempt.dt_material, model.material, f_scratch, nullptr, &points);
      });
      FrameData frame = make_frame(t0 + t_end, assembler, points, model.material, problem.u(), support);
      for (auto& c : contributors) c->add_frame_fields(frame);
      stepper.add_frame_fields(frame);
      ctx.output().write_frame(std::move(frame));
    }
    model.material.commit();
    for (auto& c : contributors) c->commit();
    model.u = problem.u();
    model.f_int = problem.f_int();
    model.time = t0 + t_end;
    ctx.output().write_history(model.time, model.u, support, dofs);
    stepper.committed();
    ++stats.increments;
    stats.iterations += last.iterations;
    q_sum += last.history.back().force_scale;
    if (ctx.progress()) {
      char line[256];
      std::snprintf(line, sizeof line, "%-10s inc %4d  t = %-10.6g s  dt = %-9.4g s  iter %2d  |r|max %.2e N",
                    name.c_str(), control.increments() + 1, model.time, dt, last.iterations, residual);
      ctx.report_progress(line + stepper.progress_note());
    }
    if (!control.accept(t_end, last.iterations, last.dt_factor))
      throw AnalysisError(where(t_end) + "more than " +
                          std::to_string(control.limits().max_increments) +
                          " increments needed (increment.max_increments); frames written so far are complete");
    if (interrupted) throw Interrupted(ctx.output().last_frame_time());
  }
  return control;
}

}  // namespace cushion::solver
