#include "material/viscoelastic.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {

double sum_g(const std::vector<PronyTerm>& terms) {
  double s = 0.0;
  for (const PronyTerm& t : terms) s += t.g;
  return s;
}

void validate(const std::vector<PronyTerm>& terms) {
  if (terms.size() > 20) throw std::invalid_argument("Viscoelastic: at most 20 Prony terms");
  for (const PronyTerm& t : terms) {
    if (!(t.g >= 0.0) || !std::isfinite(t.g)) throw std::invalid_argument("Prony: g_i must be >= 0");
    if (!(t.tau > 0.0) || !std::isfinite(t.tau)) throw std::invalid_argument("Prony: tau_i must be > 0");
  }
  if (!(sum_g(terms) < 1.0)) throw std::invalid_argument("Prony: sum of g_i must be < 1");
}

}  // namespace

PronyRecursion prony_recursion(double dt, double tau) {
  const double x = dt / tau;
  if (x == 0.0) return {1.0, 1.0};
  // The result depends on x alone, and the same x recurs at every Newton iteration and time step of a test (fixed
  // dt per sine frequency or ramp, the same tau_i): remember the last x per slot, per thread (no locking; an exact
  // match returns the bit-identical values). exp and expm1 were a quarter of a diagnose run (perf, session 14).
  struct Slot {
    double x = -1.0;
    PronyRecursion q{1.0, 1.0};
  };
  thread_local std::array<Slot, 64> slots;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  Slot& slot = slots[((bits ^ (bits >> 31)) * 0x9E3779B97F4A7C15ull) >> 58];
  if (slot.x != x) slot = {x, {std::exp(-x), -std::expm1(-x) / x}};
  return slot.q;
}

std::vector<PronyTerm> prony_from_absolute(double E_inf, const std::vector<double>& E, const std::vector<double>& tau) {
  if (E.size() != tau.size()) throw std::invalid_argument("prony_from_absolute: E and tau differ in length");
  if (!(E_inf >= 0.0)) throw std::invalid_argument("prony_from_absolute: E_inf must be >= 0");
  double E0 = E_inf;
  for (double e : E) {
    if (!(e >= 0.0)) throw std::invalid_argument("prony_from_absolute: E_i must be >= 0");
    E0 += e;
  }
  if (!(E0 > 0.0)) throw std::invalid_argument("prony_from_absolute: instantaneous modulus must be > 0");
  std::vector<PronyTerm> terms;
  for (std::size_t i = 0; i < E.size(); ++i) {
    if (!(tau[i] > 0.0)) throw std::invalid_argument("prony_from_absolute: tau_i must be > 0");
    terms.push_back({E[i] / E0, tau[i]});
  }
  return terms;
}

std::complex<double> prony_complex_factor(const std::vector<PronyTerm>& terms, double omega) {
  const double long_term_fraction = 1.0 - sum_g(terms);
  std::complex<double> f = 1.0;
  for (const PronyTerm& t : terms) {
    // a_i i w tau_i / (1 + i w tau_i) = a_i (w^2 tau^2 + i w tau) / (1 + w^2 tau^2)
    const double a = t.g / long_term_fraction, wt = omega * t.tau;
    f += a * std::complex<double>(wt * wt, wt) / (1.0 + wt * wt);
  }
  return f;
}

Viscoelastic::Viscoelastic(std::shared_ptr<const Hyperelastic> base, std::vector<PronyTerm> terms,
                           ModuliConvention convention)
    : terms_(std::move(terms)) {
  if (!base) throw std::invalid_argument("Viscoelastic: no base material");
  validate(terms_);
  const double long_term_fraction = 1.0 - sum_g(terms_);
  // INSTANTANEOUS: the given constants are the t = 0+ ones; the long-term base is (1 - sum g) times them.
  long_term_ = convention == ModuliConvention::long_term ? std::move(base) : base->scaled(long_term_fraction);
  for (const PronyTerm& t : terms_) a_.push_back(t.g / long_term_fraction);
}

PointResponse Viscoelastic::integrate(const Mat3& /*F_old*/, const Mat3& F_new, double dt,
                                      std::span<const double> state_old, std::span<double> state_new) const {
  PointResponse r;
  if (!(dt >= 0.0) || state_old.size() != state_size() || state_new.size() != state_size()) {
    r.status = Status::failed;
    r.message = "Viscoelastic: dt < 0 or wrong state size";
    return r;
  }
  const ElasticEval e = long_term_->evaluate(F_new);
  if (e.status == Status::failed) {
    r.status = Status::failed;
    r.message = e.message;
    r.dt_factor = 0.5;
    return r;
  }
  // State: S_inf^n (6), then H_1..H_n (6 each).
  const Vec6 S_inf_old = Eigen::Map<const Vec6>(state_old.data());
  const Vec6 dS_inf = e.S - S_inf_old;
  Eigen::Map<Vec6>(state_new.data()) = e.S;
  r.S = e.S;
  double tangent_factor = 1.0;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const PronyRecursion q = prony_recursion(dt, terms_[i].tau);
    const Vec6 H = q.decay * Eigen::Map<const Vec6>(state_old.data() + 6 * (i + 1)) + q.weight * dS_inf;
    Eigen::Map<Vec6>(state_new.data() + 6 * (i + 1)) = H;
    r.S += a_[i] * H;
    tangent_factor += a_[i] * q.weight;
  }
  r.dS_dE = tangent_factor * e.dS_dE;
  r.status = e.status;
  r.message = e.message;
  if (!r.S.allFinite()) {
    r.status = Status::failed;
    r.message = "Viscoelastic: non-finite stress (corrupt state?)";
    r.dt_factor = 0.5;
  }
  return r;
}

double Viscoelastic::add_to_memory(std::span<double> state, double dt, const Vec6& dS) const {
  double factor = 0.0;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const double q = prony_recursion(dt, terms_[i].tau).weight;
    Eigen::Map<Vec6>(state.data() + 6 * (i + 1)) += q * dS;
    factor += a_[i] * q;
  }
  return factor;
}

MemoryGain Viscoelastic::drive_memory(const Mat3& /*F_new*/, std::span<double> state_new, double dt,
                                      const Vec6& dS) const {
  return {add_to_memory(state_new, dt, dS), Vec6::Zero()};
}

std::complex<double> Viscoelastic::memory_complex_factor(const Mat3& /*F_base*/, double omega) const {
  return prony_complex_factor(terms_, omega);
}

Vec6 Viscoelastic::viscous_stress(const Mat3& /*F*/, std::span<const double> state) const {
  Vec6 S = Vec6::Zero();
  for (std::size_t i = 0; i < terms_.size(); ++i) S += a_[i] * Eigen::Map<const Vec6>(state.data() + 6 * (i + 1));
  return S;
}

Mat6c Viscoelastic::complex_tangent(const Mat3& F_base, double omega) const {
  return prony_complex_factor(terms_, omega) * long_term_->evaluate(F_base).dS_dE.cast<std::complex<double>>();
}

std::string Viscoelastic::describe() const {
  std::ostringstream o;
  o << "viscoelastic (Prony, " << terms_.size() << " terms:";
  for (const PronyTerm& t : terms_) o << " g=" << t.g << "/tau=" << t.tau << " s";
  o << ") over long-term " << long_term_->describe();
  return o.str();
}

}  // namespace cushion::material
