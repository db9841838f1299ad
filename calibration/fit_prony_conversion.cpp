#include "calibration/fit_prony_conversion.hpp"

#include <stdexcept>

#include "material/hyperfoam.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::calibration {

std::string to_string(PronyNormalisation n) { return n == PronyNormalisation::paper ? "paper" : "tangent"; }

PronyConversion convert_prony(double E_inf, const std::vector<double>& E, const std::vector<double>& tau,
                              const std::vector<material::HyperfoamTerm>& terms, double preload, Lateral lateral) {
  PronyConversion c;
  c.E_inf = E_inf;
  c.E = E;
  c.tau = tau;
  c.E_0 = E_inf;
  for (double e : E) c.E_0 += e;
  const material::Hyperfoam base(terms);
  c.preload = preload_tangent(base, preload, lateral);
  if (!(c.preload.K_v > 0.0))
    throw std::runtime_error("Prony conversion: the hyperfoam has no positive tangent at the preload");
  c.paper = material::prony_from_absolute(E_inf, E, tau);
  c.a_paper = long_term_ratios(c.paper);
  for (double e : E) c.a_tangent.push_back(e / c.preload.K_v);
  c.tangent = prony_from_long_term_ratios(c.a_tangent, tau);
  return c;
}

const std::vector<material::PronyTerm>& relative_moduli(const PronyConversion& c, PronyNormalisation n) {
  return n == PronyNormalisation::paper ? c.paper : c.tangent;
}

}  // namespace cushion::calibration
