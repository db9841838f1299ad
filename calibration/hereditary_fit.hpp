#pragma once
/// Identification of the hereditary-integral parameters (paper section 3.3): fit the model difference
/// stress sigma_v(t1) - sigma_v(t2) to the measured one by bounded nonlinear least squares (Ceres trust
/// region, analytic derivatives) from several deterministic starts. For fixed decay rates beta the
/// model is linear in the residues alpha, so every start is first solved over the decay rates only
/// (variable projection), and the best `refined_starts` of those are refined in all 4M parameters.
#include <string>
#include <vector>

#include "calibration/difference_stress.hpp"

namespace cushion::calibration {

struct HereditaryFitOptions {
  int modes = 2;                        ///< number of residue/mode pairs (paper: 2)
  std::vector<double> start_decay_rates;///< Re beta of the start grid [1/s]; empty: {0.01,0.1,1,10}/T, T = test duration
  double start_imag_ratio = 0.2;        ///< Im beta = ratio * Re beta at the grid starts
  bool paper_start = true;              ///< also start from Table 2 (2 modes only)
  double beta_max_factor = 100.0;       ///< bounds 0 <= Re beta, Im beta <= factor / T
  double alpha_max_factor = 1e4;        ///< bounds |Re alpha|, |Im alpha| <= factor * peak stress
  double function_tolerance = 1e-12, gradient_tolerance = 1e-12, parameter_tolerance = 1e-10;
  int max_projected_iterations = 500;   ///< stage 1 (decay rates only) per start
  int refined_starts = 2;               ///< stage 2 (all parameters) from the best stage-1 results
  int max_iterations = 500;             ///< stage 2 per refined start
};

struct HereditaryFit {
  std::vector<HereditaryMode> modes;  ///< canonical form (Im beta >= 0, sorted by Re beta); alpha [MPa], beta [1/s]
  double rmse = 0.0;                  ///< eq. 11 [MPa]
  double rmse_relative = 0.0;         ///< rmse / peak stress of the record [-]
  std::vector<double> model;          ///< model difference stress at the pairs [MPa]
  std::vector<double> measured;       ///< measured difference stress at the pairs [MPa]
  int starts = 0;                     ///< number of starts tried
  std::string report;                 ///< Ceres brief report of the best start
};

/// Fits the hereditary parameters to the difference stress of `record` at `pairs`.
/// Throws std::invalid_argument if there are fewer pairs than 4*modes parameters.
HereditaryFit fit_hereditary(const StressStrainRecord& record, const Segments& segments, const StrainPairs& pairs,
                             const HereditaryFitOptions& options = {});

/// Variable projection step: the least-squares residues alpha for fixed decay rates betas [1/s]
/// (returns modes with those betas and the optimal alphas).
std::vector<HereditaryMode> best_residues(const StressStrainRecord& record, const StrainPairs& pairs,
                                          const std::vector<double>& measured, const std::vector<cplx>& betas);

}  // namespace cushion::calibration
