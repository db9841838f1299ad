// Material-point driver against closed forms (hyperfoam uniaxial/constrained/volumetric, neo-Hookean
// simple shear) and the platen (push-only) control of a lagging viscoelastic foam.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "material/hyperfoam.hpp"
#include "io/input_error.hpp"
#include "material/neo_hookean.hpp"
#include "material/point_driver.hpp"
#include "material/viscoelastic.hpp"

namespace cm = cushion::material;
using cm::Segment;

namespace {

// Three terms, one common nu (closed forms of docs/physics.md 2.3 need a common nu). MPa.
std::vector<cm::HyperfoamTerm> terms(double nu) { return {{0.010, 10.0, nu}, {0.0001, -2.0, nu}, {0.0005, 3.0, nu}}; }

Segment ramp(double target, double duration, int steps = 0) {
  Segment s;
  s.kind = Segment::Kind::ramp;
  s.target = target;
  s.duration = duration;
  s.steps = steps;
  return s;
}
Segment hold(double duration, int steps = 0) {
  Segment s;
  s.kind = Segment::Kind::hold;
  s.duration = duration;
  s.steps = steps;
  return s;
}

double relative_error(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

}  // namespace

TEST(BuildHistory, RampHoldSineSampling) {
  Segment sine;
  sine.kind = Segment::Kind::sine;
  sine.amplitude = 0.1;
  sine.frequency = 2.0;
  sine.cycles = 1.5;
  const cm::History h = cm::build_history({ramp(-0.5, 10.0, 4), hold(2.0), sine});
  ASSERT_EQ(h.time.size(), 1u + 4u + 100u + 96u);  // defaults: 100 per hold, 64 per sine cycle
  EXPECT_DOUBLE_EQ(h.time[0], 0.0);
  EXPECT_DOUBLE_EQ(h.control[0], 0.0);
  EXPECT_NEAR(h.control[2], -0.25, 1e-15);  // linear ramp
  EXPECT_NEAR(h.time[4], 10.0, 1e-12);
  EXPECT_NEAR(h.control[104], -0.5, 1e-15);  // hold keeps the value
  EXPECT_NEAR(h.time[104], 12.0, 1e-12);
  for (std::size_t k = 105; k < h.time.size(); ++k) {  // c + A sin(2 pi f t')
    const double t_local = h.time[k] - 12.0;
    EXPECT_NEAR(h.control[k], -0.5 + 0.1 * std::sin(2.0 * std::numbers::pi * 2.0 * t_local), 1e-14);
  }
  EXPECT_NEAR(h.time.back(), 12.75, 1e-12);
  EXPECT_THROW(cm::build_history({ramp(-0.5, 0.0)}), cushion::InputError);
  EXPECT_THROW(cm::build_history({hold(-1.0)}), cushion::InputError);
  sine.frequency = 0.0;
  EXPECT_THROW(cm::build_history({sine}), cushion::InputError);
}

TEST(PointDriver, UniaxialFreeHyperfoamMatchesClosedForm) {
  // T_U = sum (2 mu_i/alpha_i)(l^(alpha_i - 1) - l^(-alpha_i nu - 1)), lateral stretch l^(-nu).
  const double nu = 0.2;
  const cm::Hyperfoam foam(terms(nu));
  for (double target : {-0.7, 0.6}) {
    const cm::PointResult r = cm::run_point(foam, cm::LoadMode::uniaxial_free, cm::build_history({ramp(target, 1.0, 20)}));
    for (std::size_t i = 0; i < r.time.size(); ++i) {
      const double l = r.F[i](0, 0);
      EXPECT_NEAR(l, 1.0 + r.control[i], 1e-15);
      double T = 0.0;
      for (const auto& t : terms(nu)) T += 2.0 * t.mu / t.alpha * (std::pow(l, t.alpha - 1.0) - std::pow(l, -t.alpha * nu - 1.0));
      EXPECT_NEAR(r.P[i](0, 0), T, 1e-9 * std::max(std::abs(T), 1e-6)) << "l = " << l;
      EXPECT_LT(relative_error(r.F[i](1, 1), std::pow(l, -nu)), 1e-9) << "l = " << l;
      EXPECT_LT(relative_error(r.F[i](2, 2), std::pow(l, -nu)), 1e-9) << "l = " << l;
      // Laterally free: the Newton stops when its next correction is below 1e-12 l, so the lateral stress left is
      // that correction times the lateral modulus (measured: up to 7e-12 |T| at l = 0.3; round-off before).
      EXPECT_LT(std::abs(r.P[i](1, 1)), 1e-10 * std::max(std::abs(T), 1e-6));
    }
  }
}

/// Linear orthotropic (Saint-Venant-Kirchhoff) test material, S = C E, whose two lateral axes differ: the free-stretch
/// Newton first ties axes that start equal and must untie them here.
class Orthotropic final : public cm::Material {
 public:
  explicit Orthotropic(const cushion::Mat6& C) : C_(C) {}
  std::size_t state_size() const override { return 0; }
  cm::PointResponse integrate(const cushion::Mat3&, const cushion::Mat3& F, double, std::span<const double>,
                              std::span<double>) const override {
    cm::PointResponse r;
    r.S = C_ * cushion::to_voigt_strain(cushion::green_lagrange(F));
    r.dS_dE = C_;
    return r;
  }
  cushion::Mat6c complex_tangent(const cushion::Mat3&, double) const override { return C_.cast<std::complex<double>>(); }
  std::string describe() const override { return "orthotropic test material"; }

