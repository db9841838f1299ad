#include "material/spring_pot.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "material/viscoelastic.hpp"

namespace cushion::material {

namespace {
constexpr double tau_lo_s = 1e-5, tau_hi_s = 1e5;
constexpr int nodes_per_decade = 2;
}  // namespace

SpringPotBank::SpringPotBank(double q) : q_(q) {
  if (!(q > 0.0 && q <= 1.0)) throw std::invalid_argument("spring-pot: the order q must lie in (0, 1]");
  if (q == 1.0) {
    eta_ = 1.0;  // D^1 x = x': a dashpot, no bank
    return;
  }
  const double s = std::sin(q * std::numbers::pi) / std::numbers::pi;
  const int K = static_cast<int>(std::lround(std::log10(tau_hi_s / tau_lo_s) * nodes_per_decade));
  const double h = std::numbers::ln10 / nodes_per_decade;
  for (int k = 0; k <= K; ++k) {
    const double tau = tau_lo_s * std::pow(10.0, static_cast<double>(k) / nodes_per_decade);
    const double w = (k == 0 || k == K) ? 0.5 * h : h;
    tau_.push_back(tau);
    m_.push_back(s * w * std::pow(tau, -q));
  }
  eta_ = s * std::pow(tau_lo_s, 1.0 - q) / (1.0 - q);
  kappa_ = s * std::pow(tau_hi_s, -q) / q;
}

const SpringPotBank::StepFactors& SpringPotBank::factors(double dt) const {
  thread_local StepFactors f;  // keyed by (q, dt), which fix every factor: no stale answer for another bank
  if (f.q == q_ && f.dt == dt) return f;
  f.q = q_;
  f.dt = dt;
  f.decay.resize(tau_.size());
  f.phi.resize(tau_.size());
  f.weight = eta_ / dt + kappa_;
  for (std::size_t k = 0; k < tau_.size(); ++k) {
    const PronyRecursion p = prony_recursion(dt, tau_[k]);  // a Maxwell branch's recursion is a Prony term's
    f.decay[k] = p.decay;
    f.phi[k] = p.weight;
    f.weight += m_[k] * f.phi[k];
  }
  return f;
}

double SpringPotBank::increment_weight(double dt) const { return factors(dt).weight; }

void SpringPotBank::advance(double dt, std::span<const double> dx, std::span<const double> old_memory,
                            std::span<double> new_memory, std::span<double> value) const {
  const std::size_t w = dx.size(), K = tau_.size();
  if (old_memory.size() != memory_size(w) || new_memory.size() != memory_size(w) || value.size() != w)
    throw std::invalid_argument("spring-pot: memory of the wrong size");
  const StepFactors& f = factors(dt);
  for (std::size_t c = 0; c < w; ++c) {
    new_memory[K * w + c] = old_memory[K * w + c] + dx[c];
    value[c] = kappa_ * new_memory[K * w + c];
  }
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t c = 0; c < w; ++c) {
      const double h = f.decay[k] * old_memory[k * w + c] + f.phi[k] * dx[c];
      new_memory[k * w + c] = h;
      value[c] += m_[k] * h;
    }
}

void SpringPotBank::memory_value(std::span<const double> memory, std::span<double> out) const {
  const std::size_t w = out.size(), K = tau_.size();
  if (memory.size() != memory_size(w)) throw std::invalid_argument("spring-pot: memory of the wrong size");
  for (std::size_t c = 0; c < w; ++c) out[c] = K == 0 ? 0.0 : kappa_ * memory[K * w + c];
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t c = 0; c < w; ++c) out[c] += m_[k] * memory[k * w + c];
}

std::complex<double> SpringPotBank::transfer(double omega) const {
  const std::complex<double> iw(0.0, omega);
  std::complex<double> g = eta_ * iw + kappa_;
  for (std::size_t k = 0; k < tau_.size(); ++k) g += m_[k] * iw * tau_[k] / (1.0 + iw * tau_[k]);
  return g;
}

}  // namespace cushion::material
