// Quasi-static records: nominal conversion, segment detection with hold, noise and lift-off, and
// rejection of bad records with messages naming the file.
#include <gtest/gtest.h>

#include <random>

#include "calibration/segments.hpp"
#include "io/input_error.hpp"

namespace cal = cushion::calibration;

namespace {

const cal::Specimen kBlock{80.0, 80.0, 80.0, 6.5e-11};

/// Force-displacement record of the paper's protocol: 2 mm/s to 60 mm, hold, unload; force a smooth
/// function of displacement with a loading/unloading offset. Optional Gaussian noise (seeded).
struct Raw {
  std::vector<double> t, u, F;
};
Raw paper_like(double hold, double noise_u = 0.0, double noise_F = 0.0, double lift_off_u = -1.0) {
  std::mt19937 gen(42);
  std::normal_distribution<double> n(0.0, 1.0);
  Raw r;
  const double dt = 0.02, T = 30.0;
  for (double t = 0.0; t <= 2 * T + hold + 1e-9; t += dt) {
    double u, F;
    if (t <= T) {
      u = 2.0 * t;
      F = 60.0 * std::pow(u / 60.0, 1.5) * 100.0;
    } else if (t <= T + hold) {
      u = 60.0;
      F = 6000.0 - 50.0 * (t - T);
    } else {
      u = 60.0 - 2.0 * (t - T - hold);
      F = (6000.0 - 50.0 * hold) * std::pow(u / 60.0, 2.0);
      if (u < lift_off_u) F = 0.0;
    }
    r.t.push_back(t);
    r.u.push_back(u + noise_u * n(gen));
    r.F.push_back(F + noise_F * n(gen));
  }
  return r;
}

cal::StressStrainRecord nominal(const Raw& r) { return cal::to_nominal("qs.csv", r.t, r.u, r.F, kBlock); }

std::string message_of(const cal::StressStrainRecord& r) {
  try {
    cal::detect_segments(r);
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Segments, NominalConversion) {
  const auto r = cal::to_nominal("x.csv", {0.0, 1.0}, {0.0, 8.0}, {0.0, 64.0}, kBlock);
  EXPECT_DOUBLE_EQ(r.strain[1], 0.1);    // 8 mm / 80 mm
  EXPECT_DOUBLE_EQ(r.stress[1], 0.01);   // 64 N / 6400 mm^2 = 0.01 MPa
  EXPECT_THROW(cal::to_nominal("x.csv", {0.0, 0.0}, {0.0, 1.0}, {0.0, 1.0}, kBlock), cushion::InputError);
}

TEST(Segments, DetectsLoadingHoldUnloading) {
  const auto r = nominal(paper_like(2.0));
  const auto s = cal::detect_segments(r);
  // Corners at t = 30 s and 32 s, exact samples of the 0.02 s grid: within one sample.
  EXPECT_NEAR(r.time[s.load_end], 30.0, 0.021);
  EXPECT_NEAR(r.time[s.unload_begin], 32.0, 0.021);
  EXPECT_NEAR(s.hold_duration, 2.0, 0.05);
  EXPECT_DOUBLE_EQ(s.peak_strain, 0.75);
  EXPECT_FALSE(s.lift_off);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(Segments, NoiseBelowToleranceIsAccepted) {
  // 0.01 mm displacement noise (1.25e-4 strain) and 1 N force noise: the per-sample strain step is
  // 5e-4 so raw samples are non-monotonic, but within 6 x the estimated noise.
  const auto r = nominal(paper_like(2.0, 0.01, 1.0));
  const auto s = cal::detect_segments(r);
  EXPECT_NEAR(s.strain_noise, 0.01 / 80.0, 0.3 * 0.01 / 80.0);  // noise estimate within 30 %
  EXPECT_NEAR(s.hold_duration, 2.0, 0.1);
}

TEST(Segments, LiftOffTruncatesTheUnloadingBranchWithAWarning) {
  const auto r = nominal(paper_like(2.0, 0.0, 0.0, 12.0));  // force 0 below 12 mm (strain 0.15)
  const auto s = cal::detect_segments(r);
  EXPECT_TRUE(s.lift_off);
  EXPECT_NEAR(s.lift_off_strain, 0.15, 0.001);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("lifted off"), std::string::npos);
  EXPECT_NEAR(r.strain[s.unload_end], 0.15, 0.001);
}

TEST(Segments, RejectsNoUnloadingBranch) {
  Raw raw = paper_like(0.0);
  const std::size_t half = raw.t.size() / 2 + 1;
  raw.t.resize(half);
  raw.u.resize(half);
  raw.F.resize(half);
  const std::string m = message_of(nominal(raw));
  EXPECT_NE(m.find("qs.csv"), std::string::npos) << m;
  EXPECT_NE(m.find("no unloading branch"), std::string::npos) << m;
}

// A fast test of a slowly recovering foam: the stress is gone within 4 mm of the peak (strain 0.05 of 0.75) and the
// machine stopped recording there (foreign campaign seed 2026 c028, qs_600). The branch is short but it is one.
TEST(Segments, AnUnloadingWhoseStressIsGoneWithinAFewPercentOfStrainIsABranch) {
  Raw raw = paper_like(0.0);
  Raw cut;
  for (std::size_t i = 0; i < raw.t.size(); ++i) {
    if (raw.t[i] > 30.0 + 2.0) break;  // 4 mm of unloading at 2 mm/s
    cut.t.push_back(raw.t[i]);
    cut.u.push_back(raw.u[i]);
    cut.F.push_back(raw.t[i] <= 30.0 ? raw.F[i] : raw.F[i] * std::pow(1.0 - (raw.t[i] - 30.0) / 2.0, 3.0) + 0.5);
  }
  const auto r = nominal(cut);
  const auto s = cal::detect_segments(r);
  // Truncated where the force reaches ~0 (below 1e-3 of the peak: 6 N, at u = 56.4 mm), as any lift-off.
  EXPECT_TRUE(s.lift_off);
  EXPECT_NEAR(r.strain[s.unload_end], 56.4 / 80.0, 0.002);
  EXPECT_GT(s.unload_end - s.unload_begin, 80u);
  // The same record with the stress still at 20 % of its peak where it ends: no unloading branch.
  for (std::size_t i = 0; i < cut.t.size(); ++i)
    if (cut.t[i] > 30.0) cut.F[i] = std::max(cut.F[i], 0.2 * 6000.0);
  const std::string m = message_of(nominal(cut));
  EXPECT_NE(m.find("no unloading branch"), std::string::npos) << m;
}

TEST(Segments, RejectsNonMonotonicLoading) {
  Raw raw = paper_like(2.0);
  for (std::size_t i = 0; i < raw.t.size(); ++i)
    if (raw.t[i] > 10.0 && raw.t[i] < 12.0) raw.u[i] -= 3.0;  // 3 mm back-off mid-loading
  const auto r = nominal(raw);
  const std::string m = message_of(r);
  EXPECT_NE(m.find("qs.csv"), std::string::npos) << m;
  EXPECT_NE(m.find("non-monotonic loading"), std::string::npos) << m;
}

TEST(Segments, RejectsTooFewPoints) {
  const std::string m = message_of(cal::to_nominal("qs.csv", {0, 1, 2, 3}, {0, 1, 2, 1}, {0, 1, 2, 1}, kBlock));
  EXPECT_NE(m.find("too few points"), std::string::npos) << m;
}

TEST(Segments, NoiseLevelOfWhiteNoise) {
  std::mt19937 gen(7);
  std::normal_distribution<double> n(0.0, 0.5);
  std::vector<double> x;
  for (int i = 0; i < 20000; ++i) x.push_back(0.01 * i + n(gen));
  // Robust estimator of sigma = 0.5 from second differences: within 5 % on 20000 samples.
  EXPECT_NEAR(cal::noise_level(x), 0.5, 0.025);
}
