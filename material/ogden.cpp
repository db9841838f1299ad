#include "material/ogden.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "material/principal_stretch.hpp"

namespace cushion::material {

namespace {

/// Isochoric Ogden terms at log principal stretches s (docs: ogden.hpp). With x_a = lb_a^alpha:
/// tau_a = 2 mu/alpha (x_a - m), m = mean x; dtau_a/ds_b = 2 mu (x_a delta_ab - (x_a + x_b - m)/3);
/// S_a = 2 mu/alpha (J^(-alpha/3) l_a^(alpha-2) - m l_a^(-2)), hence
/// G_ab = 2 mu/alpha [J^(-alpha/3) q(alpha-2) - m q(-2)], q(p) = (l_b^p - l_a^p)/(l_b^2 - l_a^2).
void add_isochoric(const OgdenTerm& term, const Vec3& s, principal::Response& r) {
  const double mu = term.mu, a = term.alpha, lnJ = s.sum();
  Vec3 x_m1;  // x_a - 1 in expm1 form: exact near the undeformed state
  for (int k = 0; k < 3; ++k) x_m1(k) = std::expm1(a * (s(k) - lnJ / 3.0));
  const double m_m1 = x_m1.mean(), m = 1.0 + m_m1, J_a = std::exp(-a * lnJ / 3.0);
  r.W += 2.0 * mu / (a * a) * x_m1.sum();
  for (int k = 0; k < 3; ++k) {
    r.tau(k) += 2.0 * mu / a * (x_m1(k) - m_m1);
    for (int b = 0; b < 3; ++b)
      r.dtau(k, b) += 2.0 * mu * ((k == b ? 1.0 + x_m1(k) : 0.0) - (2.0 + x_m1(k) + x_m1(b) - m) / 3.0);
    for (int b = 0; b < 3; ++b)
      if (b != k)
        r.G(k, b) += 2.0 * mu / a *
                     (J_a * principal::power_difference_quotient(a - 2.0, s(b), s(k)) -
                      m * principal::power_difference_quotient(-2.0, s(b), s(k)));
  }
}

/// Volumetric part U(J) = sum_k (J - 1)^(2k) / D_k: tau_a = J U', dtau_a/ds_b = J (U' + J U''),
/// G_ab = J U' q(-2).
void add_volumetric(const std::vector<double>& D, const Vec3& s, principal::Response& r) {
  const double lnJ = s.sum(), J = std::exp(lnJ), j = std::expm1(lnJ);  // j = J - 1
  double U = 0.0, U1 = 0.0, U2 = 0.0;
  for (std::size_t i = 0; i < D.size(); ++i) {
    if (D[i] == 0.0) continue;
    const int n = 2 * static_cast<int>(i + 1);
    U += std::pow(j, n) / D[i];
    U1 += n * std::pow(j, n - 1) / D[i];
    U2 += n * (n - 1) * std::pow(j, n - 2) / D[i];
  }
  r.W += U;
  for (int k = 0; k < 3; ++k) {
    r.tau(k) += J * U1;
    for (int b = 0; b < 3; ++b) {
      r.dtau(k, b) += J * (U1 + J * U2);
      if (b != k) r.G(k, b) += J * U1 * principal::power_difference_quotient(-2.0, s(b), s(k));
    }
  }
}

}  // namespace

Ogden::Ogden(std::vector<OgdenTerm> terms, std::vector<double> D) : terms_(std::move(terms)), D_(std::move(D)) {
  if (terms_.empty() || terms_.size() > 6) throw std::invalid_argument("Ogden: need 1 to 6 terms");
  if (D_.empty() || D_.size() > 6) throw std::invalid_argument("Ogden: need 1 to 6 compressibility coefficients D");
  for (const OgdenTerm& t : terms_)
    if (!std::isfinite(t.mu) || !std::isfinite(t.alpha) || t.alpha == 0.0)
      throw std::invalid_argument("Ogden: alpha must be non-zero and mu, alpha finite");
  for (double d : D_)
    if (!(d >= 0.0) || !std::isfinite(d)) throw std::invalid_argument("Ogden: D must be finite and >= 0");
  if (!(D_.front() > 0.0)) throw std::invalid_argument("Ogden: D1 must be > 0 (no hybrid elements: J is free)");
  if (!(initial_shear_modulus() > 0.0)) throw std::invalid_argument("Ogden: sum of mu_i must be > 0");
}

ElasticEval Ogden::evaluate(const Mat3& F) const {
  const principal::Stretches st = principal::decompose(F);
  if (!st.failure.empty()) return principal::failure("Ogden", st.failure);
  principal::Response r;
  for (const OgdenTerm& t : terms_) add_isochoric(t, st.s, r);
  add_volumetric(D_, st.s, r);
  return principal::assemble(r, st, "Ogden");
}

std::shared_ptr<const Hyperelastic> Ogden::scaled(double factor) const {
  std::vector<OgdenTerm> t = terms_;
  for (OgdenTerm& term : t) term.mu *= factor;
  std::vector<double> D = D_;
  for (double& d : D) d /= factor;  // 1/D is a modulus
  return std::make_shared<Ogden>(std::move(t), std::move(D));
}

double Ogden::initial_shear_modulus() const {
  double mu0 = 0.0;
  for (const OgdenTerm& t : terms_) mu0 += t.mu;
  return mu0;
}

std::string Ogden::describe() const {
  std::ostringstream o;
  o << "Ogden N=" << terms_.size() << ":";
  for (const OgdenTerm& t : terms_) o << " (mu=" << t.mu * 1e3 << " kPa, alpha=" << t.alpha << ")";
  o << " D=";
  for (std::size_t i = 0; i < D_.size(); ++i) o << (i ? "," : "") << D_[i] * 1e-3 << " 1/kPa";
  return o.str();
}

}  // namespace cushion::material
