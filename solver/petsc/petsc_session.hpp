#pragma once
/// PETSc (and the MPI under it) started and stopped in one place: a Session object that the
/// program's main creates when a case chooses "linear_solver": "petsc", before any PETSc solver is
/// made, and destroys after the last one is gone.
namespace cushion::solver::petsc {

/// PetscInitialize on construction, PetscFinalize on destruction. At most one per process, ever:
/// MPI cannot be initialized twice. PETSc is started without command-line arguments (cushion's own
/// are not PETSc options) and without its signal handlers (cushion's interrupt handling stays); its
/// errors are returned to the caller instead of printed, and reported by the solvers as exceptions.
class Session {
 public:
  /// Throws std::runtime_error if PETSc cannot start or a Session was made before in this process.
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  /// True while a Session exists.
  static bool active();
};

/// Stops every process of a distributed run at once (MPI_Abort with exit code `code`): for an error met
/// by one process only, which the others would otherwise wait for. Needs a live Session.
[[noreturn]] void abort_all(int code);

}  // namespace cushion::solver::petsc
