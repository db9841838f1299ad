// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/:
// the 1D base foam (hyperfoam at nu = 0 plus Prony weights) and its seeded random families.
#include "foreign_foam.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace foreign_bench {

namespace {

double stretch_of(double strain) { return 1.0 - strain; }

/// Compressive stress of one term per unit mu: -2/alpha (l^(alpha-1) - 1/l).
double term_stress_per_mu(double alpha, double strain) {
  const double l = stretch_of(strain);
  return -2.0 / alpha * (std::pow(l, alpha - 1.0) - 1.0 / l);
}

double stress_of_terms(const std::vector<HyperfoamTerm>& terms, double strain) {
  double s = 0.0;
  for (const auto& t : terms) s += t.mu_kPa * term_stress_per_mu(t.alpha, strain);
  return s;
}

struct FamilyRanges {
  double density_lo, density_hi;
  double plateau_alpha_lo, plateau_alpha_hi;
  double densification_alpha_lo, densification_alpha_hi;
  double stress_50_lo_kPa, stress_50_hi_kPa;
  double prony_sum_lo, prony_sum_hi;
};

// Ranges (seat foam, plausible; the README's shipped foams sit inside them):
//   soft_plateau_50: 48-52 kg/m^3, s_e(50 %) 2-3.5 kPa, sum g 0.35-0.6, sharp plateau (alpha 12-18), late densification.
//   stiff_65:        63-67 kg/m^3, s_e(50 %) 5-9 kPa, sum g 0.25-0.45, rounder knee (alpha 7-10), earlier densification.
//   random:          30-80 kg/m^3, sum g 0.2-0.6, s_e(50 %) = 3.5 kPa (rho/55)^1.5 x lognormal(0.3), clipped to 1-10 kPa.
constexpr FamilyRanges soft_plateau{48, 52, 12, 18, -5.0, -3.5, 2.0, 3.5, 0.35, 0.6};
constexpr FamilyRanges stiff{63, 67, 7, 10, -2.5, -1.5, 5.0, 9.0, 0.25, 0.45};

std::vector<PronyTerm> draw_prony(double prony_sum, Random& random) {
  std::vector<PronyTerm> prony;
  double weights = 0.0;
  for (int decade = -2; decade <= 2; ++decade) {
    PronyTerm p;
    p.tau_s = std::pow(10.0, decade + random.uniform(-0.25, 0.25));
    p.g = std::pow(10.0, -0.15 * decade) * std::exp(0.5 * random.normal());  // falling with tau, as measured foams
    weights += p.g;
    prony.push_back(p);
  }
  for (auto& p : prony) p.g *= prony_sum / weights;
  return prony;
}

/// Terms with given alphas and shares of s_e(0.5); mu_i follow from the target stress at 50 %.
std::vector<HyperfoamTerm> terms_with_shares(const std::vector<double>& alphas, const std::vector<double>& shares,
                                             double stress_50_kPa) {
  std::vector<HyperfoamTerm> terms;
  for (std::size_t i = 0; i < alphas.size(); ++i)
    terms.push_back({shares[i] * stress_50_kPa / term_stress_per_mu(alphas[i], 0.5), alphas[i]});
  return terms;
}

BaseFoam draw_once(const std::string& family, Random& random) {
  BaseFoam foam;
  foam.family = family;
  std::vector<double> alphas, shares;
  double stress_50_kPa = 0.0, prony_sum = 0.0;
  const double densification_share = random.uniform(0.06, 0.25);
  if (family == "soft_plateau_50" || family == "stiff_65") {
    const FamilyRanges& r = family == "stiff_65" ? stiff : soft_plateau;
    foam.density_kg_m3 = random.uniform(r.density_lo, r.density_hi);
    const double extra_alpha = family == "stiff_65" ? random.uniform(3.0, 4.5) : random.uniform(1.5, 3.0);
    const double extra_share = random.uniform(0.05, 0.2);
    alphas = {random.uniform(r.plateau_alpha_lo, r.plateau_alpha_hi),
              random.uniform(r.densification_alpha_lo, r.densification_alpha_hi), extra_alpha};
    shares = {1.0 - densification_share - extra_share, densification_share, extra_share};
    stress_50_kPa = random.uniform(r.stress_50_lo_kPa, r.stress_50_hi_kPa);
    prony_sum = random.uniform(r.prony_sum_lo, r.prony_sum_hi);
  } else if (family == "random") {
    foam.density_kg_m3 = random.uniform(30.0, 80.0);
    const int extra_terms = static_cast<int>(random.index(3));  // 2-4 terms in all
    alphas = {random.uniform(6.0, 20.0), random.uniform(-5.0, -1.5)};
    shares = {0.0, densification_share};
    double rest = 1.0 - densification_share;
    for (int k = 0; k < extra_terms; ++k) {
      alphas.push_back(random.unit() < 0.5 ? random.uniform(1.0, 5.0) : random.uniform(-1.2, -0.3));
      const double share = random.uniform(0.03, 0.12);
      shares.push_back(share);
      rest -= share;
    }
    shares[0] = rest;
    stress_50_kPa = std::clamp(3.5 * std::pow(foam.density_kg_m3 / 55.0, 1.5) * std::exp(0.3 * random.normal()), 1.0, 10.0);
    prony_sum = random.uniform(0.2, 0.6);
  } else {
    throw std::invalid_argument("unknown base-foam family '" + family + "'");
  }
  foam.hyperfoam = terms_with_shares(alphas, shares, stress_50_kPa);
  foam.prony = draw_prony(prony_sum, random);
  return foam;
}

}  // namespace

double BaseFoam::energy_kPa(double strain) const {
  const double l = stretch_of(strain);
  double w = 0.0;
  for (const auto& t : hyperfoam)
    w += 2.0 * t.mu_kPa / (t.alpha * t.alpha) * (std::pow(l, t.alpha) - 1.0 - t.alpha * std::log(l));
  return w;
}

double BaseFoam::elastic_stress_kPa(double strain) const { return stress_of_terms(hyperfoam, strain); }

double BaseFoam::elastic_tangent_kPa(double strain) const {
  const double l = stretch_of(strain);
  double e = 0.0;
  for (const auto& t : hyperfoam)
    e += 2.0 * t.mu_kPa / t.alpha * ((t.alpha - 1.0) * std::pow(l, t.alpha - 2.0) + 1.0 / (l * l));
  return e;
}

double BaseFoam::prony_sum() const {
  double s = 0.0;
  for (const auto& p : prony) s += p.g;
  return s;
}

double BaseFoam::decorator_weight(std::size_t j) const { return prony[j].g / (1.0 - prony_sum()); }

BaseFoam draw_base_foam(const std::string& family, Random& random) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    BaseFoam foam = draw_once(family, random);
    const double densification = foam.elastic_stress_kPa(0.75) / foam.elastic_stress_kPa(0.5);
    const bool positive = std::all_of(foam.hyperfoam.begin(), foam.hyperfoam.end(), [](auto& t) { return t.mu_kPa > 0; });
    if (positive && densification >= 1.8 && densification <= 8.0) return foam;
  }
  throw std::runtime_error("draw_base_foam: no plausible foam in 1000 draws");
}

std::string draw_base_family(Random& random) {
  static const char* families[] = {"soft_plateau_50", "stiff_65", "random"};
  return families[random.index(3)];
}

}  // namespace foreign_bench
