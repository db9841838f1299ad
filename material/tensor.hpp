#pragma once
/// Small-tensor types and Voigt conventions shared by every material and element.
///
/// Voigt order for symmetric second-order tensors: [11, 22, 33, 12, 23, 13].
///  - Stress-like (S, sigma): tensor components, v = [S11, S22, S33, S12, S23, S13].
///  - Strain-like (E): engineering shear, v = [E11, E22, E33, 2E12, 2E23, 2E13],
///    so that the work product is S:E = dot(S_voigt, E_voigt) and a tangent C (6x6)
///    maps dE_voigt to dS_voigt with C(I,J) = C_ijkl for I~(ij), J~(kl).
#include <Eigen/Dense>
#include <complex>

namespace cushion {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6c = Eigen::Matrix<std::complex<double>, 6, 1>;
using Mat6c = Eigen::Matrix<std::complex<double>, 6, 6>;

/// Voigt index of the symmetric pair (i, j), i, j in {0,1,2}.
constexpr int voigt_index(int i, int j) {
  if (i == j) return i;
  const int s = i + j;  // (0,1)->1, (1,2)->3, (0,2)->2
  return s == 1 ? 3 : (s == 3 ? 4 : 5);
}

/// Symmetric tensor -> stress-like Voigt vector (tensor shear components).
inline Vec6 to_voigt_stress(const Mat3& A) {
  Vec6 v;
  v << A(0, 0), A(1, 1), A(2, 2), A(0, 1), A(1, 2), A(0, 2);
  return v;
}

/// Symmetric tensor -> strain-like Voigt vector (engineering shear, 2*A_ij).
inline Vec6 to_voigt_strain(const Mat3& A) {
  Vec6 v;
  v << A(0, 0), A(1, 1), A(2, 2), 2.0 * A(0, 1), 2.0 * A(1, 2), 2.0 * A(0, 2);
  return v;
}

/// Stress-like Voigt vector -> symmetric tensor.
inline Mat3 from_voigt_stress(const Vec6& v) {
  Mat3 A;
  A << v(0), v(3), v(5), v(3), v(1), v(4), v(5), v(4), v(2);
  return A;
}

/// Strain-like Voigt vector (engineering shear) -> symmetric tensor.
inline Mat3 from_voigt_strain(const Vec6& v) {
  Mat3 A;
  A << v(0), 0.5 * v(3), 0.5 * v(5), 0.5 * v(3), v(1), 0.5 * v(4), 0.5 * v(5), 0.5 * v(4), v(2);
  return A;
}

/// Green-Lagrange strain E = (F^T F - I)/2 (reference frame, dimensionless).
inline Mat3 green_lagrange(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }

/// Cauchy stress sigma = F S F^T / J from PK2 stress S (same stress unit).
inline Mat3 cauchy_from_pk2(const Mat3& F, const Mat3& S) {
  return F * S * F.transpose() / F.determinant();
}

/// First Piola-Kirchhoff (nominal) stress P = F S (force per reference area).
inline Mat3 pk1_from_pk2(const Mat3& F, const Mat3& S) { return F * S; }

}  // namespace cushion
