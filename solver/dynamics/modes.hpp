#pragma once
/// Natural frequencies of the undamped linearised model: K_R(0) phi = w^2 M phi on the free DOFs
/// (K_R(0): long-term base-state tangent, material + geometric; M: consistent mass). Dense
/// generalized self-adjoint solver (Eigen): for small models and verification (a few thousand DOFs).
#include <vector>

#include "solver/assembler.hpp"

namespace cushion::solver::dynamics {

/// Lowest `count` natural frequencies [Hz], ascending, of (K, M) restricted to the DOFs `free`
/// (K [N/mm], M [t], all-DOF matrices, symmetrised). Throws std::invalid_argument if M_ff is not
/// positive definite or the system has more than 6000 free DOFs (dense solver).
std::vector<double> natural_frequencies(const SparseMatrix& K, const SparseMatrix& M, const std::vector<int>& free,
                                        int count);

}  // namespace cushion::solver::dynamics
