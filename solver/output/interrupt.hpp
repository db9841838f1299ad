#pragma once
/// Ctrl-C handling for long runs. While an InterruptGuard lives, the first SIGINT only sets a flag
/// (and prints one line); the step loop polls interrupt_requested(), finishes the current frame,
/// closes its files and throws Interrupted (the program exits non-zero with its message). The
/// handler is one-shot (SA_RESETHAND): a second Ctrl-C gets the default action and ends the process.
#include <stdexcept>
#include <string>

namespace cushion::solver {

/// True once SIGINT arrived while a guard was installed (async-signal-safe flag).
bool interrupt_requested();

/// Clears the flag (a new run, or tests).
void clear_interrupt();

class InterruptGuard {
 public:
  InterruptGuard();   ///< clears the flag and installs the handler
  ~InterruptGuard();  ///< restores the previous SIGINT disposition
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  struct Saved;
  Saved* saved_;
};

/// Thrown by the step driver after it has closed its output on an interrupt.
class Interrupted : public std::runtime_error {
 public:
  /// `time`: total time of the last frame written [s].
  explicit Interrupted(double time);
};

}  // namespace cushion::solver
