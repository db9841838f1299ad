// rival_gap.hpp: the winner's smallest BIC advantage over another candidate with each test's chi2 reweighted within
// the uncertainty of its noise estimate.
//  - with every factor 1 it is the plain BIC difference;
//  - it equals the minimum over every corner of the weight box, found by enumeration (the gap is linear in the
//    weights, so the minimum over the box lies at a corner), and no weighting inside the box goes below it (random
//    interior points);
//  - a hand-computed case; bad input throws.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "calibration/rival_gap.hpp"

namespace cc = cushion::calibration;

namespace {

double weighted_gap(const std::vector<double>& w, const std::vector<double>& o, const std::vector<double>& s,
                    double penalty) {
  double g = penalty;
  for (std::size_t t = 0; t < w.size(); ++t) g += s[t] * (o[t] - w[t]);
  return g;
}

}  // namespace

TEST(RivalGap, EveryFactorOneIsThePlainBicDifference) {
  const std::vector<double> w{120.0, 80.0, 40.0}, o{100.0, 95.0, 60.0};
  EXPECT_DOUBLE_EQ(cc::least_bic_gap(w, o, {1.0, 1.0, 1.0}, 5.8), 5.8 + (255.0 - 240.0));
}

TEST(RivalGap, HandComputedCase) {
  // winner better on the dynamic test (20 chi2), the other on the quasi-static one (8 chi2), same penalty:
  // least gap = 8 * (-1) * 1.15^2 + 20 / 1.6^2
  const double g = cc::least_bic_gap({108.0, 30.0}, {100.0, 50.0}, {1.15, 1.6}, 0.0);
  EXPECT_NEAR(g, -8.0 * 1.15 * 1.15 + 20.0 / (1.6 * 1.6), 1e-12);
}

TEST(RivalGap, IsTheMinimumOverTheWeightBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> chi2(0.0, 400.0), factor(1.0, 2.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 1 + trial % 6;
    std::vector<double> w(n), o(n), u(n);
    for (std::size_t t = 0; t < n; ++t) w[t] = chi2(rng), o[t] = chi2(rng), u[t] = factor(rng);
    const double penalty = 40.0 * (unit(rng) - 0.5);
    const double g = cc::least_bic_gap(w, o, u, penalty);
    double corner_min = INFINITY;
    for (unsigned mask = 0; mask < (1u << n); ++mask) {
      std::vector<double> s(n);
      for (std::size_t t = 0; t < n; ++t) s[t] = (mask >> t & 1u) ? u[t] * u[t] : 1.0 / (u[t] * u[t]);
      corner_min = std::min(corner_min, weighted_gap(w, o, s, penalty));
    }
    EXPECT_NEAR(g, corner_min, 1e-9 * (1.0 + std::abs(corner_min))) << "trial " << trial;
    for (int k = 0; k < 20; ++k) {
      std::vector<double> s(n);
      for (std::size_t t = 0; t < n; ++t) s[t] = std::exp((2.0 * unit(rng) - 1.0) * 2.0 * std::log(u[t]));
      EXPECT_GE(weighted_gap(w, o, s, penalty), g - 1e-9 * (1.0 + std::abs(g)));
    }
  }
}

TEST(RivalGap, BadInputThrows) {
  EXPECT_THROW(cc::least_bic_gap({1.0, 2.0}, {1.0}, {1.0, 1.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(cc::least_bic_gap({1.0}, {1.0}, {0.9}, 0.0), std::invalid_argument);
  EXPECT_THROW(cc::least_bic_gap({1.0}, {1.0}, {NAN}, 0.0), std::invalid_argument);
}

TEST(RivalGap, FactorsByKindOfTest) {
  const cc::NoiseUncertainty u;
  EXPECT_DOUBLE_EQ(u.of("quasi_static"), u.quasi_static);
  EXPECT_DOUBLE_EQ(u.of("indentation"), u.quasi_static);
  EXPECT_DOUBLE_EQ(u.of("dynamic"), u.dynamic);
  EXPECT_DOUBLE_EQ(u.of("dynamic_stiffness"), u.dynamic);
}
