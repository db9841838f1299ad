#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: its own forms, parameters and code (C++ standard library, Eigen, nlohmann-json only).
///
/// The base foam of the 1D test machine: uniaxial compression with zero lateral contraction
/// (nu = 0, F = diag(l, 1, 1), l = 1 - e, e = nominal compressive strain, compression positive).
///   Hyperfoam energy (nu = 0, J = l):  W(l) = sum_i 2 mu_i/alpha_i^2 (l^alpha_i - 1 - alpha_i ln l)
///   Tension-positive nominal stress:   P(l) = dW/dl = sum_i 2 mu_i/alpha_i (l^(alpha_i - 1) - l^-1)
///   Compressive nominal stress:        s_e(e) = -P(1 - e) = dW/de  (> 0 in compression for mu_i > 0,
///                                      any sign of alpha_i; monotone in e for mu_i > 0)
///   Viscoelasticity (FEBio decorator form on the elastic second Piola-Kirchhoff stress S_e = s_e/l, 1D;
///   foreign_machine.cpp):
///     s = l (S_e + sum_j h_j),  h_j(t+dt) = exp(-dt/tau_j) h_j + a_j (1 - exp(-x))/x (S_e(t+dt) - S_e(t)),
///     x = dt/tau_j, a_j = g_j/(1 - sum g): g_j are the usual relative Prony moduli (fractions of the
///     instantaneous modulus, sum g < 1; drawn with sum g 0.2-0.6), a_j the same weights on the LONG-TERM
///     stress s_e (relaxed stress s_e, instantaneous s_e/(1 - sum g)).
/// Stresses in kPa, times in s.
#include <string>
#include <vector>

#include "foreign_random.hpp"

namespace foreign_bench {

struct HyperfoamTerm {
  double mu_kPa = 0.0;
  double alpha = 0.0;  ///< != 0
};

struct PronyTerm {
  double g = 0.0;      ///< relative modulus (fraction of the instantaneous modulus)
  double tau_s = 0.0;
};

struct BaseFoam {
  std::string family;             ///< "soft_plateau_50", "stiff_65" or "random"
  double density_kg_m3 = 0.0;
  std::vector<HyperfoamTerm> hyperfoam;
  std::vector<PronyTerm> prony;

  double energy_kPa(double strain) const;            ///< W(e) [kPa = kJ/m^3]
  double elastic_stress_kPa(double strain) const;    ///< s_e(e) = dW/de
  double elastic_tangent_kPa(double strain) const;   ///< E_t(e) = ds_e/de
  double prony_sum() const;                          ///< sum g_j
  double decorator_weight(std::size_t j) const;      ///< a_j = g_j/(1 - sum g)
};

/// The base-foam families: "soft_plateau_50" (50 kg/m^3, long plateau, s_e(0.5) 2-3.5 kPa, sum g 0.35-0.6),
/// "stiff_65" (65 kg/m^3, s_e(0.5) 5-9 kPa, sum g 0.25-0.45), "random" (30-80 kg/m^3, 2-4 terms,
/// s_e(0.5) 1-10 kPa growing with density, sum g 0.2-0.6). Every family: all mu_i > 0, one plateau term
/// (alpha 6..20), one densification term (alpha -5..-1.5), s_e(0.75)/s_e(0.5) in 1.8..8; Prony times one
/// per decade 0.01..100 s, each shifted by up to +-0.25 decade (not the fit's preset times), weights
/// lognormal about a profile falling 0.15 decade per decade of tau.
BaseFoam draw_base_foam(const std::string& family, Random& random);

/// "soft_plateau_50", "stiff_65" or "random" with probability 1/3 each.
std::string draw_base_family(Random& random);

}  // namespace foreign_bench
