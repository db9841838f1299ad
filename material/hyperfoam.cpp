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

/// The term-independent part of the difference quotients q_p = (l_b^p - l_a^p) / (l_b^2 - l_a^2) of one pair a < b
/// of principal stretches, at s_a = ln l_a, d = s_b - s_a. Written without cancellation as
/// q_p = e^{(p-2) s_a} expm1(p d) / expm1(2 d), with the limit p/2 e^{(p-2) s_a} at d = 0, so relative accuracy
/// does not degrade as l_b -> l_a (no "nearly equal" branch).
struct StretchPair {
  int a = 0, b = 0;
  double d = 0.0;             ///< s_b - s_a
  double expm1_2d = 0.0;      ///< expm1(2 d)
  double inv_la4 = 0.0;       ///< e^{-4 s_a} = l_a^{-4}
  double q_minus2 = 0.0;      ///< q_{-2} = -1 / (l_a^2 l_b^2), exact (expm1(-2d)/expm1(2d) = -e^{-2d})

  StretchPair(const Vec3& s, int a_, int b_) : a(a_), b(b_), d(s(b_) - s(a_)) {
    expm1_2d = std::expm1(2.0 * d);
    inv_la4 = std::exp(-4.0 * s(a_));
    q_minus2 = -std::exp(-2.0 * (s(a_) + s(b_)));
  }
  /// q_{alpha-2} given l_a^alpha = la_alpha.
  double q_alpha_minus2(double alpha, double la_alpha) const {
    const double scale = la_alpha * inv_la4;  // e^{(alpha - 4) s_a}
    if (d == 0.0) return 0.5 * (alpha - 2.0) * scale;
    return scale * std::expm1((alpha - 2.0) * d) / expm1_2d;
  }
};

PrincipalResponse principal_response(const std::vector<HyperfoamTerm>& terms, const Vec3& s) {
  PrincipalResponse r;
  const double lnJ = s.sum();
  const StretchPair pairs[3] = {StretchPair(s, 0, 1), StretchPair(s, 0, 2), StretchPair(s, 1, 2)};
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
    // G_ab = 2 mu/alpha [q_(alpha-2) - J^(-alpha beta) q_(-2)] (symmetric in a, b).
    for (const StretchPair& p : pairs) {
      const double g = 2.0 * mu / a * (p.q_alpha_minus2(a, 1.0 + la_m1(p.a)) - Jb * p.q_minus2);
      r.G(p.a, p.b) += g;
      r.G(p.b, p.a) += g;
    }
  }
  return r;
}

/// Principal values e and directions N (columns) of the symmetric E; a diagonal E (the material-point
/// driver's uniaxial and volumetric paths) is taken as it is, without an eigen-solve (`aligned` set).
/// False if the solve fails.
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

/// S and dS/dE (Voigt) from the principal S_a, D_ab = dS_a/dE_b and the spin moduli G_ab, principal directions N_a
/// (columns of N). The spin part is dS_ab = 2 G_ab dE_ab in the principal frame: with m_ab = Voigt_stress(N_a N_b +
/// N_b N_a), m_ab . dE_voigt = 2 dE_ab (engineering shear), so the term is G_ab m_ab m_ab^T.
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
  Vec3 e;  // principal Green-Lagrange strains E_a
  Mat3 N;  // column a: principal direction N_a (reference frame)
  bool aligned = false;  // N = I
  if (!principal_frame(E, e, N, aligned)) return failure("eigen-decomposition of E failed");
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
  Mat3 D;  // D_ab = dS_a/dE_b
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) D(a, b) = (p.dtau(a, b) - (a == b ? 2.0 * p.tau(a) : 0.0)) * inv_c(a) * inv_c(b);
  ElasticEval out;
  out.W = p.W;
  if (aligned)
    assemble_aligned(S_a, D, p.G, out);
  else
    assemble_rotated(S_a, D, p.G, N, out);
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
