#pragma once
/// Shared machinery of isotropic hyperelastic models written in principal stretches (Hyperfoam,
/// Ogden): the spectral decomposition of E, and PK2 stress and tangent in the reference frame from
/// the principal Kirchhoff stresses as functions of the log stretches s_a = ln l_a.
#include <string>

#include "material/hyperelastic.hpp"

namespace cushion::material::principal {

/// What a principal-stretch model supplies at log principal stretches s.
struct Response {
  double W = 0.0;            ///< strain energy [MPa]
  Vec3 tau = Vec3::Zero();   ///< Kirchhoff principal stresses tau_a [MPa]
  Mat3 dtau = Mat3::Zero();  ///< dtau_a / d ln l_b [MPa]
  Mat3 G = Mat3::Zero();     ///< (S_b - S_a) / (l_b^2 - l_a^2) for a != b [MPa], S_a = tau_a / l_a^2
};

/// Log principal stretches s (ascending) and reference principal directions N (columns) of F.
struct Stretches {
  Vec3 s = Vec3::Zero();
  Mat3 N = Mat3::Identity();
  std::string failure;  ///< non-empty: J <= 0 or the decomposition failed (then s, N are unusable)
};
Stretches decompose(const Mat3& F);

/// (x^p - y^p) / (x^2 - y^2) for x = e^s, y = e^t, without cancellation as x -> y (limit p/2 e^{(p-2)t}).
double power_difference_quotient(double p, double s, double t);

/// W, PK2 S = sum S_a N_a N_a and dS/dE (principal part plus the spin part 2 G_ab dE_ab) of a response;
/// status failed with `model: ...` if anything is not finite.
ElasticEval assemble(const Response& r, const Stretches& st, const std::string& model);

/// An ElasticEval with status failed and message "<model>: <why>".
ElasticEval failure(const std::string& model, const std::string& why);

}  // namespace cushion::material::principal
