#include "calibration/exponent_grid.hpp"

#include <functional>

namespace cushion::calibration {

std::vector<double> alpha_grid(int N, double alpha_max) {
  std::vector<double> positive{0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 15.0, 18.0, 22.0, 27.0, 33.0, 40.0, 50.0};
  std::vector<double> negative{-0.5, -1.0, -1.5, -2.0, -2.5, -3.0, -4.0, -5.0, -6.0, -8.0, -10.0, -13.0, -16.0, -20.0};
  if (N >= 4) {
    positive = {0.5, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 18.0, 27.0, 40.0};
    negative = {-0.5, -1.0, -2.0, -3.0, -5.0, -8.0, -13.0, -20.0};
  }
  if (N >= 5) {
    positive = {1.0, 2.0, 4.0, 8.0, 15.0, 27.0, 45.0};
    negative = {-1.0, -2.0, -4.0, -8.0, -16.0};
  }
  std::vector<double> grid;
  for (double a : negative)
    if (-a <= alpha_max) grid.push_back(a);
  for (double a : positive)
    if (a <= alpha_max) grid.push_back(a);
  return grid;
}

std::vector<std::vector<int>> subsets(int size, int N) {
  std::vector<std::vector<int>> out;
  std::vector<int> pick(N);
  std::function<void(int, int)> choose = [&](int depth, int from) {
    if (depth == N) {
      out.push_back(pick);
      return;
    }
    for (int k = from; k < size; ++k) {
      pick[depth] = k;
      choose(depth + 1, k + 1);
    }
  };
  choose(0, 0);
  return out;
}

}  // namespace cushion::calibration
