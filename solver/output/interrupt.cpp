#include "solver/output/interrupt.hpp"

#include <csignal>
#include <unistd.h>

#include "io/text_support.hpp"

namespace cushion::solver {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_sigint(int) {
  g_interrupted = 1;
  static const char message[] =
      "\ncushion: interrupt received - finishing the current frame (Ctrl-C again to abort now)\n";
  [[maybe_unused]] const auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
}

}  // namespace

struct InterruptGuard::Saved {
  struct sigaction previous {};
};

bool interrupt_requested() { return g_interrupted != 0; }

void clear_interrupt() { g_interrupted = 0; }

InterruptGuard::InterruptGuard() : saved_(new Saved) {
  clear_interrupt();
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // one-shot: the second Ctrl-C takes the default action
  sigaction(SIGINT, &action, &saved_->previous);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &saved_->previous, nullptr);
  delete saved_;
}

Interrupted::Interrupted(double time)
    : std::runtime_error("interrupted by Ctrl-C; results are complete up to t = " + io::format_double(time) +
                         " s") {}

}  // namespace cushion::solver
