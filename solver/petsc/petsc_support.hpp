#pragma once
/// Internal to solver/petsc: PETSc error codes as exceptions, and the options scope of a solver.
#include <petscsys.h>

#include <string>

namespace cushion::solver::petsc {

/// "<PETSc's text for the code>: <the specific message of PETSc's last error>".
std::string error_text(PetscErrorCode code);

/// Throws LinearSolveError("PETSc: <call>: <error_text>") unless `code` is 0.
void check(PetscErrorCode code, const char* call);

/// Makes `options` PETSc's default options database for the lifetime of the scope (PetscOptionsPush /
/// Pop), so every object PETSc creates meanwhile (multigrid levels, sub-solvers) reads it.
class OptionsScope {
 public:
  explicit OptionsScope(PetscOptions options) { check(PetscOptionsPush(options), "PetscOptionsPush"); }
  ~OptionsScope() { PetscOptionsPop(); }
  OptionsScope(const OptionsScope&) = delete;
  OptionsScope& operator=(const OptionsScope&) = delete;
};

/// Discards everything PETSc prints (monitors, -ksp_view) for the lifetime of the scope.
class SilenceScope {
 public:
  SilenceScope();
  ~SilenceScope();
  SilenceScope(const SilenceScope&) = delete;
  SilenceScope& operator=(const SilenceScope&) = delete;

 private:
  PetscErrorCode (*saved_)(FILE*, const char[], va_list);
};

}  // namespace cushion::solver::petsc
