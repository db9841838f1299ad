#include "solver/newton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cushion::solver {

std::string to_string(NewtonOutcome outcome) {
  switch (outcome) {
    case NewtonOutcome::converged: return "converged";
    case NewtonOutcome::diverged: return "diverged";
    case NewtonOutcome::failed: return "failed";
    case NewtonOutcome::singular: return "singular";
    case NewtonOutcome::linear_solve_failed: return "linear solve failed";
  }
  return "unknown";
}

std::string format_iterate(const NewtonIterate& it) {
  char line[260];
  std::snprintf(line, sizeof line, "iter %2d  |r|max %.3e N  |r|2 %.3e N  q %.3e N  |c|max %.3e mm  step %.3f%s",
                it.iteration, it.residual_max, it.residual_norm, it.force_scale, it.correction_max, it.line_search,
                it.iteration == 0 ? "" : it.refreshed ? "  K new (reused K failed the line search)"
                                                   : it.new_tangent ? "  K new" : "  K reused");
  return line;
}

namespace {

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

bool usable(const ProblemEvaluation& ev, const Eigen::VectorXd& r) {
  return ev.status != material::Status::failed && r.allFinite();
}

// Backtracking line search along c from x on ||r||_2: quadratic model of ||r(x + s c)||^2 with slope
// -2 ||r||^2, new factor clamped to [0.1 s, 0.5 s]; halving after a material failure. r_trial and ev
// hold the last trial evaluated.
struct LineSearch {
  bool accepted = false;  ///< sufficient decrease (or no line search) at `step`
  double step = 1.0;      ///< accepted factor [-]
  double best_step = 0.0; ///< factor of the smallest usable trial residual (0: none usable) [-]
};

LineSearch line_search(NonlinearProblem& problem, const Eigen::VectorXd& x, const Eigen::VectorXd& c, double phi0,
                       const NewtonOptions& options, bool want_tangent, Eigen::VectorXd& r_trial,
                       ProblemEvaluation& ev) {
  LineSearch out;
  double s = 1.0, best_phi = INFINITY;
  for (int ls = 0; ls <= options.max_line_search && s >= options.min_step; ++ls) {
    ev = problem.evaluate(x + s * c, r_trial, want_tangent);
    if (!usable(ev, r_trial)) {
      s *= 0.5;
      continue;
    }
    const double phi = r_trial.norm();
    if (!options.line_search || phi <= (1.0 - 1e-4 * s) * phi0) {
      out.accepted = true;
      out.step = s;
      return out;
    }
    if (phi < best_phi) best_phi = phi, out.best_step = s;
    const double s_model = phi0 * phi0 * s * s / (phi * phi - phi0 * phi0 + 2.0 * phi0 * phi0 * s);
    s = std::clamp(s_model, 0.1 * s, 0.5 * s);
  }
  return out;
}

}  // namespace

