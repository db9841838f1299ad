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

Stretches decompose(const Mat3& F) {
  Stretches out;
  if (!(F.determinant() > 0.0)) {
    out.failure = "J = det F <= 0 (or NaN)";
    return out;
  }
  // E = (F^T F - I)/2 = sym(H) + H^T H / 2 with H = F - I: no round-off cancellation at small strain.
  const Mat3 H = F - Mat3::Identity();
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(E);
  if (eig.info() != Eigen::Success) {
    out.failure = "eigen-decomposition of E failed";
    return out;
  }
  out.N = eig.eigenvectors();  // column a: principal direction N_a (reference frame)
  for (int a = 0; a < 3; ++a) {
    const double e = eig.eigenvalues()(a);
    if (!(1.0 + 2.0 * e > 0.0)) {
      out.failure = "principal stretch squared <= 0";
      return out;
    }
    out.s(a) = 0.5 * std::log1p(2.0 * e);  // s_a = ln l_a = ln(1 + 2 E_a) / 2
  }
  return out;
}

ElasticEval assemble(const Response& p, const Stretches& st, const std::string& model) {
  const Mat3& N = st.N;
  // S_a = tau_a / l_a^2;  D_ab = dS_a/dE_b = [dtau_a/dln l_b - 2 tau_a delta_ab] / (l_a^2 l_b^2).
  Vec3 S_a, inv_c;
  for (int a = 0; a < 3; ++a) {
    inv_c(a) = std::exp(-2.0 * st.s(a));
    S_a(a) = p.tau(a) * inv_c(a);
  }
  Vec6 v[3];
  for (int a = 0; a < 3; ++a) v[a] = to_voigt_stress(N.col(a) * N.col(a).transpose());

  ElasticEval out;
  out.W = p.W;
  for (int a = 0; a < 3; ++a) {
    out.S += S_a(a) * v[a];
    for (int b = 0; b < 3; ++b) {
      const double D_ab = (p.dtau(a, b) - (a == b ? 2.0 * p.tau(a) : 0.0)) * inv_c(a) * inv_c(b);
      out.dS_dE += D_ab * v[a] * v[b].transpose();
    }
  }
  // Spin part: dS_ab = 2 G_ab dE_ab in the principal frame. With m_ab = Voigt_stress(N_a N_b + N_b N_a),
  // m_ab . dE_voigt = 2 dE_ab (engineering shear), so the term is G_ab m_ab m_ab^T.
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const Mat3 sym = N.col(a) * N.col(b).transpose() + N.col(b) * N.col(a).transpose();
      const Vec6 m = to_voigt_stress(sym);
      out.dS_dE += p.G(a, b) * m * m.transpose();
    }
  if (!std::isfinite(out.W) || !out.S.allFinite() || !out.dS_dE.allFinite())
    return failure(model, "non-finite energy, stress or tangent (stretches out of range)");
  return out;
}

}  // namespace cushion::material::principal
