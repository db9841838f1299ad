// Requirement: the spring-pot bank (material/spring_pot.hpp) reproduces the Caputo derivative D^q of order q in (0, 1]
// against closed forms: its transfer function against (i omega)^q over 1e-4 to 1e3 Hz, the time-domain recursion
// against D^q of a ramp, t^(1-q)/Gamma(2-q), and D^q of a unit step held, t^-q/Gamma(1-q); at q = 1 it is the plain
// rate.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "material/spring_pot.hpp"

namespace cushion::material {
namespace {

TEST(SpringPotBank, TransferFunctionFollowsThePowerLawOverTheBand) {
  // |G|/|(i w)^q| - 1 within 0.3 % and the phase within 0.1 deg from 1e-4 Hz to 100 Hz (the trapezoid in ln tau at 2
  // nodes a decade errs by about exp(-pi^2/h) = 2e-4; the closed tails put the band's edges outside 1e-5..1e5 s).
  for (double q : {0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.0}) {
    const SpringPotBank bank(q);
    for (double f = 1e-4; f <= 1e2 * 1.0001; f *= std::sqrt(10.0)) {
      const double w = 2.0 * std::numbers::pi * f;
      const std::complex<double> g = bank.transfer(w), exact = std::pow(std::complex<double>(0.0, w), q);
      EXPECT_LT(std::abs(std::abs(g) / std::abs(exact) - 1.0), 3e-3) << "q " << q << ", " << f << " Hz";
      EXPECT_LT(std::abs(std::arg(g / exact)) * 180.0 / std::numbers::pi, 0.1) << "q " << q << ", " << f << " Hz";
    }
  }
}

TEST(SpringPotBank, RampAndHeldStepFollowTheirClosedForms) {
  // x(t) = t for t <= 1 s, then held: D^q x = t^(1-q)/Gamma(2-q) during the ramp and
  // (t^(1-q) - (t-1)^(1-q))/Gamma(2-q) after it. 1000 steps on the ramp (the recursion is exact for a piecewise-linear x;
  // what is left is the bank's own error), then geometric steps to 1000 s: within 0.3 % of the closed form at
  // t = 0.01, 0.1, 1, 10, 100 s and 0.5 % at 1000 s (a hundredth of tau_hi, where the slow tail's spring begins to err).
  for (double q : {0.2, 0.5, 0.8}) {
    const SpringPotBank bank(q);
    std::vector<double> memory(bank.memory_size(1), 0.0);
    double t = 0.0;
    auto closed = [q](double time) {
      const double a = std::pow(time, 1.0 - q), b = time > 1.0 ? std::pow(time - 1.0, 1.0 - q) : 0.0;
      return (a - b) / std::tgamma(2.0 - q);
    };
    auto step = [&](double dt, double dx) {
      double value = 0.0, again = 0.0;
      bank.advance(dt, {&dx, 1}, memory, memory, {&value, 1});
      bank.memory_value(memory, {&again, 1});
      EXPECT_EQ(value, again);
      t += dt;
      return value + bank.dashpot() * dx / dt;
    };
    std::vector<double> checks{0.01, 0.1, 1.0, 10.0, 100.0, 1000.0};
    std::size_t next = 0;
    for (int k = 0; k < 1000; ++k) {
      const double value = step(1e-3, 1e-3);
      if (next < checks.size() && std::abs(t - checks[next]) < 1e-9) {
        EXPECT_NEAR(value / closed(t), 1.0, 3e-3) << "q " << q << ", t " << t;
        ++next;
      }
    }
    const double dt_factor = std::pow(1000.0, 1.0 / 3000.0);  // 1 s -> 1000 s in 3000 geometric steps
    double dt = 1.0 * (dt_factor - 1.0);
    while (next < checks.size()) {
      double target_dt = dt;
      if (t + target_dt > checks[next]) target_dt = checks[next] - t;
      const double value = step(target_dt, 0.0);
      if (std::abs(t - checks[next]) < 1e-9 * checks[next]) {
        EXPECT_NEAR(value / closed(t), 1.0, t < 500.0 ? 3e-3 : 5e-3) << "q " << q << ", t " << t;
        ++next;
      }
      dt *= dt_factor;
    }
  }
}

TEST(SpringPotBank, OrderOneIsTheRate) {
  // q = 1: no branches, no spring, dashpot 1, weight 1/dt, transfer i omega (exact).
  const SpringPotBank bank(1.0);
  EXPECT_EQ(bank.branches(), 0u);
  EXPECT_EQ(bank.memory_size(6), 0u);
  EXPECT_EQ(bank.spring(), 0.0);
  EXPECT_EQ(bank.dashpot(), 1.0);
  EXPECT_EQ(bank.increment_weight(0.01), 100.0);
  EXPECT_EQ(bank.transfer(3.0), std::complex<double>(0.0, 3.0));
  EXPECT_THROW(SpringPotBank(0.0), std::invalid_argument);
  EXPECT_THROW(SpringPotBank(1.01), std::invalid_argument);
  EXPECT_THROW(SpringPotBank(std::nan("")), std::invalid_argument);
}

TEST(SpringPotBank, OrderJustBelowOneApproachesTheRate) {
  // q = 1 - 1e-6: the bank and spring carry a share of order 1e-6, the dashpot tends to 1 (continuity of the form as a
  // fit moves q to its bound): the increment weight at dt = 0.01 s within 1e-4 of 1/dt.
  const SpringPotBank bank(1.0 - 1e-6);
  EXPECT_NEAR(bank.increment_weight(0.01) * 0.01, 1.0, 1e-4);
}

}  // namespace
}  // namespace cushion::material
