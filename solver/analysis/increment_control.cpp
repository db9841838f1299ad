#include "solver/analysis/increment_control.hpp"

#include <algorithm>
#include <cmath>

namespace cushion::solver {

IncrementLimits increment_limits(const StepSpec& step, const SolverSpec& solver) {
  IncrementLimits l;
  l.period = step.period;
  l.initial = step.increment.initial;
  l.min = step.increment.min;
  l.max = step.increment.max;
  l.max_increments = step.increment.max_increments;
  l.max_cutbacks = solver.max_cutbacks;
  l.cutback_factor = solver.cutback_factor;
  l.growth_factor = solver.growth_factor;
  if (step.increment.fixed) l.growth_factor = 1.0, l.max_cutbacks = 0, l.min = l.initial;
  return l;
}

IncrementControl::IncrementControl(const IncrementLimits& limits, std::vector<double> targets)
    : limits_(limits), dt_(std::min(limits.initial, limits.period)) {
  // Targets closer than 1e-12 of the period to each other or to the end are merged.
  const double eps = 1e-12 * limits_.period;
  std::erase_if(targets, [&](double t) { return !(t > eps && t < limits_.period - eps); });
  targets.push_back(limits_.period);
  std::sort(targets.begin(), targets.end());
  for (double t : targets)
    if (targets_.empty() || t - targets_.back() > eps) targets_.push_back(t);
}

double IncrementControl::next_end() const {
  const double target = *std::upper_bound(targets_.begin(), targets_.end(), time_);
  const double remaining = target - time_;
  if (remaining <= dt_ * (1.0 + 1e-9)) return target;
  if (remaining < 1.5 * dt_) return time_ + 0.5 * remaining;  // no sliver before the target
  return time_ + dt_;
}

bool IncrementControl::is_target(double t) const {
  return std::binary_search(targets_.begin(), targets_.end(), t);
}

bool IncrementControl::accept(double end, int iterations, double dt_factor) {
  time_ = end;
  ++increments_;
  cutbacks_in_row_ = 0;
  if (dt_factor < 1.0)
    dt_ *= dt_factor;
  else if (iterations <= limits_.easy_iterations && !cut_since_accept_)
    dt_ *= limits_.growth_factor;
  dt_ = std::clamp(dt_, limits_.min, limits_.max);
  cut_since_accept_ = false;
  return increments_ <= limits_.max_increments;
}

bool IncrementControl::cut_back(double dt_factor) {
  const double attempted = next_end() - time_;
  dt_ = attempted * std::min(limits_.cutback_factor, dt_factor);
  ++cutbacks_in_row_;
  ++cutbacks_;
  cut_since_accept_ = true;
  return cutbacks_in_row_ <= limits_.max_cutbacks && dt_ >= limits_.min * (1.0 - 1e-12);
}

}  // namespace cushion::solver
