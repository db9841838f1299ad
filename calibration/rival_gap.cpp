#include "calibration/rival_gap.hpp"

#include <cmath>
#include <stdexcept>

namespace cushion::calibration {

double NoiseUncertainty::of(const std::string& kind) const {
  return kind == "quasi_static" || kind == "indentation" ? quasi_static : dynamic;
}

double least_bic_gap(const std::vector<double>& chi2_winner, const std::vector<double>& chi2_other,
                     const std::vector<double>& uncertainty, double penalty_difference) {
  if (chi2_winner.size() != chi2_other.size() || chi2_winner.size() != uncertainty.size())
    throw std::invalid_argument("least_bic_gap: chi2 per test and uncertainty factors differ in length");
  double gap = penalty_difference;
  for (std::size_t t = 0; t < chi2_winner.size(); ++t) {
    const double u = uncertainty[t];
    if (!(std::isfinite(u) && u >= 1.0))
      throw std::invalid_argument("least_bic_gap: an uncertainty factor below 1 or not finite");
    const double d = chi2_other[t] - chi2_winner[t];
    gap += (d < 0.0 ? u * u : 1.0 / (u * u)) * d;  // each weight at the end of its range that favours the other
  }
  return gap;
}

}  // namespace cushion::calibration
