#pragma once
/// The Uzawa (augmented Lagrangian) loop around Newton: solve, then let every contact set update
/// its multipliers until all penetrations are within their tolerances.
#include <functional>
#include <string>
#include <vector>

#include "solver/contact/contact_set.hpp"
#include "solver/newton.hpp"

namespace cushion::solver {

/// Outcome of one increment attempt with contact.
struct AugmentedResult {
  NewtonResult newton;         ///< the last Newton solve (its outcome decides convergence)
  int solves = 0;              ///< Newton solves (1 + augmentations)
  int iterations = 0;          ///< Newton corrections over all solves
  double max_penetration = 0;  ///< largest penetration at the end [mm]
  bool penetration_failed = false;  ///< tolerance not reachable within max_augmentations
  std::string message;         ///< when penetration_failed: names contact, penalty and remedy
  /// True if Newton converged and every set met its penetration tolerance.
  bool converged() const { return newton.converged() && !penetration_failed; }
};

/// Runs `newton_solve` (a Newton solve of the increment from the current iterate, which must keep
/// its x between calls) and, while any set's penetration exceeds its tolerance, augments and
/// solves again. Calls begin_attempt() on every set first.
AugmentedResult solve_augmented(const std::function<NewtonResult()>& newton_solve, const std::vector<ContactSet*>& sets);

/// Throws cushion::InputError if a node of `set` penetrates the indenter by more than the set's
/// tolerance at displacements u [mm] (e.g. the indenter starts inside the block); `when` names
/// the time in the message.
void check_no_initial_penetration(const ContactSet& set, const Eigen::VectorXd& u, const std::string& when);

}  // namespace cushion::solver
