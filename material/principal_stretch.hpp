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
  bool aligned = false;  ///< E was diagonal (the point driver's uniaxial and volumetric paths): N = I, no eigen-solve
  std::string failure;  ///< non-empty: J <= 0 or the decomposition failed (then s, N are unusable)
};
Stretches decompose(const Mat3& F);

/// (x^p - y^p) / (x^2 - y^2) for x = e^s, y = e^t, without cancellation as x -> y (limit p/2 e^{(p-2)t}).
double power_difference_quotient(double p, double s, double t);

/// The term-independent part of the quotients q_p = (l_b^p - l_a^p) / (l_b^2 - l_a^2) of one pair a < b at
/// s_a = ln l_a, d = s_b - s_a, for a series over terms that evaluates q_p for several p (Hyperfoam): the same
/// cancellation-free form q_p = e^{(p-2) s_a} expm1(p d) / expm1(2 d) (limit p/2 e^{(p-2) s_a} at d = 0), with
/// expm1(2d) and l_a^-4 computed once and q_{-2} = -1/(l_a^2 l_b^2) in closed form (expm1(-2d)/expm1(2d) = -e^{-2d}).
struct StretchPair {
  StretchPair() = default;
  StretchPair(const Vec3& s, int a, int b);
  /// q_{alpha-2}, given l_a^alpha.
  double q_alpha_minus2(double alpha, double la_alpha) const;
  int a = 0, b = 0;
  double d = 0.0;         ///< s_b - s_a
  double expm1_2d = 0.0;  ///< expm1(2 d)
  double inv_la4 = 0.0;   ///< l_a^-4
  double q_minus2 = 0.0;  ///< q_{-2} = -1 / (l_a^2 l_b^2)
};

/// W, PK2 S = sum S_a N_a N_a and dS/dE (principal part plus the spin part 2 G_ab dE_ab) of a response;
/// status failed with `model: ...` if anything is not finite.
ElasticEval assemble(const Response& r, const Stretches& st, const std::string& model);

/// An ElasticEval with status failed and message "<model>: <why>".
ElasticEval failure(const std::string& model, const std::string& why);

}  // namespace cushion::material::principal
