#include "solver/petsc/petsc_session.hpp"

#include <petscsys.h>

#include <cstdlib>
#include <stdexcept>

#include "solver/linear_solver.hpp"
#include "solver/petsc/petsc_support.hpp"

namespace cushion::solver::petsc {

namespace {

bool started = false;  // a Session was made in this process (MPI cannot restart)
bool running = false;  // ... and exists now

PetscErrorCode print_nothing(FILE*, const char[], va_list) { return 0; }

}  // namespace

std::string error_text(PetscErrorCode code) {
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string message = text ? text : "PETSc error " + std::to_string(code);
  if (specific && *specific) message += std::string(": ") + specific;
  return message;
}

void check(PetscErrorCode code, const char* call) {
  if (code) throw LinearSolveError(std::string("PETSc: ") + call + ": " + error_text(code));
}

SilenceScope::SilenceScope() : saved_(PetscVFPrintf) { PetscVFPrintf = print_nothing; }
SilenceScope::~SilenceScope() { PetscVFPrintf = saved_; }

Session::Session() {
  if (started) throw std::runtime_error("PETSc can be started only once per process");
  // Set before PetscInitialize, which reads them: no signal handlers (SIGINT stays cushion's).
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  if (PetscInitializeNoArguments()) throw std::runtime_error("PETSc (and MPI) could not be started");
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  started = running = true;
}

Session::~Session() {
  PetscPopErrorHandler();
  PetscFinalize();
  running = false;
}

bool Session::active() { return running; }

void abort_all(int code) {
  MPI_Abort(PETSC_COMM_WORLD, code);
  std::abort();  // MPI_Abort does not return
}

}  // namespace cushion::solver::petsc
