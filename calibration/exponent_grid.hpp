#pragma once
/// The exponent grid of the hyperfoam fits' global search (calibration/hyperfoam_fit.cpp and
/// calibration/hyperfoam_modes_fit.cpp): exponents alpha of both signs, and the N-subsets of a grid.
#include <vector>

namespace cushion::calibration {

/// Exponents of both signs with |alpha| <= alpha_max, spaced roughly geometrically; coarser for N >= 4 and
/// N >= 5 so that the number of N-subsets stays a few thousand. Negative values first, increasing.
std::vector<double> alpha_grid(int N, double alpha_max);

/// Every N-subset of {0 .. size-1}, indices increasing.
std::vector<std::vector<int>> subsets(int size, int N);

}  // namespace cushion::calibration
