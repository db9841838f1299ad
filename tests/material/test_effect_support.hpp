#pragma once
/// Shared helpers of the effect tests (tests/material/test_effect_*.cpp): base materials, the
/// finite-difference tangent check of an increment, and the time-domain vs frequency-domain
/// comparison of a small sine about a relaxed preload (point driver vs Material::complex_tangent).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <vector>

#include "material/hyperfoam.hpp"
#include "material/point_driver.hpp"
#include "material/viscoelastic.hpp"
#include "tests/material/fd.hpp"

namespace cushion::material::test {

/// A three-term hyperfoam (nu = 0.1, so lateral contraction and J matter), moduli ~10 kPa.
inline std::shared_ptr<const Hyperfoam> effect_test_foam() {
  return std::make_shared<Hyperfoam>(std::vector<HyperfoamTerm>{{0.010, 10.0, 0.1}, {0.0001, -2.0, 0.1}, {0.0005, 3.0, 0.1}});
}

/// The paper's Table 3 Prony series (relative moduli) over effect_test_foam() as the long-term base.
inline std::shared_ptr<const Viscoelastic> effect_test_visco() {
  return std::make_shared<Viscoelastic>(effect_test_foam(),
                                        prony_from_absolute(3.05, {23.9, 19.7, 8.99, 12.4, 8.14}, {0.01, 0.1, 1, 10, 100}));
}

/// Relative difference between the increment tangent and central differences of S(F_new) at fixed
/// F_old, dt and state_old (the consistent tangent of the increment).
inline double increment_tangent_error(const Material& m, const Mat3& F_old, const Mat3& F_new, double dt,
                                      const std::vector<double>& state_old) {
  std::vector<double> next(m.state_size());
  const PointResponse r = m.integrate(F_old, F_new, dt, state_old, next);
  EXPECT_NE(r.status, Status::failed) << r.message;
  const Mat6 fd = fd_dS_dE(
      [&](const Mat3& F) {
        std::vector<double> s(m.state_size());
        return m.integrate(F_old, F, dt, state_old, s).S;
      },
      F_new);
  return rel_diff(r.dS_dE, fd);
}

/// Least-squares fit x(t) = a sin(w t) + b cos(w t) + c + d t over t >= t_from; returns the phasor
/// X = b - i a (x = Re(X e^{i w t}) + drift).
inline std::complex<double> fit_phasor(const std::vector<double>& t, const std::vector<double>& x, double omega,
                                       double t_from) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t_from) rows.push_back(i);
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 4);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double ti = t[rows[k]];
    A.row(static_cast<Eigen::Index>(k)) << std::sin(omega * ti), std::cos(omega * ti), 1.0, ti - t_from;
    y(static_cast<Eigen::Index>(k)) = x[rows[k]];
  }
  const Eigen::Vector4d p = A.colPivHouseholderQr().solve(y);
  return {p(1), -p(0)};
}

/// dP11/dF11 of a uniaxial-stress point from the complex tangent at F_base (laterals condensed,
/// dS22 = dS33 = 0; dP11 = dF11 S11 + F11 dS11 with dE11 = F11 dF11).
inline std::complex<double> uniaxial_complex_modulus(const Material& m, const Mat3& F_base, double S11, double omega) {
  const Mat6c C = m.complex_tangent(F_base, omega);
  Eigen::Matrix2cd C_ll;
  C_ll << C(1, 1), C(1, 2), C(2, 1), C(2, 2);
  const Eigen::Vector2cd dE_lateral = C_ll.fullPivLu().solve(-Eigen::Vector2cd(C(1, 0), C(2, 0)));
  const std::complex<double> dS11_dE11 = C(0, 0) + C(0, 1) * dE_lateral(0) + C(0, 2) * dE_lateral(1);
  return S11 + F_base(0, 0) * F_base(0, 0) * dS11_dE11;
}

/// Time-domain (fitted over the last cycles) and frequency-domain uniaxial moduli dP11/dF11 [MPa].
struct SineComparison {
  std::complex<double> time_domain, frequency_domain;
  double modulus_error() const { return std::abs(std::abs(time_domain) / std::abs(frequency_domain) - 1.0); }
  double phase_error_deg() const { return std::abs(std::arg(time_domain / frequency_domain)) * 180.0 / std::numbers::pi; }
  double phase_deg() const { return std::arg(frequency_domain) * 180.0 / std::numbers::pi; }
};

/// Uniaxial stress (free laterals): ramp to `preload` in 10 s, hold `hold_s` in `hold_steps` (relaxed
/// base), then a sine of amplitude 1e-4 at f Hz for `cycles` cycles with `steps_per_cycle`; the last
/// 3 cycles are fitted.
inline SineComparison compare_sine(const Material& m, double preload, double hold_s, int hold_steps, double f,
                                   int cycles, int steps_per_cycle) {
  Segment ramp, hold, sine;
  ramp.kind = Segment::Kind::ramp;
  ramp.target = preload;
  ramp.duration = 10.0;
  ramp.steps = 100;
  hold.kind = Segment::Kind::hold;
  hold.duration = hold_s;
  hold.steps = hold_steps;
  sine.kind = Segment::Kind::sine;
  sine.amplitude = 1e-4;
  sine.frequency = f;
  sine.cycles = cycles;
  sine.steps = cycles * steps_per_cycle;
  const PointResult r = run_point(m, LoadMode::uniaxial_free, build_history({ramp, hold, sine}));
  const std::size_t i_base = static_cast<std::size_t>(ramp.steps + hold_steps);
  const Mat3 F_base = r.F[i_base];
  const double S11 = r.P[i_base](0, 0) / F_base(0, 0);
  std::vector<double> P11;
  for (const Mat3& P : r.P) P11.push_back(P(0, 0));
  const double omega = 2.0 * std::numbers::pi * f, t_from = r.time.back() - 3.0 / f - 1e-9;
  return {fit_phasor(r.time, P11, omega, t_from) / fit_phasor(r.time, r.control, omega, t_from),
          uniaxial_complex_modulus(m, F_base, S11, omega)};
}

}  // namespace cushion::material::test
