#include "solver/dynamics/modes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace cushion::solver::dynamics {

std::vector<double> natural_frequencies(const SparseMatrix& K, const SparseMatrix& M, const std::vector<int>& free,
                                        int count) {
  const auto n = static_cast<Eigen::Index>(free.size());
  if (n > 6000) throw std::invalid_argument("natural_frequencies: dense solver limited to 6000 free DOFs");
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::MatrixXd Kf(n, n), Mf(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) Kf(i, j) = Kd(free[i], free[j]), Mf(i, j) = Md(free[i], free[j]);
  Kf = 0.5 * (Kf + Kf.transpose()).eval();
  Mf = 0.5 * (Mf + Mf.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kf, Mf);
  if (es.info() != Eigen::Success) throw std::invalid_argument("natural_frequencies: M_ff not positive definite");
  std::vector<double> f;
  for (Eigen::Index i = 0; i < n && static_cast<int>(f.size()) < count; ++i)
    f.push_back(std::sqrt(std::max(0.0, es.eigenvalues()(i))) / (2.0 * M_PI));
  return f;
}

std::vector<double> frequency_points(double low, double high, int points, double bias, std::vector<double> resonances) {
  if (!(low > 0.0) || !(high >= low) || points < 2 || !(bias >= 1.0))
    throw std::invalid_argument("frequency_points: need 0 < low <= high, points >= 2, bias >= 1");
  if (high == low) return {low};
  std::sort(resonances.begin(), resonances.end());
  std::vector<double> ends{low};
  for (double r : resonances)
    if (r > low && r < high && r - ends.back() >= 1e-5) ends.push_back(r);
  ends.push_back(high);
  std::vector<double> f{low};
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    const double a = ends[i], b = ends[i + 1];
    for (int j = 1; j < points; ++j) {
      const double y = -1.0 + 2.0 * j / (points - 1);
      const double spread = std::abs(y) < 1e-12 ? 0.0 : std::copysign(std::pow(std::abs(y), 1.0 / bias), y);
      f.push_back(0.5 * (a + b) + 0.5 * (b - a) * spread);
    }
  }
  return f;
}

}  // namespace cushion::solver::dynamics
