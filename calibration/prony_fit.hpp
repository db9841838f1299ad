#pragma once
/// Prony-series fit to dynamic moduli (paper section 3.4): generalized Maxwell model with preset
/// relaxation times T_r (default 0.01, 0.1, 1, 10, 100 s),
///   E'(w)  = E_inf + sum_r E_r w^2 T_r^2 / (1 + w^2 T_r^2),   E''(w) = sum_r E_r w T_r / (1 + w^2 T_r^2),
/// w = 2 pi f. Objective (the paper's normalised chi-square, eq. 16 as we read it: each modulus
/// divided by its measured value so E' and E'' weigh alike at every frequency):
///   chi2 = sum_i [ (E'(w_i)/Ebar'_i - 1)^2 + (E''(w_i)/Ebar''_i - 1)^2 ],
/// linear in x = (E_inf, E_1..E_n) with x >= 0. Solved by rank-revealing QR; if that solution has a
/// negative modulus, by the Lawson-Hanson active-set NNLS (exact; Eigen 3.4 has no NNLS module).
/// From 1-20 Hz data the 100 s term and E_inf are not separable (both are storage-only there): the free fit
/// may put everything into E_100 and return E_inf = 0 (then the paper's g_i sum to 1). Given `E_inf_fixed`
/// (e.g. the hyperfoam's long-term tangent at the preload, which the conversion to the solver's relative
/// moduli assumes anyway) only E_r >= 0 are fitted.
#include <Eigen/Dense>
#include <optional>
#include <vector>

namespace cushion::calibration {

/// Measured complex modulus at a set of frequencies (nominal stress / nominal strain).
struct DynamicModuli {
  std::vector<double> frequency;  ///< [Hz] > 0
  std::vector<double> storage;    ///< E' [MPa] > 0
  std::vector<double> loss;       ///< E'' [MPa] > 0
};

/// Storage and loss moduli [MPa] of a Prony series at frequencies [Hz].
DynamicModuli prony_moduli(double E_inf, const std::vector<double>& E, const std::vector<double>& tau,
                           const std::vector<double>& frequency);

/// Model vs data at one frequency.
struct PronyResidual {
  double frequency = 0.0;                           ///< [Hz]
  double storage = 0.0, storage_model = 0.0;        ///< E' [MPa]
  double loss = 0.0, loss_model = 0.0;              ///< E'' [MPa]
  double magnitude = 0.0, magnitude_model = 0.0;    ///< |E*| [MPa]
  double phase = 0.0, phase_model = 0.0;            ///< [deg] atan(E''/E')
};

struct PronyFit {
  double E_inf = 0.0;           ///< long-term modulus [MPa]
  std::vector<double> E;        ///< E_r [MPa], >= 0
  std::vector<double> tau;      ///< T_r [s]
  double chi2 = 0.0;            ///< objective at the solution [-]
  bool bounds_active = false;   ///< the unconstrained solution had a negative modulus (NNLS path)
  bool E_inf_fixed = false;     ///< E_inf was given, not fitted
  std::vector<PronyResidual> residuals;
};

/// min |A x - b| subject to x >= 0 (Lawson-Hanson active set, columns scaled to unit norm first).
Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

/// Fits (E_inf, E_r) for preset times tau [s]; throws std::invalid_argument on fewer than 3
/// frequencies, non-positive frequency or moduli, or tau empty/non-positive.
PronyFit fit_prony(const DynamicModuli& data, const std::vector<double>& tau = {0.01, 0.1, 1.0, 10.0, 100.0},
                   std::optional<double> E_inf_fixed = std::nullopt);

}  // namespace cushion::calibration
