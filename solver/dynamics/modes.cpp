#include "solver/dynamics/modes.hpp"

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

}  // namespace cushion::solver::dynamics
