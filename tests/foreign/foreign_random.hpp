#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: this folder includes and links neither (C++ standard library, Eigen, nlohmann-json only).
///
/// Portable seeded random numbers: std::mt19937_64 is specified bit for bit by the standard, but the
/// std:: distributions are not, so uniform and Gaussian draws are written here (53-bit uniform,
/// Box-Muller). Sub-seeds come from splitmix64, so each campaign and each test has its own stream.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace foreign_bench {

/// splitmix64 step: a well-mixed 64-bit value from (seed, stream).
inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// Log-uniform in [lo, hi] (lo, hi > 0).
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  /// Integer in [0, n).
  std::size_t index(std::size_t n) { return static_cast<std::size_t>(unit() * static_cast<double>(n)); }
  /// Standard normal (Box-Muller; the second value is discarded to keep the stream simple).
  double normal() {
    const double u1 = 1.0 - unit();  // (0, 1]
    const double u2 = unit();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace foreign_bench
