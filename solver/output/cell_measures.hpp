#pragma once
/// Scalar and tensor measures written per element (from averaged Cauchy stress and F).
#include "material/tensor.hpp"

namespace cushion::solver {

/// von Mises equivalent stress sqrt(3/2 s:s), s = deviator of sigma (same unit as sigma).
double von_mises(const Mat3& sigma);

/// Pressure p = -tr(sigma)/3, positive in compression (ABAQUS convention; unit of sigma).
double pressure(const Mat3& sigma);

/// Logarithmic (Hencky) strain ln V = 1/2 ln(F F^T), current frame (ABAQUS LE) [-]; requires det F > 0.
Mat3 log_strain(const Mat3& F);

/// Principal stretches lambda_1 >= lambda_2 >= lambda_3 = sqrt(eig(F F^T)) [-].
Vec3 principal_stretches(const Mat3& F);

}  // namespace cushion::solver
