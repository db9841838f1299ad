#include "material/hyperfoam.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {

/// Principal quantities of the hyperfoam series at log principal stretches s_a = ln l_a.
struct PrincipalResponse {
  double W = 0.0;                   ///< strain energy [MPa]
  Vec3 tau = Vec3::Zero();          ///< Kirchhoff principal stresses tau_a [MPa]
  Mat3 dtau = Mat3::Zero();         ///< dtau_a / d ln l_b [MPa]
  Mat3 G = Mat3::Zero();            ///< (S_b - S_a) / (l_b^2 - l_a^2) for a != b [MPa]
};

/// (x^p - y^p) / (x^2 - y^2) for x = e^s, y = e^t, written without cancellation as
/// e^{(p-2)t} expm1(p d) / expm1(2 d), d = s - t, with the limit p/2 e^{(p-2)t} at d = 0.
/// Relative accuracy does not degrade as x -> y, so no "nearly equal" branch is needed.
double power_difference_quotient(double p, double s, double t) {
  const double d = s - t;
  const double scale = std::exp((p - 2.0) * t);
  if (d == 0.0) return 0.5 * p * scale;
  return scale * std::expm1(p * d) / std::expm1(2.0 * d);
}

PrincipalResponse principal_response(const std::vector<HyperfoamTerm>& terms, const Vec3& s) {
  PrincipalResponse r;
  const double lnJ = s.sum();
  for (const HyperfoamTerm& term : terms) {
    const double mu = term.mu, a = term.alpha, beta = term.beta();
    // l_a^alpha - 1 and J^(-alpha beta) - 1 in expm1 form: exact near the undeformed state.
    Vec3 la_m1;
    for (int k = 0; k < 3; ++k) la_m1(k) = std::expm1(a * s(k));
    const double Jb_m1 = std::expm1(-a * beta * lnJ);
    const double Jb = 1.0 + Jb_m1;
    // W_i = 2 mu/alpha^2 [sum (l^alpha - 1) + (1/beta)(J^(-alpha beta) - 1)], the last term -> -alpha ln J at beta = 0.
    const double vol = beta == 0.0 ? -a * lnJ : Jb_m1 / beta;
    r.W += 2.0 * mu / (a * a) * (la_m1.sum() + vol);
    for (int k = 0; k < 3; ++k) {
      // tau_a = 2 (mu/alpha)(l_a^alpha - J^(-alpha beta))
      r.tau(k) += 2.0 * mu / a * (la_m1(k) - Jb_m1);
      // dtau_a/dln l_b = 2 mu (l_a^alpha delta_ab + beta J^(-alpha beta))
      for (int m = 0; m < 3; ++m) r.dtau(k, m) += 2.0 * mu * ((k == m ? 1.0 + la_m1(k) : 0.0) + beta * Jb);
    }
    // S_a = 2 mu/alpha (l_a^(alpha-2) - J^(-alpha beta) l_a^(-2)), so
    // G_ab = 2 mu/alpha [q(alpha-2) - J^(-alpha beta) q(-2)], q(p) = (l_b^p - l_a^p)/(l_b^2 - l_a^2).
    for (int k = 0; k < 3; ++k)
      for (int m = 0; m < 3; ++m) {
        if (k == m) continue;
        r.G(k, m) += 2.0 * mu / a *
                     (power_difference_quotient(a - 2.0, s(m), s(k)) - Jb * power_difference_quotient(-2.0, s(m), s(k)));
      }
  }
  return r;
}

ElasticEval failure(const std::string& why) {
  ElasticEval e;
  e.status = Status::failed;
  e.message = "Hyperfoam: " + why;
  return e;
}

}  // namespace

Hyperfoam::Hyperfoam(std::vector<HyperfoamTerm> terms) : terms_(std::move(terms)) {
  if (terms_.empty() || terms_.size() > 6) throw std::invalid_argument("Hyperfoam: need 1 to 6 terms");
  for (const HyperfoamTerm& t : terms_) {
    if (!std::isfinite(t.mu) || !std::isfinite(t.alpha) || t.alpha == 0.0)
      throw std::invalid_argument("Hyperfoam: alpha must be non-zero and mu, alpha finite");
    if (!(t.nu >= 0.0 && t.nu < 0.5)) throw std::invalid_argument("Hyperfoam: nu must lie in [0, 0.5)");
  }
}

ElasticEval Hyperfoam::evaluate(const Mat3& F) const {
  const double detF = F.determinant();
  if (!(detF > 0.0)) return failure("J = det F <= 0 (or NaN)");
  // E = (F^T F - I)/2 = sym(H) + H^T H / 2 with H = F - I: no round-off cancellation at small strain.
  const Mat3 H = F - Mat3::Identity();
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(E);
  if (eig.info() != Eigen::Success) return failure("eigen-decomposition of E failed");
  const Vec3 e = eig.eigenvalues();
  const Mat3& N = eig.eigenvectors();  // column a: principal direction N_a (reference frame)
  Vec3 s;                              // s_a = ln l_a = ln(1 + 2 E_a) / 2
  for (int a = 0; a < 3; ++a) {
    if (!(1.0 + 2.0 * e(a) > 0.0)) return failure("principal stretch squared <= 0");
    s(a) = 0.5 * std::log1p(2.0 * e(a));
  }
  const PrincipalResponse p = principal_response(terms_, s);

  // S_a = tau_a / l_a^2;  D_ab = dS_a/dE_b = [dtau_a/dln l_b - 2 tau_a delta_ab] / (l_a^2 l_b^2).
  Vec3 S_a, inv_c;
  for (int a = 0; a < 3; ++a) {
    inv_c(a) = std::exp(-2.0 * s(a));
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
    return failure("non-finite energy, stress or tangent (stretches out of range)");
  return out;
}

Vec3 Hyperfoam::principal_kirchhoff(const Vec3& l) const {
  return principal_response(terms_, l.array().log().matrix()).tau;
}

std::shared_ptr<const Hyperelastic> Hyperfoam::scaled(double factor) const {
  std::vector<HyperfoamTerm> t = terms_;
  for (HyperfoamTerm& term : t) term.mu *= factor;
  return std::make_shared<Hyperfoam>(std::move(t));
}

double Hyperfoam::initial_shear_modulus() const {
  double mu0 = 0.0;
  for (const HyperfoamTerm& t : terms_) mu0 += t.mu;
  return mu0;
}

double Hyperfoam::initial_bulk_modulus() const {
  double K0 = 0.0;
  for (const HyperfoamTerm& t : terms_) K0 += 2.0 * t.mu * (1.0 / 3.0 + t.beta());
  return K0;
}

std::string Hyperfoam::describe() const {
  std::ostringstream o;
  o << "hyperfoam N=" << terms_.size() << ":";
  for (const HyperfoamTerm& t : terms_)
    o << " (mu=" << t.mu * 1e3 << " kPa, alpha=" << t.alpha << ", nu=" << t.nu << ")";
  return o.str();
}

}  // namespace cushion::material
