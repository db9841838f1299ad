#pragma once
/// Shared helpers for the material tests: states built from C or principal stretches, random
/// rotations and central finite differences of the PK2 stress with respect to the Green-Lagrange
/// strain in the Voigt convention of material/tensor.hpp (engineering shear in E).
#include <functional>
#include <random>

#include "material/tensor.hpp"

namespace cushion::material::test {

/// A deformation gradient with F^T F = C (C symmetric positive definite): F = L^T, C = L L^T.
inline Mat3 F_from_C(const Mat3& C) { return Eigen::LLT<Mat3>(C).matrixU(); }

/// Random rotation (uniform enough for tests: QR of a Gaussian matrix, det fixed to +1).
inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Mat3 A;
  for (int i = 0; i < 9; ++i) A(i) = n(rng);
  Mat3 Q = Eigen::HouseholderQR<Mat3>(A).householderQ();
  if (Q.determinant() < 0.0) Q.col(0) *= -1.0;
  return Q;
}

/// F = R diag(l) Q^T with random rotations R, Q: principal stretches exactly l.
inline Mat3 F_with_stretches(const Vec3& l, std::mt19937& rng) {
  return random_rotation(rng) * l.asDiagonal() * random_rotation(rng).transpose();
}

/// Random deformation gradient with det F > 0 (identity plus a random perturbation of size `size`).
inline Mat3 random_F(std::mt19937& rng, double size = 0.4) {
  std::uniform_real_distribution<double> u(-size, size);
  for (;;) {
    Mat3 F = Mat3::Identity();
    for (int i = 0; i < 9; ++i) F(i) += u(rng);
    if (F.determinant() > 0.2) return F;
  }
}

/// Central differences of a Voigt-valued function of F with respect to E (engineering shear):
/// column K is [f(C + 2 dE_K) - f(C - 2 dE_K)] / (2 h), dE_K = from_voigt_strain(h e_K).
/// Error O(h^2 f''') + O(eps f / h).
inline Mat6 fd_dS_dE(const std::function<Vec6(const Mat3&)>& S_of_F, const Mat3& F, double h = 1e-6) {
  const Mat3 C = F.transpose() * F;
  Mat6 D;
  for (int K = 0; K < 6; ++K) {
    Vec6 e = Vec6::Zero();
    e(K) = h;
    const Mat3 dC = 2.0 * from_voigt_strain(e);
    D.col(K) = (S_of_F(F_from_C(C + dC)) - S_of_F(F_from_C(C - dC))) / (2.0 * h);
  }
  return D;
}

/// Central differences of a scalar function of F with respect to E (engineering shear), a Voigt
/// stress-like vector: dW/dE_K.
inline Vec6 fd_dW_dE(const std::function<double(const Mat3&)>& W_of_F, const Mat3& F, double h = 1e-6) {
  const Mat3 C = F.transpose() * F;
  Vec6 g;
  for (int K = 0; K < 6; ++K) {
    Vec6 e = Vec6::Zero();
    e(K) = h;
    const Mat3 dC = 2.0 * from_voigt_strain(e);
    g(K) = (W_of_F(F_from_C(C + dC)) - W_of_F(F_from_C(C - dC))) / (2.0 * h);
  }
  return g;
}

/// max |A - B| / max |B| (norm-wise relative difference).
template <class A, class B>
double rel_diff(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace cushion::material::test