 private:
  cushion::Mat6 C_;
};

TEST(PointDriver, UniaxialFreeUntiesLateralAxesOfAnAnisotropicMaterial) {
  // S = C E: with E_11 imposed and S_22 = S_33 = 0, [C22 C23; C23 C33] (E_22, E_33) = -(C21, C31) E_11.
  cushion::Mat6 C = cushion::Mat6::Identity();
  C.topLeftCorner<3, 3>() << 1.0, 0.3, 0.1, 0.3, 0.8, 0.2, 0.1, 0.2, 1.5;
  const Orthotropic material(C);
  const cm::PointResult r = cm::run_point(material, cm::LoadMode::uniaxial_free, cm::build_history({ramp(-0.3, 1.0, 6)}));
  for (std::size_t i = 1; i < r.time.size(); ++i) {
    const double l = r.F[i](0, 0), E11 = 0.5 * (l * l - 1.0);
    const Eigen::Vector2d lateral =
        C.block<2, 2>(1, 1).inverse() * (-E11 * Eigen::Vector2d(C(1, 0), C(2, 0)));  // (E_22, E_33)
    EXPECT_NEAR(0.5 * (r.F[i](1, 1) * r.F[i](1, 1) - 1.0), lateral(0), 1e-12) << "l = " << l;
    EXPECT_NEAR(0.5 * (r.F[i](2, 2) * r.F[i](2, 2) - 1.0), lateral(1), 1e-12) << "l = " << l;
    EXPECT_GT(std::abs(lateral(0) - lateral(1)), 1e-3);  // the axes really differ
  }
}

TEST(PointDriver, ConstrainedAndVolumetricHyperfoamMatchClosedForms) {
  const double nu = 0.2, beta = nu / (1.0 - 2.0 * nu);
  const cm::Hyperfoam foam(terms(nu));
  const cm::History h = cm::build_history({ramp(-0.6, 1.0, 12)});
  // Confined: F = diag(l, 1, 1), J = l: tau_1 = 2 sum (mu/alpha)(l^alpha - J^(-alpha beta)), P11 = tau_1 / l.
  const cm::PointResult c = cm::run_point(foam, cm::LoadMode::uniaxial_constrained, h);
  // Volumetric: l = J^(1/3): tau = 2 sum (mu/alpha)(J^(alpha/3) - J^(-alpha beta)), P11 = tau / l.
  const cm::PointResult v = cm::run_point(foam, cm::LoadMode::volumetric, h);
  for (std::size_t i = 1; i < h.time.size(); ++i) {
    const double l = 1.0 + h.control[i];
    double tau_c = 0.0, tau_v = 0.0;
    for (const auto& t : terms(nu)) {
      tau_c += 2.0 * t.mu / t.alpha * (std::pow(l, t.alpha) - std::pow(l, -t.alpha * beta));
      tau_v += 2.0 * t.mu / t.alpha * (std::pow(l, t.alpha) - std::pow(l * l * l, -t.alpha * beta));
    }
    EXPECT_LT(relative_error(c.P[i](0, 0), tau_c / l), 1e-10);
    EXPECT_LT(relative_error(c.sigma[i](0, 0), tau_c / l), 1e-10);  // J = l
    EXPECT_LT(relative_error(v.P[i](0, 0), tau_v / l), 1e-10);
    EXPECT_LT(relative_error(v.sigma[i](1, 1), tau_v / (l * l * l)), 1e-10);
    EXPECT_NEAR(c.F[i](1, 1), 1.0, 0.0);
  }
}

TEST(PointDriver, SimpleShearNeoHookeanMatchesClosedForm) {
  // F = I + gamma e1 (x) e2, J = 1: sigma = mu (b - I): sigma12 = mu gamma, sigma11 = mu gamma^2,
  // sigma22 = 0; P = sigma F^-T: P12 = mu gamma, P11 = 0.
  const double mu = 0.02, lambda = 0.05;
  const cm::NeoHookean model(mu, lambda);
  const cm::PointResult r = cm::run_point(model, cm::LoadMode::simple_shear, cm::build_history({ramp(1.5, 1.0, 15)}));
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const double g = r.control[i];
    EXPECT_NEAR(r.F[i](0, 1), g, 0.0);
    EXPECT_NEAR(r.sigma[i](0, 1), mu * g, 1e-13);
    EXPECT_NEAR(r.sigma[i](0, 0), mu * g * g, 1e-13);
    EXPECT_NEAR(r.sigma[i](1, 1), 0.0, 1e-13);
    EXPECT_NEAR(r.P[i](0, 1), mu * g, 1e-13);
    EXPECT_NEAR(r.P[i](0, 0), 0.0, 1e-13);
  }
}

