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
  }
  return "unknown";
}

std::string format_iterate(const NewtonIterate& it) {
  char line[200];
  std::snprintf(line, sizeof line, "iter %2d  |r|max %.3e N  |r|2 %.3e N  q %.3e N  |c|max %.3e mm  step %.3f",
                it.iteration, it.residual_max, it.residual_norm, it.force_scale, it.correction_max, it.line_search);
  return line;
}

namespace {

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

bool usable(const ProblemEvaluation& ev, const Eigen::VectorXd& r) {
  return ev.status != material::Status::failed && r.allFinite();
}

}  // namespace

NewtonResult solve_newton(NonlinearProblem& problem, LinearSolver& linear, Eigen::VectorXd& x,
                          const NewtonOptions& options, const std::function<void(const NewtonIterate&)>& log) {
  NewtonResult result;
  const Eigen::VectorXd x0 = x;
  Eigen::VectorXd r, r_trial;
  ProblemEvaluation ev = problem.evaluate(x, r, true);
  if (!usable(ev, r)) {
    result.outcome = NewtonOutcome::failed;
    result.message = "material failure at the start of the increment: " + ev.message;
    return result;
  }
  result.dt_factor = ev.dt_factor;

  double c_max = 0.0, step = 0.0;           // last applied correction and its line-search factor
  double energy = 0.0, first_energy = 0.0;  // |c_k . r_k-1| and |c_1 . r_0|
  for (int k = 0;; ++k) {
    const double q = std::max({options.reference_force, ev.force_scale, options.force_floor});
    const NewtonIterate it{k, max_abs(r), r.norm(), c_max, step, q};
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

    // Divergence tests.
    const int n = static_cast<int>(result.history.size());
    if (options.divergence_iterations > 0 && n > options.divergence_iterations) {
      bool growing = true;
      for (int j = n - options.divergence_iterations; j < n; ++j)
        growing = growing && result.history[j].residual_max > result.history[j - 1].residual_max;
      if (growing) {
        result.outcome = NewtonOutcome::diverged;
        result.message =
            "residual grew in " + std::to_string(options.divergence_iterations) + " consecutive iterations";
        return result;
      }
    }
    if (k == options.max_iterations) {
      result.outcome = NewtonOutcome::diverged;
      result.message = "not converged in " + std::to_string(options.max_iterations) + " iterations";
      return result;
    }

    // Newton correction K c = -r.
    Eigen::VectorXd c;
    try {
      linear.factorize(problem.tangent());
      c = linear.solve(-r);
    } catch (const SingularMatrixError& e) {
      result.outcome = NewtonOutcome::singular;
      result.message = e.what();
      return result;
    }

    // Backtracking line search on ||r||_2: quadratic model of ||r(x + s c)||^2 with slope -2 ||r||^2,
    // new factor clamped to [0.1 s, 0.5 s]; halving after a material failure.
    const double phi0 = it.residual_norm;
    double s = 1.0, best_s = 0.0, best_phi = INFINITY;
    bool accepted = false;
    for (int ls = 0; ls <= options.max_line_search && s >= options.min_step; ++ls) {
      ev = problem.evaluate(x + s * c, r_trial, true);
      if (!usable(ev, r_trial)) {
        s *= 0.5;
        continue;
      }
      const double phi = r_trial.norm();
      if (!options.line_search || phi <= (1.0 - 1e-4 * s) * phi0) {
        accepted = true;
        break;
      }
      if (phi < best_phi) best_phi = phi, best_s = s;
      const double s_model = phi0 * phi0 * s * s / (phi * phi - phi0 * phi0 + 2.0 * phi0 * phi0 * s);
      s = std::clamp(s_model, 0.1 * s, 0.5 * s);
    }
    if (!accepted) {
      if (best_phi == INFINITY) {
        result.outcome = NewtonOutcome::failed;
        result.message = "material failure at every line-search point: " + ev.message;
        return result;
      }
      s = best_s;  // no sufficient decrease: take the best trial; the divergence test decides later
      ev = problem.evaluate(x + s * c, r_trial, true);
    }
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
