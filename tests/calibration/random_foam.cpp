#include "random_foam.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>

#include "calibration/hyperfoam_fit.hpp"
#include "calibration/lab.hpp"
#include "material/hyperfoam.hpp"
#include "material/io/material_file.hpp"
#include "material/stability.hpp"

namespace cushion::random_foam {

namespace {

namespace fs = std::filesystem;

/// Portable uniform draws (std::uniform_real_distribution is implementation-defined).
class Draw {
 public:
  explicit Draw(unsigned long long seed) : rng_(seed * 0x9E3779B97F4A7C15ULL + 0x5EED) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(rng_() >> 11) * 0x1.0p-53; }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  int integer(int lo, int hi) { return lo + int(rng_() % std::uint64_t(hi - lo + 1)); }

 private:
  std::mt19937_64 rng_;
};

double stress(const std::vector<material::HyperfoamTerm>& terms, double strain) {
  return calibration::hyperfoam_uniaxial_stress(terms, 0.0, calibration::Lateral::free, {strain}).front();
}

}  // namespace

RandomFoam make_random_foam(unsigned long long seed) {
  Draw d(seed);
  RandomFoam foam;
  foam.seed = seed;
  for (;;) {
    ++foam.draws;
    const int N = d.integer(2, 4);
    std::vector<material::HyperfoamTerm> terms;
    std::vector<double> share;
    for (int i = 0; i < N; ++i) {
      const bool densification = i > 0 && d.chance(0.5);
      const double alpha = densification ? -d.uniform(1.0, 8.0) : d.uniform(2.0, 25.0);
      double w = densification ? d.log_uniform(0.003, 0.3) : d.log_uniform(0.05, 1.0);
      if (i > 0 && !densification && d.chance(1.0 / 6.0)) w = -0.3 * w;  // softening correction
      terms.push_back({1.0, alpha, 0.0});
      share.push_back(w);
    }
    double total = 0.0;
    for (double w : share) total += w;
    if (!(total > 0.1)) continue;
    const double s50 = d.log_uniform(1e-3, 1e-2);  // [MPa]
    for (int i = 0; i < N; ++i) {
      const double unit = stress({terms[i]}, 0.5);  // stress at 50 % of a unit-mu term
      terms[i].mu = share[i] / total * s50 / unit;
    }
    const double ratio = stress(terms, 0.75) / stress(terms, 0.5);
    if (!(ratio >= 1.3 && ratio <= 30.0)) continue;
    if (!material::check_stability(material::Hyperfoam(terms), -0.9, 0.5).stable()) continue;
    // Prony series.
    const std::vector<double> tau{0.01, 0.1, 1.0, 10.0, 100.0};
    std::vector<double> g(tau.size(), 0.0);
    double sum = 0.0;
    for (std::size_t r = 0; r < tau.size(); ++r)
      if (d.chance(0.75)) sum += (g[r] = d.log_uniform(0.1, 1.0));
    if (sum == 0.0) sum = (g[d.integer(0, int(tau.size()) - 1)] = 1.0);
    const double g_total = d.uniform(0.2, 0.6);
    foam.material.terms = terms;
    foam.material.prony.clear();
    for (std::size_t r = 0; r < tau.size(); ++r) foam.material.prony.push_back({g[r] / sum * g_total, tau[r]});
    foam.density_kg_m3 = d.uniform(30.0, 80.0);
    return foam;
  }
}

std::string RandomFoam::describe() const {
  std::ostringstream o;
  o.precision(4);
  o << "seed " << seed << ": hyperfoam";
  for (const auto& t : material.terms) o << " (mu " << t.mu * 1e3 << " kPa, alpha " << t.alpha << ")";
  o << "; g";
  for (const auto& p : material.prony) o << " " << p.g << "@" << p.tau << "s";
  o << "; " << density_kg_m3 << " kg/m3";
  return o.str();
}

fs::path make_random_foam_campaign(const RandomFoam& foam, const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  calibration::LabTruth truth;
  truth.description = "random foam, " + foam.describe();
  truth.material_file = dir / "truth_material.json";
  material::write_material_file(calibration::to_spec(foam.material, "random_foam_" + std::to_string(foam.seed),
                                                     "SYNTHETIC random foam (tests/calibration/random_foam.hpp), " +
                                                         foam.describe(),
                                                     foam.density_kg_m3 * 1e-12),
                                truth.material_file);
  truth.specimen.density_kg_m3 = foam.density_kg_m3;
  const double rate[] = {120.0, 30.0, 480.0}, hz[] = {10.0, 4.0, 40.0};
  for (int k = 0; k < 3; ++k) {
    calibration::QuasiStaticProtocol q;
    q.name = "quasistatic_" + std::to_string(int(rate[k])) + "mm_min";
    q.rate_mm_min = rate[k];
    q.max_strain = 0.75;
    q.hold_s = 2.0;
    q.sample_hz = hz[k];
    q.prior.preflex_cycles = 0;
    q.use = "calibration";
    truth.quasi_static.push_back(q);
  }
  calibration::DynamicProtocol p;
  p.name = "dynamic_preload25";
  p.preload_strain = 0.25;
  for (int f = 1; f <= 20; ++f) p.frequencies_Hz.push_back(f);
  p.use = "calibration";
  truth.dynamic.push_back(p);
  std::ostringstream log;
  calibration::run_lab(truth, dir / "campaign", log);
  return dir / "campaign" / "campaign.json";
}

}  // namespace cushion::random_foam