TEST(PointDriver, PlatenLiftOffAfterFastUnload) {
  // Hyperfoam (nu = 0.1) with one strong, slow Prony term: compressed to 50 %, then the platen
  // retracts to 10 % in 0.05 s, much faster than the foam recovers (tau = 2 s).
  const auto base = std::make_shared<cm::Hyperfoam>(terms(0.1));
  const cm::Viscoelastic foam(base, {{0.8, 2.0}});
  const std::vector<Segment> protocol = {ramp(-0.5, 1.0, 50), ramp(-0.1, 0.05, 5), hold(40.0, 800)};

  // Displacement control of the same history pulls the foam: the platen would have to be tensile.
  const cm::PointResult pulled = cm::run_point(foam, cm::LoadMode::uniaxial_free, cm::build_history(protocol));
  double max_pulled = 0.0;
  for (const auto& P : pulled.P) max_pulled = std::max(max_pulled, P(0, 0));
  EXPECT_GT(max_pulled, 1e-3);

  const cm::History h = cm::build_history(protocol, cm::AxisControl::platen);
  const cm::PointResult r = cm::run_point(foam, cm::LoadMode::uniaxial_free, h);
  std::size_t clear = 0, resumed = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    EXPECT_LE(r.P[i](0, 0), 0.0) << "tensile platen force at t = " << r.time[i];
    if (!r.in_contact[i]) {
      ++clear;
      EXPECT_EQ(r.P[i](0, 0), 0.0);                  // exactly no force while clear
      EXPECT_LT(r.control[i], h.control[i]);          // the foam surface lags below the platen
      if (i > 0) { EXPECT_GT(r.control[i], r.control[i - 1]); }  // and recovers monotonically
    } else {
      EXPECT_DOUBLE_EQ(r.control[i], h.control[i]);   // in contact: the platen position is imposed
      if (clear > 0) ++resumed;
    }
  }
  EXPECT_GT(clear, 5u);
  EXPECT_GT(resumed, 5u) << "contact should resume once the foam has recovered to the platen";
  EXPECT_TRUE(r.in_contact.back());
  EXPECT_LT(r.P.back()(0, 0), 0.0);
  EXPECT_NEAR(r.control.back(), -0.1, 1e-15);
}

TEST(PointDriver, FreeRecoveryFollowsRetardationTime) {
  // Small strain, one Prony term: with S = 0 (lift-off), E_inf e + a h = 0 and h' = -h/tau + E_inf e'
  // give e(t) = e(t0) exp(-(t - t0) / (tau (1 + a))). Strain 1e-4 (nonlinearity ~1e-4 relative).
  const auto base = std::make_shared<cm::Hyperfoam>(std::vector<cm::HyperfoamTerm>{{0.01, 5.0, 0.0}});
  const double g = 0.6, tau = 1.0, a = g / (1.0 - g);
  const cm::Viscoelastic foam(base, {{g, tau}});
  // A fast compression held for 2 s (the Maxwell branch relaxes), then the platen returns to 0 at once.
  const cm::History h = cm::build_history({ramp(-1e-4, 1e-4, 1), hold(2.0, 200), ramp(0.0, 1e-4, 1), hold(4.0, 4000)},
                                          cm::AxisControl::platen);
  const cm::PointResult r = cm::run_point(foam, cm::LoadMode::uniaxial_free, h);
  // After the release the foam is clear for the whole hold (it never quite reaches the platen at 0).
  const std::size_t i0 = 202;
  ASSERT_FALSE(r.in_contact[i0]);
  const double e0 = r.control[i0], t0 = r.time[i0];
  EXPECT_LT(e0, -1e-5);
  for (std::size_t i = i0; i < r.time.size(); i += 500) {
    ASSERT_FALSE(r.in_contact[i]);
    const double expected = e0 * std::exp(-(r.time[i] - t0) / (tau * (1.0 + a)));
    EXPECT_NEAR(r.control[i], expected, 1e-3 * std::abs(e0)) << "t = " << r.time[i];
  }
}

TEST(PointDriver, FailureAndBadInputAreReported) {
  const cm::NeoHookean model(0.01, 0.01);
  // Volumetric compression to zero volume: the material fails; the error names the time.
  try {
    cm::run_point(model, cm::LoadMode::volumetric, cm::build_history({ramp(-1.0, 2.0, 4)}));
    FAIL() << "expected a failure";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("t = 2 s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(cm::run_point(model, cm::LoadMode::simple_shear, cm::build_history({ramp(0.1, 1.0)}, cm::AxisControl::platen)),
               cushion::InputError);
  EXPECT_THROW(cm::load_mode_from_string("uniaxial"), cushion::InputError);
  EXPECT_EQ(cm::load_mode_from_string("simple_shear"), cm::LoadMode::simple_shear);
}
