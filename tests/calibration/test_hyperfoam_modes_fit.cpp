// Hyperfoam fit from ABAQUS test modes (hyperfoam-only campaigns): the mode responses against the material
// model, a round trip on data from an INDEPENDENT forward computation written here (per-term nu, lateral stretch
// by bisection), and the real Kossa & Berezvai (2016) PE-foam case at the figures measured when it was shipped.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "calibration/hyperfoam_campaign.hpp"
#include "calibration/hyperfoam_modes_fit.hpp"
#include "material/hyperfoam.hpp"
#include "material/stability.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;

namespace {

struct Term {
  double mu, alpha, nu;
};

/// Root of a function increasing on [lo, hi] by bisection (independent of the fit's Newton solver).
double bisect(const std::function<double(double)>& g, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Kirchhoff principal stress of the ABAQUS hyperfoam along stretch l at volume ratio J.
double tau(const std::vector<Term>& terms, double l, double J) {
  double t = 0.0;
  for (const auto& c : terms) {
    const double beta = c.nu / (1.0 - 2.0 * c.nu);
    t += 2.0 * c.mu / c.alpha * (std::pow(l, c.alpha) - std::pow(J, -c.alpha * beta));
  }
  return t;
}

/// Uniaxial: l1 = l, l2 = l3 = t with tau_2 = 0; returns {nominal stress tau_1/l, t}.
std::pair<double, double> uniaxial(const std::vector<Term>& terms, double l) {
  const double t = bisect([&](double x) { return tau(terms, x, l * x * x); }, 0.5, 2.0);
  return {tau(terms, l, l * t * t) / l, t};
}

/// Equibiaxial: l1 = l2 = l, l3 = t with tau_3 = 0.
std::pair<double, double> equibiaxial(const std::vector<Term>& terms, double l) {
  const double t = bisect([&](double x) { return tau(terms, x, l * l * x); }, 0.5, 2.0);
  return {tau(terms, l, l * l * t) / l, t};
}

cal::HyperfoamTest make_test(cal::HyperfoamMode mode, const std::vector<Term>& truth, const std::vector<double>& stretch) {
  cal::HyperfoamTest t;
  t.name = cal::to_string(mode);
  t.mode = mode;
  for (double l : stretch) {
    const auto [P, lateral] = mode == cal::HyperfoamMode::uniaxial ? uniaxial(truth, l) : equibiaxial(truth, l);
    t.control.push_back(l);
    t.stress.push_back(P);
    t.lateral.push_back(lateral);
  }
  return t;
}

std::vector<double> stretches(double lo, int n) {
  std::vector<double> s;
  for (int k = 1; k <= n; ++k) s.push_back(1.0 - (1.0 - lo) * k / n);
  return s;
}

}  // namespace

TEST(HyperfoamModes, ResponsesHaveZeroFreeStressAndMatchTheMaterialModel) {
  // Per-term nu: the free stretch zeroes the free Kirchhoff stress of mat::Hyperfoam, and the loaded nominal
  // stress is its tau_1 / l_1 (volumetric: tau/l; simple shear: (tau_1 - tau_2)/(l_1 + l_2)). 1e-10 MPa.
  const std::vector<mat::HyperfoamTerm> terms{{0.05, 6.0, 0.2}, {-0.01, -2.0, 0.05}, {0.02, 15.0, 0.1}};
  const mat::Hyperfoam foam(terms);
  std::vector<double> mu, alpha, nu;
  for (const auto& t : terms) mu.push_back(t.mu), alpha.push_back(t.alpha), nu.push_back(t.nu);
  const cal::HyperfoamTermsView<double> v{mu.data(), alpha.data(), nu.data(), 3};
  for (double x : {0.4, 0.8, 1.2}) {
    const auto u = cal::mode_response(v, cal::HyperfoamMode::uniaxial, x);
    const auto tu = foam.principal_kirchhoff({x, u.lateral, u.lateral});
    EXPECT_NEAR(tu(1), 0.0, 1e-10);
    EXPECT_NEAR(u.stress, tu(0) / x, 1e-10);
    const auto b = cal::mode_response(v, cal::HyperfoamMode::equibiaxial, x);
    const auto tb = foam.principal_kirchhoff({x, x, b.lateral});
    EXPECT_NEAR(tb(2), 0.0, 1e-10);
    EXPECT_NEAR(b.stress, tb(0) / x, 1e-10);
    const auto p = cal::mode_response(v, cal::HyperfoamMode::planar, x);
    const auto tp = foam.principal_kirchhoff({x, 1.0, p.lateral});
    EXPECT_NEAR(tp(2), 0.0, 1e-10);
    EXPECT_NEAR(p.stress, tp(0) / x, 1e-10);
    const auto vol = cal::mode_response(v, cal::HyperfoamMode::volumetric, x);
    EXPECT_NEAR(vol.stress, foam.principal_kirchhoff({x, x, x})(0) / x, 1e-10);
    const double gamma = x - 0.8, l1 = std::sqrt(1.0 + 0.25 * gamma * gamma) + 0.5 * gamma;
    const auto ts = foam.principal_kirchhoff({l1, 1.0 / l1, 1.0});
    EXPECT_NEAR(cal::mode_response(v, cal::HyperfoamMode::simple_shear, gamma).stress, (ts(0) - ts(1)) / (l1 + 1.0 / l1), 1e-10);
  }
}

TEST(HyperfoamModesFit, RoundTripOnIndependentForwardData) {
  // Known stable 2-term foam with different nu per term; uniaxial to 0.3 and equibiaxial to 0.5 compression with
  // the lateral stretch. The refit reproduces every stress and stretch and the parameters to 1e-4.
  const std::vector<Term> truth{{0.05, 5.0, 0.15}, {0.02, 15.0, 0.05}};
  std::vector<cal::HyperfoamTest> tests{make_test(cal::HyperfoamMode::uniaxial, truth, stretches(0.3, 14)),
                                        make_test(cal::HyperfoamMode::equibiaxial, truth, stretches(0.5, 10))};
  cal::HyperfoamFitSettings s;
  s.terms = 2;
  const cal::HyperfoamModesFit fit = cal::fit_hyperfoam_modes(tests, s);
  for (const auto& f : fit.tests) {
    EXPECT_LT(f.max, 1e-4);
    EXPECT_LT(f.lateral_max, 1e-4);
    EXPECT_GT(f.r2, 1.0 - 1e-8);
  }
  ASSERT_EQ(fit.terms.size(), 2u);
  const bool swapped = fit.terms[0].alpha > fit.terms[1].alpha;
  for (int i = 0; i < 2; ++i) {
    const auto& got = fit.terms[std::size_t(swapped ? 1 - i : i)];
    EXPECT_NEAR(got.mu, truth[std::size_t(i)].mu, 1e-4 * truth[std::size_t(i)].mu);
    EXPECT_NEAR(got.alpha, truth[std::size_t(i)].alpha, 1e-4 * truth[std::size_t(i)].alpha);
    EXPECT_NEAR(got.nu, truth[std::size_t(i)].nu, 1e-4);
  }
}

TEST(HyperfoamModesFit, KossaPolyethyleneFoamReachesTheShippedFigures) {
  // cases/kossa_pe_foam (real data; N = 4, lateral_weight 0.15). Figures measured when the case was shipped (README
  // there), asserted with a small margin: stress R^2 uniaxial 0.999812, equibiaxial 0.999931 (issue 13: >= 0.9998);
  // transverse stretch within 0.449 % and 0.267 % (issue 13: 0.5 %); Drucker-stable in each mode over its data and
  // beyond. About 20 s.
  const cal::HyperfoamCampaign c =
      cal::read_hyperfoam_campaign(std::string(CUSHION_SOURCE_DIR) + "/cases/kossa_pe_foam/campaign.json");
  const cal::HyperfoamModesFit fit = cal::fit_hyperfoam_modes(c.tests, c.settings);
  ASSERT_EQ(fit.tests.size(), 2u);
  EXPECT_GT(fit.tests[0].r2, 0.99980);
  EXPECT_GT(fit.tests[1].r2, 0.99990);
  EXPECT_LT(fit.tests[0].lateral_max, 0.0047);
  EXPECT_LT(fit.tests[1].lateral_max, 0.0030);
  EXPECT_TRUE(cal::stable_over(mat::Hyperfoam(fit.terms), fit.stable_stretch));
  // Each mode's data and beyond: uniaxial from 0.2 (data 0.25), equibiaxial from 0.44 (data 0.55).
  EXPECT_NEAR(fit.stable_stretch[0].first, 0.2, 1e-12);
  EXPECT_NEAR(fit.stable_stretch[1].first, 0.44, 1e-12);
  const auto report = mat::check_stability(mat::Hyperfoam(fit.terms), -0.8, 0.5);
  EXPECT_FALSE(report.modes[0].first_unstable_compression.has_value());  // uniaxial stable to stretch 0.2
}
