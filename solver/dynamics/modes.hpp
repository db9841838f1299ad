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

/// Frequencies [Hz] of a steady-state sweep over [low, high] spread as ABAQUS and CalculiX document it
/// for *STEADY STATE DYNAMICS: the `resonances` [Hz] strictly inside the range split it into intervals
/// (values closer than 1e-5 Hz count once); each interval [a, b] gets `points` (>= 2) frequencies
///   f_j = (a + b)/2 + (b - a)/2 sign(y) |y|^(1/bias),  y = -1 + 2 j/(points - 1),  j = 0 .. points - 1,
/// consecutive intervals sharing their end point; bias = 1 spaces them evenly, bias > 1 clusters them at
/// the interval ends (the resonances). low == high gives one frequency. std::invalid_argument on
/// low <= 0, high < low, points < 2 or bias < 1.
std::vector<double> frequency_points(double low, double high, int points, double bias, std::vector<double> resonances);

}  // namespace cushion::solver::dynamics
