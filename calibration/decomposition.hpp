#pragma once
/// Decomposition of a quasi-static record into viscous and elastic stress (paper eq. 7):
///   sigma_e = sigma - sigma_v, with sigma_v the hereditary-integral stress of the fitted modes.
/// If the model is right, sigma_e is the same on loading and unloading at equal strain; the RMS of
/// sigma_e(t1) - sigma_e(t2) over the paired strain range, relative to the peak stress, measures that.
#include <vector>

#include "calibration/difference_stress.hpp"

namespace cushion::calibration {

/// Elastic (rate-independent) curve for the hyperfoam fit: nominal, compression positive.
struct ElasticCurve {
  std::vector<double> strain;  ///< [-] increasing, starts at 0
  std::vector<double> stress;  ///< [MPa]
};

struct Decomposition {
  std::vector<double> time, strain, sigma, sigma_v, sigma_e;  ///< samples load_begin..unload_end; [s], [-], [MPa]
  std::vector<bool> loading;           ///< true on the loading branch (up to load_end)
  double branch_mismatch = 0.0;        ///< RMS(sigma_e(t1) - sigma_e(t2)) / peak stress over the pairs [-]
  double paired_strain_min = 0.0, paired_strain_max = 0.0;  ///< strain range of that comparison [-]
  ElasticCurve elastic;                ///< branch-averaged sigma_e(strain), loading branch where unpaired
};

/// sigma_v, sigma_e on both branches; the comparison uses `pairs_per_branch` equally spaced loading
/// times; the elastic curve is resampled at `curve_points` strains from 0 to the peak.
Decomposition decompose(const StressStrainRecord& record, const Segments& segments,
                        const std::vector<HereditaryMode>& modes, int pairs_per_branch = 200,
                        int curve_points = 60);

}  // namespace cushion::calibration
