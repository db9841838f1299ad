#pragma once
/// The fractional derivative D^q x(t) = int_0^t k(t - s) x'(s) ds, k(t) = t^-q / Gamma(1 - q), 0 < q <= 1 (Caputo, from a
/// relaxed start), as a bank of Maxwell branches with closed tails (docs/physics.md 5.4b):
///   k(t) = sin(q pi)/pi int tau^-q e^(-t/tau) d ln tau
///        ~ eta delta(t) + kappa + sum_k m_k e^(-t/tau_k),
///   tau_k = tau_lo 10^(k/n), k = 0..K (n nodes a decade, trapezoid weights w_k in ln tau),
///   m_k = sin(q pi)/pi w_k tau_k^-q,
///   eta = sin(q pi)/pi tau_lo^(1-q)/(1 - q)   (branches faster than tau_lo: a dashpot; 1 at q = 1),
///   kappa = sin(q pi)/pi tau_hi^-q / q        (branches slower than tau_hi: a spring).
/// At q = 1 the bank and the spring vanish and D^1 x = x' exactly. Its transfer function G(i omega) (D^q of e^(i omega t)
/// in the steady state) is within 0.3 % in modulus and 0.1 deg in phase of (i omega)^q for 1e-4 to 100 Hz and q in
/// [0.1, 1] (tests/material/test_spring_pot.cpp). Times in s, eta in s^(1-q), kappa and m_k in s^-q.
#include <complex>
#include <span>
#include <vector>

namespace cushion::material {

class SpringPotBank {
 public:
  /// q in (0, 1] (else std::invalid_argument); tau_lo 1e-5 s and tau_hi 1e5 s, 2 nodes a decade (21 branches).
  explicit SpringPotBank(double q);

  double order() const { return q_; }
  const std::vector<double>& times_s() const { return tau_; }     ///< tau_k [s]
  const std::vector<double>& moduli() const { return m_; }        ///< m_k [s^-q]
  double dashpot() const { return eta_; }                         ///< eta [s^(1-q)]
  double spring() const { return kappa_; }                        ///< kappa [s^-q]
  std::size_t branches() const { return tau_.size(); }
  /// Doubles of memory for a quantity of `width` components: one set a branch and one for the spring (0 at q = 1).
  std::size_t memory_size(std::size_t width) const { return tau_.empty() ? 0 : width * (tau_.size() + 1); }

  /// Weight of an increment Delta x taken linearly over dt > 0 in D^q x at the increment's end: eta/dt + kappa +
  /// sum_k m_k phi(dt/tau_k), phi(x) = (1 - e^-x)/x, prony_recursion's weight [s^-q] (the tangent of the recursion
  /// below).
  double increment_weight(double dt) const;
  /// Advances the memories of a quantity of dx.size() components (layout: branch k at [k w, (k + 1) w), the spring
  /// after the last branch; `memory_size(w)` doubles in `old_memory` and `new_memory`, which may be the same) by an
  /// increment dx taken linearly over dt > 0: h_k <- e^(-dt/tau_k) h_k + phi(dt/tau_k) dx, the spring's memory
  /// (x - x(0)) gains dx; `value` (w components) receives memory_value of the new memories.
  void advance(double dt, std::span<const double> dx, std::span<const double> old_memory, std::span<double> new_memory,
               std::span<double> value) const;
  /// out = kappa x_spring + sum_k m_k h_k: D^q x without the dashpot's eta x', from the memories (out.size() = w).
  void memory_value(std::span<const double> memory, std::span<double> out) const;

  /// G(i omega) = eta i omega + kappa + sum_k m_k i omega tau_k/(1 + i omega tau_k) [s^-q], omega [rad/s].
  std::complex<double> transfer(double omega) const;

 private:
  /// e^(-dt/tau_k), phi(dt/tau_k) and the increment weight for one dt; remembered per thread for the last (q, dt)
  /// (the same dt recurs at every Newton iteration and time step of a test segment).
  struct StepFactors {
    double q = -1.0, dt = -1.0, weight = 0.0;
    std::vector<double> decay, phi;
  };
  const StepFactors& factors(double dt) const;

  double q_, eta_ = 0.0, kappa_ = 0.0;
  std::vector<double> tau_, m_;
};

}  // namespace cushion::material
