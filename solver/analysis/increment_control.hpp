#pragma once
/// Automatic time incrementation of one step (after ABAQUS/Standard): the increment grows by the
/// growth factor after an easy increment, is cut back after a failed attempt, and is shortened so
/// that every target time (amplitude corners, frame times, the step end) is hit exactly. The class
/// only does the bookkeeping of step time [s]; the step driver decides what an attempt is.
#include <string>
#include <vector>

#include "solver/case/case_spec.hpp"

namespace cushion::solver {

/// Limits of the increment control of one step (times in s of step time).
struct IncrementLimits {
  double period = 1.0;          ///< step time period [s]
  double initial = 1.0;         ///< first increment [s]
  double min = 1e-5;            ///< smallest increment allowed [s]
  double max = 1.0;             ///< largest increment allowed [s]
  int max_increments = 100;     ///< converged increments allowed in the step
  int max_cutbacks = 5;         ///< failed attempts in a row allowed
  double cutback_factor = 0.25; ///< increment multiplier after a failed attempt [-]
  double growth_factor = 1.5;   ///< increment multiplier after an easy increment [-]
  int easy_iterations = 5;      ///< an increment with at most this many Newton iterations is easy
};

/// The limits of a step from its case-file specification and the case's solver block.
IncrementLimits increment_limits(const StepSpec& step, const SolverSpec& solver);

/// Step-time bookkeeping of the automatic incrementation.
class IncrementControl {
 public:
  /// `targets`: step times [s] that must be reached exactly (any order, values outside (0, period)
  /// are ignored; the period itself is always a target).
  IncrementControl(const IncrementLimits& limits, std::vector<double> targets);

  double time() const { return time_; }               ///< step time reached [s]
  bool finished() const { return time_ >= limits_.period; }
  /// End time [s] of the next attempt: time() + increment, shortened to the next target (exactly its
  /// value); when the increment would leave less than half an increment before the target, the
  /// remaining interval is split into two equal increments.
  double next_end() const;
  /// True if `t` [s] (as returned by next_end) is one of the targets.
  bool is_target(double t) const;

  /// A converged increment ending at `end` (from next_end()) with `iterations` Newton iterations and
  /// the materials' proposed factor: advances the time, grows the nominal increment after an easy
  /// increment (never right after a cut-back), shrinks it to dt_factor < 1 proposals. Returns false
  /// if max_increments is now exceeded.
  bool accept(double end, int iterations, double dt_factor);
  /// A failed attempt: the nominal increment becomes the attempted one times
  /// min(cutback_factor, dt_factor). Returns false (give up) when more than max_cutbacks attempts
  /// failed in a row or the new increment is below the minimum.
  bool cut_back(double dt_factor);

  double increment() const { return dt_; }            ///< nominal increment [s]
  int increments() const { return increments_; }      ///< converged increments so far
  int cutbacks_in_row() const { return cutbacks_in_row_; }
  int cutbacks() const { return cutbacks_; }          ///< failed attempts in the step
  const IncrementLimits& limits() const { return limits_; }

 private:
  IncrementLimits limits_;
  std::vector<double> targets_;  ///< sorted, unique, in (0, period]
  double time_ = 0.0, dt_ = 0.0;
  int increments_ = 0, cutbacks_in_row_ = 0, cutbacks_ = 0;
  bool cut_since_accept_ = false;
};

}  // namespace cushion::solver
