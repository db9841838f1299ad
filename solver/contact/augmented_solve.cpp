#include "solver/contact/augmented_solve.hpp"

#include <algorithm>
#include <cstdio>

#include "io/input_error.hpp"

namespace cushion::solver {

AugmentedResult solve_augmented(const std::function<NewtonResult()>& newton_solve, const std::vector<ContactSet*>& sets) {
  AugmentedResult out;
  for (ContactSet* s : sets) s->begin_attempt();
  for (;;) {
    out.newton = newton_solve();
    ++out.solves;
    out.iterations += out.newton.iterations;
    if (!out.newton.converged()) return out;
    bool all_within = true;
    out.max_penetration = 0.0;
    for (ContactSet* s : sets) {
      const AugmentOutcome a = s->augment();
      out.max_penetration = std::max(out.max_penetration, a.max_penetration);
      all_within = all_within && a.converged;
      if (a.failed && !out.penetration_failed) out.penetration_failed = true, out.message = a.message;
    }
    if (all_within || out.penetration_failed) return out;
  }
}

void check_no_initial_penetration(const ContactSet& set, const Eigen::VectorXd& u, const std::string& when) {
  const auto [depth, label] = set.penetration_at(u);
  if (depth <= set.parameters().tolerance) return;
  char text[160];
  std::snprintf(text, sizeof text, "penetrates the indenter by %.4g mm", depth);
  throw InputError("contact '" + set.name() + "': the indenter starts inside the block " + when + ": node " +
                   std::to_string(label) + " " + text + " (tolerance " + std::to_string(set.parameters().tolerance) +
                   " mm); move the indenter (" + set.surface().describe() + ") clear of the foam surface");
}

}  // namespace cushion::solver
