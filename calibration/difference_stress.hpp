#pragma once
/// Difference-stress method (paper eqs. 8-11): loading and unloading samples at equal strain share
/// the same elastic stress, so their stress difference is purely viscous:
///   delta_sigma(t1) = sigma(t1) - sigma(t2) = sigma_v(t1) - sigma_v(t2),   eps(t2) = eps(t1),
/// with t1 on the loading branch and t2 on the unloading branch. t2 is found from the actual strain
/// histories (interpolated), so it works with a hold (t1 + t2 != T) and with a truncated unloading
/// branch (only loading strains that the unloading branch reaches are paired).
#include <vector>

#include "calibration/hereditary.hpp"
#include "calibration/segments.hpp"

namespace cushion::calibration {

/// Loading/unloading pairs at equal strain.
struct StrainPairs {
  std::vector<double> t1;      ///< [s] loading times
  std::vector<double> t2;      ///< [s] unloading times with eps(t2) = eps(t1)
  std::vector<double> strain;  ///< [-] eps(t1), compression positive
};

/// Pairs loading times t1 = t_load_begin + i dt (i = 1, 2, ..., t1 <= t_load_end) with unloading
/// times. dt [s] > 0: 1 s in the paper. Loading strains outside the unloading branch's range are skipped.
StrainPairs pair_loading_unloading(const StressStrainRecord& record, const Segments& segments, double dt = 1.0);

/// Measured difference stress [MPa] at the pairs: sigma(t1) - sigma(t2) (time-interpolated).
std::vector<double> measured_difference_stress(const StressStrainRecord& record, const StrainPairs& pairs);

/// Model difference stress [MPa] sigma_v(t1) - sigma_v(t2) for the record's strain history.
std::vector<double> model_difference_stress(const StressStrainRecord& record, const StrainPairs& pairs,
                                            const std::vector<HereditaryMode>& modes);

/// RMSE of eq. 11 [MPa]: sqrt(mean (model - measured)^2).
double rmse(const std::vector<double>& model, const std::vector<double>& measured);

/// A strain-controlled triangle history with hold: 0 -> peak_strain at `rate` [1/s], hold [s], back
/// to 0 at the same rate; sampled every dt [s] (segment corners are always samples).
struct ProtocolHistory {
  std::vector<double> time;    ///< [s]
  std::vector<double> strain;  ///< [-], compression positive
};
ProtocolHistory triangle_history(double peak_strain, double rate, double hold, double dt);

/// What a parameter set gives for a protocol: sigma_v along the history and the difference stress at
/// 1 s loading intervals.
struct ProtocolCurve {
  ProtocolHistory history;
  std::vector<double> sigma_v;       ///< [MPa] at history.time, compression positive
  StrainPairs pairs;                 ///< 1 s pairs
  std::vector<double> delta_sigma;   ///< [MPa] sigma_v(t1) - sigma_v(t2)
};
/// Defaults are the paper's protocol: 80 mm block, 120 mm/min to 75 % (30 s), 2 s hold, unloading at
/// the same rate, evaluated with the Table 2 parameters (paper_table2_modes()).
ProtocolCurve protocol_curve(const std::vector<HereditaryMode>& modes, double thickness = 80.0,
                             double speed_mm_per_min = 120.0, double peak_strain = 0.75, double hold = 2.0,
                             double dt = 0.05);

}  // namespace cushion::calibration
