#pragma once
/// The last few model runs of a fit, by the exact parameter vector they ran at (thread-safe).
///
/// Why: a fit asks for the same point more than once. Ceres' Levenberg-Marquardt evaluates the cost at a trial step and,
/// when it accepts the step, evaluates the residuals and Jacobian at that same point again (one whole model run an
/// iteration, out of the n + 1 of a forward-difference Jacobian); the start scan's last trial is run again by
/// TrialScore::start_from and by Levenberg-Marquardt's first evaluation; a Jacobian step clamped back onto a bound runs
/// the centre again. A model run is deterministic in its parameters, so a run found here is bit for bit the one a new
/// run would give, and a fit's path and result do not change (docs/physics.md 9.20).
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

namespace cushion::calibration {

template <class Result>
class RecentRuns {
 public:
  explicit RecentRuns(std::size_t capacity = 8) : capacity_(capacity) {}

  /// The result kept for exactly u (every component equal), if any.
  std::optional<std::optional<Result>> find(const std::vector<double>& u) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [key, result] : runs_)
      if (key == u) {
        ++hits_;
        return result;
      }
    return std::nullopt;
  }
  /// Keeps the result of a run at u (a failed run too: nullopt), forgetting the oldest beyond the capacity.
  void keep(std::vector<double> u, const std::optional<Result>& result) {
    const std::lock_guard<std::mutex> lock(mutex_);
    runs_.emplace_back(std::move(u), result);
    if (runs_.size() > capacity_) runs_.pop_front();
  }
  /// How many lookups found their point.
  int hits() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return hits_;
  }

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  mutable int hits_ = 0;
  std::deque<std::pair<std::vector<double>, std::optional<Result>>> runs_;
};

}  // namespace cushion::calibration
