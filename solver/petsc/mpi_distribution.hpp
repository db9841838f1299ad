#pragma once
/// The Distribution (solver/distribution.hpp) of a run started by `mpirun -np N`: the processes of
/// PETSC_COMM_WORLD, the nodes partitioned by METIS (k-way, on the graph of nodes sharing an element,
/// computed on process 0 and broadcast, so every process has the same partition).
#include <memory>

#include "mesh/mesh.hpp"
#include "solver/distribution.hpp"

namespace cushion::solver::petsc {

/// Number of processes PETSc runs on (1 without mpirun). Needs a live petsc::Session.
int world_size();
/// This process's rank in PETSC_COMM_WORLD. Needs a live petsc::Session.
int world_rank();

/// The partition of `mesh` over the processes of PETSC_COMM_WORLD (size >= 2), collective. Needs a live
/// petsc::Session. Throws std::runtime_error if METIS fails.
std::shared_ptr<const Distribution> make_distribution(const mesh::Mesh& mesh);

/// METIS k-way partition of the nodes of `mesh` into `parts` (>= 2) parts: the part of every node.
/// Nodes in no element go to part 0. Throws std::runtime_error if METIS fails.
std::vector<int> partition_nodes(const mesh::Mesh& mesh, int parts);

}  // namespace cushion::solver::petsc