NewtonResult solve_newton(NonlinearProblem& problem, LinearSolver& linear, Eigen::VectorXd& x,
                          const NewtonOptions& options, const std::function<void(const NewtonIterate&)>& log,
                          TangentFactor* factor) {
  NewtonResult result;
  const bool reuse = options.tangent_reuse.enabled;
  TangentFactor local;
  TangentFactor& held = reuse && factor ? *factor : local;
  // Full Newton assembles the tangent at every evaluation (the accepted trial's is the next one);
  // modified Newton only when a factorization is due.
  bool have_tangent = !reuse || !held.current;
  const Eigen::VectorXd x0 = x;
  Eigen::VectorXd r, r_trial;
  ProblemEvaluation ev = problem.evaluate(x, r, have_tangent);
  if (!usable(ev, r)) {
    held.current = false;
    result.outcome = NewtonOutcome::failed;
    result.message = "material failure at the start of the increment: " + ev.message;
    return result;
  }
  result.dt_factor = ev.dt_factor;
  // Any exit but convergence leaves no factor worth keeping (the caller cuts back).
  auto give_up = [&](NewtonOutcome outcome, std::string message) {
    held.current = false;
    result.outcome = outcome;
    result.message = std::move(message);
    return result;
  };

  double c_max = 0.0, step = 0.0;           // last applied correction and its line-search factor
  bool new_tangent = false;                 // the last correction used a new factorization
  bool refreshed = false;                   // ... after a reused one failed the line search
  double energy = 0.0, first_energy = 0.0;  // |c_k . r_k-1| and |c_1 . r_0|
  int growth = 0;                           // consecutive residual growths with a new tangent
  for (int k = 0;; ++k) {
    const double q = std::max({options.reference_force, ev.force_scale, options.force_floor});
    const NewtonIterate it{k, max_abs(r), r.norm(), c_max, step, q, new_tangent, refreshed};
    result.history.push_back(it);
    if (log) log(it);

    // Convergence tests.
    bool converged = it.residual_max <= options.zero_residual_tolerance * q;
    if (k > 0) {
      const double increment = max_abs(x - x0) + options.prescribed_increment;
      const bool force_ok = it.residual_max <= options.residual_tolerance * q;
      const bool correction_ok =
          c_max <= options.correction_tolerance * std::max(increment, options.displacement_floor);
      converged = converged || (force_ok && correction_ok);
      if (options.energy_tolerance > 0.0) converged = converged || energy <= options.energy_tolerance * first_energy;
    }
    if (converged) {
      result.outcome = NewtonOutcome::converged;
      return result;
    }

    // Divergence tests (a growth after a reused factor only triggers a new factorization).
    if (k > 0) {
      const bool grew = it.residual_max > result.history[k - 1].residual_max;
      if (!grew) growth = 0;
      else if (new_tangent) ++growth;
    }
    if (options.divergence_iterations > 0 && growth >= options.divergence_iterations)
      return give_up(NewtonOutcome::diverged,
                     "residual grew in " + std::to_string(options.divergence_iterations) + " consecutive iterations");
    if (k == options.max_iterations)
      return give_up(NewtonOutcome::diverged, "not converged in " + std::to_string(options.max_iterations) + " iterations");

    // Correction K c = -r, with a new factorization unless a reused one is still contracting well.
    // A reused factorization is kept only if its correction passes the line search with a full step;
    // otherwise (a short step, no decrease, or material failure such as J <= 0 at every trial point)
    // the iteration is redone with the tangent at the current iterate before anything is given up.
    new_tangent = !reuse || !held.current;
    refreshed = false;
    Eigen::VectorXd c;
    LineSearch ls;
    for (;;) {
      try {
        if (new_tangent) {
          if (!have_tangent) ev = problem.evaluate(x, r, true);  // same x: same r, now with its tangent
          linear.factorize(problem.tangent());
          held.current = true;
          held.uses = 0;
        }
        c = linear.solve(-r);
        ++held.uses;
      } catch (const SingularMatrixError& e) {
        return give_up(NewtonOutcome::singular, e.what());
      } catch (const LinearSolveError& e) {
        return give_up(NewtonOutcome::linear_solve_failed, e.what());
      }
      ls = line_search(problem, x, c, it.residual_norm, options, !reuse, r_trial, ev);
      if (new_tangent || (ls.accepted && ls.step == 1.0)) break;
      new_tangent = refreshed = true;
      have_tangent = false;
    }
    if (refreshed) ++result.tangent_refreshes;
    double s = ls.step;
    if (!ls.accepted) {
      if (ls.best_step == 0.0)
        return give_up(NewtonOutcome::failed, "material failure at every line-search point: " + ev.message);
      s = ls.best_step;  // no sufficient decrease: take the best trial; the divergence test decides later
      ev = problem.evaluate(x + s * c, r_trial, !reuse);
    }
    have_tangent = !reuse;
    if (reuse && (s < 1.0 || r_trial.norm() > options.tangent_reuse.max_contraction * it.residual_norm))
      held.current = false;
    energy = std::abs(s * c.dot(r));
    if (k == 0) first_energy = energy;
    x += s * c;
    r.swap(r_trial);
    ++result.iterations;
    result.dt_factor = std::min(result.dt_factor, ev.dt_factor);
    c_max = s * max_abs(c);
    step = s;
  }
}

}  // namespace cushion::solver
