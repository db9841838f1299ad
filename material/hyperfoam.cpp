#include "material/hyperfoam.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "material/principal_stretch.hpp"

namespace cushion::material {

namespace {

using PrincipalResponse = principal::Response;

/// first[k]: the first axis j <= k with s_j == s_k (k itself if none); equal stretches share every power.
std::array<int, 3> first_equal_axis(const Vec3& s) {
  std::array<int, 3> first{0, 1, 2};
  for (int k = 1; k < 3; ++k)
    for (int j = 0; j < k; ++j)
      if (s(j) == s(k)) {
        first[k] = j;
        break;
      }
  return first;
}

PrincipalResponse principal_response(const std::vector<HyperfoamTerm>& terms, const Vec3& s) {
  PrincipalResponse r;
  const double lnJ = s.sum();
  // Axes and pairs of equal log stretch (the uniaxial paths: l2 = l3) are evaluated once and shared: the same inputs
  // give the same results, so this only skips transcendental calls (about half of them on a uniaxial path).
  const std::array<int, 3> axis = first_equal_axis(s);
  constexpr int pair_axes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  std::array<int, 3> pair_source{0, 1, 2};  // an earlier pair with the same two stretches, else the pair itself
  for (int p = 1; p < 3; ++p)
    for (int q = 0; q < p; ++q)
      if (axis[pair_axes[q][0]] == axis[pair_axes[p][0]] && axis[pair_axes[q][1]] == axis[pair_axes[p][1]]) {
        pair_source[p] = q;
        break;
      }
  std::array<principal::StretchPair, 3> pairs;
  for (int p = 0; p < 3; ++p)
    pairs[p] = pair_source[p] == p ? principal::StretchPair(s, pair_axes[p][0], pair_axes[p][1]) : pairs[pair_source[p]];
  for (const HyperfoamTerm& term : terms) {
    const double mu = term.mu, a = term.alpha, beta = term.beta();
    // l_a^alpha - 1 and J^(-alpha beta) - 1 in expm1 form: exact near the undeformed state (beta = 0: exactly 0).
    Vec3 la_m1;
    for (int k = 0; k < 3; ++k) la_m1(k) = axis[k] == k ? std::expm1(a * s(k)) : la_m1(axis[k]);
    const double Jb_m1 = beta == 0.0 ? 0.0 : std::expm1(-a * beta * lnJ);
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
    std::array<double, 3> g{};
    for (int p = 0; p < 3; ++p) {
      const principal::StretchPair& pair = pairs[p];
      g[p] = pair_source[p] == p
                 ? 2.0 * mu / a * (pair.q_alpha_minus2(a, 1.0 + la_m1(pair.a)) - Jb * pair.q_minus2)
                 : g[pair_source[p]];
      const int i = pair_axes[p][0], j = pair_axes[p][1];
      r.G(i, j) += g[p];
      r.G(j, i) += g[p];
    }
  }
  return r;
}

/// A number no other Hyperfoam constructed in this process has (the key of the evaluation memo).
std::uint64_t next_instance_id() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

}  // namespace

Hyperfoam::Hyperfoam(std::vector<HyperfoamTerm> terms) : terms_(std::move(terms)), id_(next_instance_id()) {
  if (terms_.empty() || terms_.size() > 6) throw std::invalid_argument("Hyperfoam: need 1 to 6 terms");
  for (const HyperfoamTerm& t : terms_) {
    if (!std::isfinite(t.mu) || !std::isfinite(t.alpha) || t.alpha == 0.0)
      throw std::invalid_argument("Hyperfoam: alpha must be non-zero and mu, alpha finite");
    if (!(t.nu >= 0.0 && t.nu < 0.5)) throw std::invalid_argument("Hyperfoam: nu must lie in [0, 0.5)");
  }
}

ElasticEval Hyperfoam::evaluate(const Mat3& F) const {
  // The last evaluation of this thread, by instance and exact F (see the class comment).
  struct Memo {
    std::uint64_t id = 0;
    Mat3 F;
    ElasticEval e;
  };
  thread_local Memo memo;
  if (memo.id == id_ && memo.F == F) return memo.e;
  const principal::Stretches st = principal::decompose(F);
  if (!st.failure.empty()) return principal::failure("Hyperfoam", st.failure);
  memo.e = principal::assemble(principal_response(terms_, st.s), st, "Hyperfoam");
  memo.id = id_;
  memo.F = F;
  return memo.e;
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
