#pragma once
/// Protocol details a campaign does not record, as nuisance parameters of `diagnose` (issue 15, part 2; why they
/// matter and how the values are chosen: docs/physics.md 9.3).
///
/// A dynamic test that leaves out a protocol key is modelled with the key's default (campaign.hpp): 20 cycles a
/// frequency with the last 10 fitted, a 30 mm/min preload ramp, no dwell before the sweep, the acceleration read as
/// peak-to-peak. A lab that ran otherwise leaves a residual that no material effect should be named for (with 5
/// cycles a frequency the 1-10 s Prony terms have not settled when the modulus is read; read as peak, the amplitude is
/// twice the modelled one). search_protocol treats such keys as discrete nuisance parameters over bounded sets of
/// plausible values, one value for every dynamic test that leaves the key out (one machine, one procedure): first the
/// joint grid of the coarse values (the keys interact: cycles, ramp and dwell all set how far the slow Prony terms
/// have relaxed when a modulus is read), on two threads, then each key over its finer values from the grid's best, the
/// others held, until none moves. The best values replace the defaults when they lower the material's chi2 on the
/// dynamic tests (sum of squared noise-normalised residuals, compare.hpp normalised_residuals) by more than
/// `min_gain`. Values (coarse grid in brackets):
///   cycles                 [5, 10, 20, 50] a frequency, the last half fitted (fit_cycles, when recorded, kept)
///   preload_rate_mm_min    [10, 30, 100], 15, 20, 50, 70 mm/min (30: the compare options' default rate)
///   dwell_before_sweep_s   [0, 10, 30, 100, 300], 3, 20, 60, 200 s
///   amplitude_convention   [peak_to_peak, peak]
/// The values found are those that explain the data best, not necessarily what the lab ran: cycles, ramp and dwell
/// trade against one another. Measured on 6 foreign controls with their exact base (test_protocol_search.cpp):
/// amplitude convention right on 6 of 6, worst dynamic error/noise 1.5-4.8x -> 0.54-0.73x on 5, 2.14 -> 1.78x on the
/// one run with 5 cycles and 2 fitted; 129-150 runs, 1.0-1.3 s on two loaded cores.
/// Not searched: preflex cycles and lift-off (quasi-static and dynamic); a campaign that omits them is modelled with
/// the defaults (no preflex; platen that only pushes in quasi-static tests, bonded in dynamic ones).
#include <limits>
#include <string>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "material/material.hpp"

namespace cushion::calibration {

/// One value of a key and the material's chi2 with it (the other keys at their chosen values).
struct ProtocolValue {
  std::string label;  ///< e.g. "20 (last 10 fitted)", "30 mm/min", "300 s", "peak"
  double chi2 = std::numeric_limits<double>::quiet_NaN();  ///< NaN: a dynamic run failed with it
};

struct ProtocolKeySearch {
  std::string key;                 ///< campaign key
  std::vector<std::string> tests;  ///< the dynamic tests that leave it out
  std::string assumed;             ///< label of the default a forward model assumes
  std::string chosen;              ///< label of the value kept
  std::vector<ProtocolValue> tried;
  /// Largest minus smallest finite chi2 over the values tried: how much the assumption matters [-].
  double chi2_range() const;
};

struct ProtocolSearch {
  Campaign campaign;                    ///< the campaign with the chosen values
  std::vector<ProtocolKeySearch> keys;  ///< every unrecorded key searched; empty: the campaign records them all
  double chi2_assumed = 0.0;  ///< chi2 of the dynamic tests with the defaults [-]
  double chi2_chosen = 0.0;   ///< and with the chosen values [-]
  bool moved = false;         ///< `campaign` models some dynamic test otherwise than the campaign searched did
  int runs = 0;               ///< campaign comparisons run
  double seconds = 0.0;
  /// Some key's chosen value is not its default.
  bool changed() const;
};

/// Searches the unrecorded dynamic protocol keys of `campaign` for `model` (see above). `noise`: estimate_noise of
/// the campaign (quasi-static first, then dynamic). Deterministic.
ProtocolSearch search_protocol(const material::Material& model, const Campaign& campaign,
                               const std::vector<TestNoise>& noise, const CompareOptions& options, double min_gain);

}  // namespace cushion::calibration
