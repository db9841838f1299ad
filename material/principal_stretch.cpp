#include "material/principal_stretch.hpp"

#include <cmath>

namespace cushion::material::principal {

ElasticEval failure(const std::string& model, const std::string& why) {
  ElasticEval e;
  e.status = Status::failed;
  e.message = model + ": " + why;
  return e;
}

double power_difference_quotient(double p, double s, double t) {
  // e^{(p-2)t} expm1(p d) / expm1(2 d), d = s - t: relative accuracy does not degrade as x -> y,
  // so no "nearly equal stretches" branch is needed.
  const double d = s - t;
  const double scale = std::exp((p - 2.0) * t);
  if (d == 0.0) return 0.5 * p * scale;
  return scale * std::expm1(p * d) / std::expm1(2.0 * d);
}

StretchPair::StretchPair(const Vec3& s, int a_, int b_) : a(a_), b(b_), d(s(b_) - s(a_)) {
  expm1_2d = std::expm1(2.0 * d);
  inv_la4 = std::exp(-4.0 * s(a_));
  q_minus2 = -std::exp(-2.0 * (s(a_) + s(b_)));
}

double StretchPair::q_alpha_minus2(double alpha, double la_alpha) const {
  const double scale = la_alpha * inv_la4;  // e^{(alpha - 4) s_a}
  if (d == 0.0) return 0.5 * (alpha - 2.0) * scale;
  return scale * std::expm1((alpha - 2.0) * d) / expm1_2d;
}

namespace {

/// Principal values e and directions N (columns) of the symmetric E; a diagonal E is taken as it is (aligned).
bool principal_frame(const Mat3& E, Vec3& e, Mat3& N, bool& aligned) {
  aligned = E(0, 1) == 0.0 && E(0, 2) == 0.0 && E(1, 2) == 0.0 && E(1, 0) == 0.0 && E(2, 0) == 0.0 && E(2, 1) == 0.0;
  if (aligned) {
    e = E.diagonal();
    N.setIdentity();
    return true;
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(E);
  if (eig.info() != Eigen::Success) return false;
  e = eig.eigenvalues();
  N = eig.eigenvectors();
  return true;
}

/// S and dS/dE (Voigt) from the principal S_a, D_ab = dS_a/dE_b and the spin moduli G_ab, principal directions N_a.
/// Spin part: dS_ab = 2 G_ab dE_ab in the principal frame. With m_ab = Voigt_stress(N_a N_b + N_b N_a),
/// m_ab . dE_voigt = 2 dE_ab (engineering shear), so the term is G_ab m_ab m_ab^T.
void assemble_rotated(const Vec3& S_a, const Mat3& D, const Mat3& G, const Mat3& N, ElasticEval& out) {
  Vec6 v[3];
  for (int a = 0; a < 3; ++a) v[a] = to_voigt_stress(N.col(a) * N.col(a).transpose());
  for (int a = 0; a < 3; ++a) {
    out.S += S_a(a) * v[a];
    for (int b = 0; b < 3; ++b) out.dS_dE += D(a, b) * v[a] * v[b].transpose();
  }
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const Vec6 m = to_voigt_stress(N.col(a) * N.col(b).transpose() + N.col(b) * N.col(a).transpose());
      out.dS_dE += G(a, b) * m * m.transpose();
    }
}

/// The same for N = I (v_a and m_ab are unit Voigt vectors): the entries are set directly.
void assemble_aligned(const Vec3& S_a, const Mat3& D, const Mat3& G, ElasticEval& out) {
  out.S.head<3>() = S_a;
  out.dS_dE.topLeftCorner<3, 3>() = D;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) out.dS_dE(voigt_index(a, b), voigt_index(a, b)) = G(a, b);
}

}  // namespace

Stretches decompose(const Mat3& F) {
  Stretches out;
  if (!(F.determinant() > 0.0)) {
    out.failure = "J = det F <= 0 (or NaN)";
    return out;
  }
  // E = (F^T F - I)/2 = sym(H) + H^T H / 2 with H = F - I: no round-off cancellation at small strain.
  const Mat3 H = F - Mat3::Identity();
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
  Vec3 e;  // principal Green-Lagrange strains E_a
  if (!principal_frame(E, e, out.N, out.aligned)) {  // column a of N: principal direction N_a (reference frame)
    out.failure = "eigen-decomposition of E failed";
    return out;
  }
  for (int a = 0; a < 3; ++a) {
    if (!(1.0 + 2.0 * e(a) > 0.0)) {
      out.failure = "principal stretch squared <= 0";
      return out;
    }
    // s_a = ln l_a = ln(1 + 2 E_a) / 2; equal strains (a uniaxial path: E_2 = E_3) share one logarithm
    out.s(a) = a > 0 && e(a) == e(a - 1) ? out.s(a - 1) : 0.5 * std::log1p(2.0 * e(a));
  }
  return out;
}

ElasticEval assemble(const Response& p, const Stretches& st, const std::string& model) {
  // S_a = tau_a / l_a^2;  D_ab = dS_a/dE_b = [dtau_a/dln l_b - 2 tau_a delta_ab] / (l_a^2 l_b^2).
  Vec3 S_a, inv_c;
  for (int a = 0; a < 3; ++a) {
    inv_c(a) = a > 0 && st.s(a) == st.s(a - 1) ? inv_c(a - 1) : std::exp(-2.0 * st.s(a));
    S_a(a) = p.tau(a) * inv_c(a);
  }
  Mat3 D;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) D(a, b) = (p.dtau(a, b) - (a == b ? 2.0 * p.tau(a) : 0.0)) * inv_c(a) * inv_c(b);
  ElasticEval out;
  out.W = p.W;
  if (st.aligned)
    assemble_aligned(S_a, D, p.G, out);
  else
    assemble_rotated(S_a, D, p.G, st.N, out);
  if (!std::isfinite(out.W) || !out.S.allFinite() || !out.dS_dE.allFinite())
    return failure(model, "non-finite energy, stress or tangent (stretches out of range)");
  return out;
}

}  // namespace cushion::material::principal
