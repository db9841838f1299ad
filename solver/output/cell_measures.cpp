#include "solver/output/cell_measures.hpp"

#include <cmath>

namespace cushion::solver {

double von_mises(const Mat3& sigma) {
  const Mat3 s = sigma - sigma.trace() / 3.0 * Mat3::Identity();
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

double pressure(const Mat3& sigma) { return -sigma.trace() / 3.0; }

Mat3 log_strain(const Mat3& F) {
  // B = F F^T = Q diag(lambda^2) Q^T, so ln V = Q diag(ln lambda) Q^T.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(F * F.transpose());
  const Vec3 ln_lambda = 0.5 * eig.eigenvalues().array().log();
  return eig.eigenvectors() * ln_lambda.asDiagonal() * eig.eigenvectors().transpose();
}

Vec3 principal_stretches(const Mat3& F) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(F * F.transpose(), Eigen::EigenvaluesOnly);
  const Vec3 ascending = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return ascending.reverse();
}

}  // namespace cushion::solver
