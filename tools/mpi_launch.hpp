#pragma once
/// Whether this process was started by an MPI launcher (mpirun/mpiexec of OpenMPI or MPICH), read
/// from the launcher's environment, so that the program can tell before MPI is started (or in a
/// build without MPI) that it is one of several processes.
#include <cstdlib>
#include <string>

namespace cushion::tools {

/// The value of the first of `names` that is set, as an integer; `fallback` if none is.
inline int launcher_value(std::initializer_list<const char*> names, int fallback) {
  for (const char* name : names)
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return fallback;
}

/// Processes started together by mpirun -np N (1 when not started by mpirun).
inline int launched_processes() { return launcher_value({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}, 1); }
/// This process's rank among them (0 when not started by mpirun).
inline int launched_rank() { return launcher_value({"OMPI_COMM_WORLD_RANK", "PMI_RANK"}, 0); }

}  // namespace cushion::tools
