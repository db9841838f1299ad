// Requirement: check_stability finds the first Drucker-unstable nominal strain of each mode and side,
// agreeing with an independent closed-form scan for hyperfoam (analytic lateral stretches and
// analytic dtau/d ln l), flags known unstable sets and passes stable ones.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "material/hyperfoam.hpp"
#include "material/neo_hookean.hpp"
#include "material/stability.hpp"

namespace cushion::material {
namespace {

const StabilityMode kModes[4] = {StabilityMode::uniaxial, StabilityMode::equibiaxial, StabilityMode::planar,
                                 StabilityMode::volumetric};

// ---- independent closed forms for hyperfoam with one common nu (docs/physics.md 2.2-2.4) ----
Vec3 tau_closed(const std::vector<HyperfoamTerm>& t, const Vec3& l) {
  const double J = l.prod();
  Vec3 tau = Vec3::Zero();
  for (const auto& k : t)
    for (int a = 0; a < 3; ++a) tau(a) += 2.0 * k.mu / k.alpha * (std::pow(l(a), k.alpha) - std::pow(J, -k.alpha * k.beta()));
  return tau;
}
Mat3 M_closed(const std::vector<HyperfoamTerm>& t, const Vec3& l) {  // dtau_a/d ln l_b
  const double J = l.prod();
  Mat3 M = Mat3::Zero();
  for (const auto& k : t)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        M(a, b) += 2.0 * k.mu * ((a == b ? std::pow(l(a), k.alpha) : 0.0) + k.beta() * std::pow(J, -k.alpha * k.beta()));
  return M;
}
double K_closed(const std::vector<HyperfoamTerm>& t, const Vec3& l, int a, int b) {
  if (l(a) == l(b)) {  // limit dtau_a/d eps_a - dtau_a/d eps_b = 2 sum mu_i l^alpha_i
    double K = 0.0;
    for (const auto& k : t) K += 2.0 * k.mu * std::pow(l(a), k.alpha);
    return K;
  }
  const Vec3 tau = tau_closed(t, l);
  return (tau(a) - tau(b)) / (std::log(l(a)) - std::log(l(b)));
}
Vec3 mode_stretches(StabilityMode m, double l, double nu) {
  switch (m) {
    case StabilityMode::uniaxial: return {l, std::pow(l, -nu), std::pow(l, -nu)};
    case StabilityMode::equibiaxial: return {l, l, std::pow(l, -2.0 * nu / (1.0 - nu))};
    case StabilityMode::planar: return {l, 1.0, std::pow(l, -nu / (1.0 - nu))};
    case StabilityMode::volumetric: return {l, l, l};
  }
  return {};
}
std::optional<double> closed_form_scan(const std::vector<HyperfoamTerm>& t, double nu, StabilityMode m, double end,
                                       int steps) {
  for (int i = 0; i <= steps; ++i) {
    const double strain = end * i / steps;
    const Vec3 l = mode_stretches(m, 1.0 + strain, nu);
    bool ok = Eigen::SelfAdjointEigenSolver<Mat3>(M_closed(t, l)).eigenvalues().minCoeff() > 0.0;
    ok = ok && K_closed(t, l, 0, 1) > 0.0 && K_closed(t, l, 1, 2) > 0.0 && K_closed(t, l, 0, 2) > 0.0;
    if (!ok) return strain;
  }
  return std::nullopt;
}

TEST(Stability, LogTangentPushForwardMatchesClosedForms) {
  // Hyperfoam: M = 2 sum mu (l^a delta + beta J^(-a beta)), K from tau differences; neo-Hookean:
  // M = 2 mu l_a^2 delta + lambda, K = mu (l_a^2 - l_b^2)/(ln l_a - ln l_b). Tolerance 1e-10 relative.
  const std::vector<HyperfoamTerm> t{{0.02, 9.0, 0.2}, {0.004, -3.0, 0.2}, {-0.002, 2.0, 0.2}};
  const Hyperfoam foam(t);
  const double mu = 0.05, lambda = 0.2;
  const NeoHookean neo(mu, lambda);
  for (const Vec3& l : {Vec3(0.6, 1.3, 0.9), Vec3(0.7, 0.7, 1.2), Vec3(1.0, 1.0, 1.0), Vec3(0.3, 2.0, 2.0)}) {
    const Mat6 T = kirchhoff_log_tangent(foam, l);
    const Mat3 M = M_closed(t, l);
    EXPECT_LT((T.topLeftCorner<3, 3>() - M).cwiseAbs().maxCoeff(), 1e-10 * M.cwiseAbs().maxCoeff()) << l.transpose();
    const int A[3] = {0, 1, 0}, B[3] = {1, 2, 2};
    for (int p = 0; p < 3; ++p) {
      const double K = K_closed(t, l, A[p], B[p]);
      EXPECT_NEAR(T(3 + p, 3 + p), K, 1e-10 * std::abs(K)) << l.transpose() << " pair " << p;
      const double Kn = l(A[p]) == l(B[p]) ? 2.0 * mu * l(A[p]) * l(A[p])
                                           : mu * (l(A[p]) * l(A[p]) - l(B[p]) * l(B[p])) / std::log(l(A[p]) / l(B[p]));
      EXPECT_NEAR(kirchhoff_log_tangent(neo, l)(3 + p, 3 + p), Kn, 1e-10 * Kn);
    }
    const Mat3 Mn = (2.0 * mu * l.cwiseProduct(l)).asDiagonal().toDenseMatrix() + Mat3::Constant(lambda);
    EXPECT_LT((kirchhoff_log_tangent(neo, l).topLeftCorner<3, 3>() - Mn).cwiseAbs().maxCoeff(), 1e-10 * Mn.maxCoeff());
  }
}

TEST(Stability, StableSetsPass) {
  // All mu_i > 0 and nu >= 0 is sufficient for stability (docs/physics.md 2.4); neo-Hookean is stable too.
  for (const auto& t : {std::vector<HyperfoamTerm>{{0.02, 9.0, 0.1}, {0.004, -3.0, 0.1}},
                        std::vector<HyperfoamTerm>{{0.01, 12.0, 0.0}, {0.002, -5.0, 0.2}, {0.001, 2.0, 0.3}}}) {
    const StabilityReport r = check_stability(Hyperfoam(t));
    EXPECT_TRUE(r.stable()) << r.summary();
    ASSERT_EQ(r.modes.size(), 4u);
    EXPECT_NE(r.summary().find("uniaxial: stable over [-0.9, 10]"), std::string::npos) << r.summary();
  }
  EXPECT_TRUE(check_stability(NeoHookean(0.05, 0.2)).stable());
}

TEST(Stability, NegativeSingleTermIsUnstableEverywhere) {
  const StabilityReport r = check_stability(Hyperfoam({{-0.01, 2.0, 0.0}}));
  EXPECT_FALSE(r.stable());
  for (const StabilityModeResult& m : r.modes) {
    ASSERT_TRUE(m.first_unstable_compression && m.first_unstable_tension) << to_string(m.mode);
    EXPECT_EQ(*m.first_unstable_compression, 0.0);
    EXPECT_EQ(*m.first_unstable_tension, 0.0);
  }
}

TEST(Stability, MixedSignSetFailsInCompressionAtTheAnalyticStrain) {
  // nu = 0, mu = (0.02, -0.005), alpha = (2, -4): M = 2 (0.02 l^2 - 0.005 l^-4) in every mode, singular
  // at l* = 0.25^(1/6). The first unstable grid strain lies in (l* - 1 - step, l* - 1]; tension is stable.
  const Hyperfoam foam({{0.02, 2.0, 0.0}, {-0.005, -4.0, 0.0}});
  const int steps = 400;
  const double step = 0.9 / steps, e_star = std::pow(0.25, 1.0 / 6.0) - 1.0;
  const StabilityReport r = check_stability(foam, -0.9, 10.0, steps);
  for (const StabilityModeResult& m : r.modes) {
    ASSERT_TRUE(m.first_unstable_compression.has_value()) << to_string(m.mode);
    EXPECT_LE(*m.first_unstable_compression, e_star) << to_string(m.mode);
    EXPECT_GT(*m.first_unstable_compression, e_star - step - 1e-12) << to_string(m.mode);
    EXPECT_FALSE(m.first_unstable_tension.has_value()) << to_string(m.mode);
  }
}

TEST(Stability, ModeDependentInstabilityMatchesClosedFormScan) {
  // Lateral stretches solved numerically vs the analytic ones of docs/physics.md 2.3: the first unstable
  // grid strain agrees within one grid step per mode and side. This set is stable in uniaxial and
  // planar compression but unstable in equibiaxial and volumetric compression.
  const double nu = 0.2;
  const int steps = 400;
  for (const auto& t : {std::vector<HyperfoamTerm>{{0.02, 4.0, nu}, {-0.01, 2.0, nu}},
                        std::vector<HyperfoamTerm>{{0.02, -2.0, nu}, {-0.006, 6.0, nu}},
                        std::vector<HyperfoamTerm>{{0.02, 2.0, nu}, {-0.005, -4.0, nu}}}) {
    const StabilityReport r = check_stability(Hyperfoam(t), -0.9, 10.0, steps);
    for (const StabilityModeResult& m : r.modes) {
      for (auto [end, got] : {std::pair{-0.9, m.first_unstable_compression}, std::pair{10.0, m.first_unstable_tension}}) {
        const std::optional<double> want = closed_form_scan(t, nu, m.mode, end, steps);
        ASSERT_EQ(got.has_value(), want.has_value()) << to_string(m.mode) << " end " << end << "\n" << r.summary();
        if (want) {
          EXPECT_NEAR(*got, *want, std::abs(end) / steps + 1e-12) << to_string(m.mode) << " end " << end;
        }
      }
    }
  }
  const StabilityReport r = check_stability(Hyperfoam({{0.02, 4.0, nu}, {-0.01, 2.0, nu}}));
  EXPECT_FALSE(r.modes[0].first_unstable_compression.has_value());  // uniaxial
  EXPECT_TRUE(r.modes[1].first_unstable_compression.has_value());   // equibiaxial
  EXPECT_FALSE(r.modes[2].first_unstable_compression.has_value());  // planar
  EXPECT_TRUE(r.modes[3].first_unstable_compression.has_value());   // volumetric
  EXPECT_EQ(r.modes[1].mode, StabilityMode::equibiaxial);
  EXPECT_THROW(check_stability(Hyperfoam({{0.01, 2.0, 0.0}}), 0.1, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::material
