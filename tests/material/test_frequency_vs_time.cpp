// Issue acceptance: the time-domain response to a small sinusoid about a relaxed 25 % compressive
// preload agrees with the frequency-domain prediction of Material::complex_tangent (uniaxial stress).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <complex>

#include "material/hyperfoam.hpp"
#include "material/point_driver.hpp"
#include "material/viscoelastic.hpp"

namespace cm = cushion::material;
using cd = std::complex<double>;

namespace {

/// Least-squares fit x(t) = a sin(w t) + b cos(w t) + c + d t over the samples with t >= t_from;
/// returns the complex amplitude X with x = Re(X e^{i w t}) + drift, i.e. X = b - i a.
cd fit_phasor(const std::vector<double>& t, const std::vector<double>& x, double omega, double t_from) {
  Eigen::MatrixXd A(0, 4);
  Eigen::VectorXd y(0);
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t_from) rows.push_back(i);
  A.resize(static_cast<Eigen::Index>(rows.size()), 4);
  y.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double ti = t[rows[k]];
    A.row(static_cast<Eigen::Index>(k)) << std::sin(omega * ti), std::cos(omega * ti), 1.0, ti - t_from;
    y(static_cast<Eigen::Index>(k)) = x[rows[k]];
  }
  const Eigen::Vector4d p = A.colPivHouseholderQr().solve(y);
  return {p(1), -p(0)};
}

/// dP11/dF11 (complex) of a uniaxial-stress point at F_base: laterals condensed with dS22 = dS33 = 0,
/// dP11 = dF11 S11 + F11 dS11, dE11 = F11 dF11.
cd uniaxial_complex_modulus(const cm::Material& material, const cushion::Mat3& F_base, double S11, double omega) {
  const cushion::Mat6c C = material.complex_tangent(F_base, omega);
  Eigen::Matrix2cd C_ll;
  C_ll << C(1, 1), C(1, 2), C(2, 1), C(2, 2);
  const Eigen::Vector2cd dE_lateral = C_ll.fullPivLu().solve(-Eigen::Vector2cd(C(1, 0), C(2, 0)));  // per unit dE11
  const cd dS11_dE11 = C(0, 0) + C(0, 1) * dE_lateral(0) + C(0, 2) * dE_lateral(1);
  const double F11 = F_base(0, 0);
  return S11 + F11 * F11 * dS11_dE11;
}

}  // namespace

TEST(FrequencyVsTime, SmallSineAboutRelaxedPreloadMatchesComplexTangent) {
  // Hyperfoam with nu = 0.1 (so the lateral condensation matters) and the paper's Table 3 Prony series.
  const auto base = std::make_shared<cm::Hyperfoam>(
      std::vector<cm::HyperfoamTerm>{{0.010, 10.0, 0.1}, {0.0001, -2.0, 0.1}, {0.0005, 3.0, 0.1}});
  const cm::Viscoelastic foam(base, cm::prony_from_absolute(3.05, {23.9, 19.7, 8.99, 12.4, 8.14}, {0.01, 0.1, 1, 10, 100}));

  const double amplitude = 1e-4, cycles = 20, fitted_cycles = 5;
  const int steps_per_cycle = 200;
  for (double f : {1.0, 5.0, 20.0}) {
    cm::Segment preload, hold, sine;
    preload.kind = cm::Segment::Kind::ramp;
    preload.target = -0.25;
    preload.duration = 10.0;
    preload.steps = 100;
    hold.kind = cm::Segment::Kind::hold;
    hold.duration = 3000.0;  // 30 tau_max: relaxed to e^-30; the exponential update is exact for holds
    hold.steps = 30;
    sine.kind = cm::Segment::Kind::sine;
    sine.amplitude = amplitude;
    sine.frequency = f;
    sine.cycles = cycles;
    sine.steps = static_cast<int>(cycles) * steps_per_cycle;
    const cm::PointResult r = cm::run_point(foam, cm::LoadMode::uniaxial_free, cm::build_history({preload, hold, sine}));

    const std::size_t i_base = 130;  // end of the hold
    ASSERT_NEAR(r.time[i_base], 3010.0, 1e-9);
    const cushion::Mat3 F_base = r.F[i_base];
    const double S11 = r.P[i_base](0, 0) / F_base(0, 0);
    std::vector<double> P11;
    for (const auto& P : r.P) P11.push_back(P(0, 0));

    const double omega = 2.0 * std::numbers::pi * f, t_from = r.time.back() - fitted_cycles / f - 1e-9;
    const cd strain = fit_phasor(r.time, r.control, omega, t_from);
    const cd stress = fit_phasor(r.time, P11, omega, t_from);
    const cd time_domain = stress / strain;
    const cd frequency_domain = uniaxial_complex_modulus(foam, F_base, S11, omega);

    const double modulus_error = std::abs(std::abs(time_domain) / std::abs(frequency_domain) - 1.0);
    const double phase_error_deg = std::abs(std::arg(time_domain / frequency_domain)) * 180.0 / std::numbers::pi;
    EXPECT_LT(modulus_error, 5e-3) << f << " Hz: |E*| time " << std::abs(time_domain) << ", frequency " << std::abs(frequency_domain);
    EXPECT_LT(phase_error_deg, 0.2) << f << " Hz: phase time " << std::arg(time_domain) * 180 / std::numbers::pi << " deg, frequency "
                                    << std::arg(frequency_domain) * 180 / std::numbers::pi << " deg";
    // The comparison is not trivial: a lossy modulus with a clear phase lag at every frequency.
    EXPECT_GT(std::arg(frequency_domain) * 180.0 / std::numbers::pi, 5.0);
    std::printf("  %5.1f Hz: |E*| time %.6g MPa, frequency %.6g MPa (rel. diff %.2e); phase %.4f vs %.4f deg\n", f,
                std::abs(time_domain), std::abs(frequency_domain), modulus_error,
                std::arg(time_domain) * 180 / std::numbers::pi, std::arg(frequency_domain) * 180 / std::numbers::pi);
  }
}
