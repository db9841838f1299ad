#pragma once
/// Method step 7: from the absolute Prony moduli measured about the preload (E_inf, E_i [MPa], paper
/// Table 3 form) to the relative moduli g_i the solver uses on top of the LONG-TERM hyperfoam.
///
/// (a) paper:   g_i = E_i / (E_inf + sum E_j)            => a_i = g_i/(1 - sum g) = E_i / E_inf
/// (b) tangent: a_i = E_i / K_v,  g_i = a_i / (1 + sum a) (K_v = l^2 C_c of fit_model.hpp)
/// The solver's dynamic modulus at the preload is E*(w) = K_hf + K_v sum a_i iw tau_i / (1 + iw tau_i)
/// (fit_model.hpp), so (b) reproduces the measured viscous part sum E_i iw tau_i/(1 + iw tau_i) exactly,
/// while (a) scales it by K_v / E_inf; the storage offset at w -> 0 is K_hf for both (the hyperfoam's),
/// against the measured E_inf. The quasi-static response scales the same way (a_i multiply the base's
/// stress increments), so (a) and (b) differ in the predicted hysteresis by the same factor.
#include <string>
#include <vector>

#include "calibration/fit_model.hpp"

namespace cushion::calibration {

enum class PronyNormalisation { paper, tangent };
std::string to_string(PronyNormalisation n);

struct PronyConversion {
  double E_inf = 0.0, E_0 = 0.0;      ///< measured long-term and instantaneous moduli [MPa] (E_0 = E_inf + sum E_i)
  PreloadTangent preload;             ///< hyperfoam at the preload: K_hf, K_v, S11 [MPa]
  std::vector<double> E, tau;         ///< absolute moduli [MPa], times [s]
  std::vector<material::PronyTerm> paper, tangent;  ///< relative g_i for (a) and (b)
  std::vector<double> a_paper, a_tangent;           ///< moduli relative to the long-term modulus
};

/// Both normalisations for the hyperfoam `terms` (long-term) at the dynamic test's preload [-].
PronyConversion convert_prony(double E_inf, const std::vector<double>& E, const std::vector<double>& tau,
                              const std::vector<material::HyperfoamTerm>& terms, double preload,
                              Lateral lateral = Lateral::free);

const std::vector<material::PronyTerm>& relative_moduli(const PronyConversion& c, PronyNormalisation n);

}  // namespace cushion::calibration
