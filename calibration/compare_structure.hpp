#pragma once
/// `cushion compare --run RUN_DIR`: the structure-level tests of a campaign (compare_structure_data.hpp)
/// against the outputs of a `cushion run`, with the error figures and data-only noise estimates of the
/// material level (compare_metrics.hpp), reported as TestCompare entries (compare.hpp).
///
/// Indentation (kind "indentation"): the measured record is split at its largest indentation x_max:
/// loading = samples up to the first one within 1e-3 x_max of it, unloading = from the last one on
/// (samples in between, a hold, are not compared). The run's curve is split the same way and each branch
/// interpolated linearly (in indentation, monotone part only) at the measured samples of that branch;
/// measured samples outside the run's range of the branch are left out with a warning (the run does not
/// reach the measured indentation: another protocol or specimen). Regions (N): all, loading, unloading,
/// low/mid/high_indentation (thirds of x_max), hysteresis_area (N mm); NRMSE relative to the peak measured
/// force; noise: the reading-dependent noise of the measured force (compare_metrics.hpp reading_noise).
/// Dynamic stiffness (kind "dynamic_stiffness"): the run's |K*| and phase interpolated linearly in log f at
/// the measured frequencies (outside the run's range: left out with a warning). Regions: all_stiffness
/// (N/mm), all_phase (deg), band_low/mid/high_stiffness and _phase (thirds of the compared frequencies);
/// NRMSE: RMS / mean measured |K*|, RMS / 90 deg; noise: scatter about a polynomial in log f.
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/compare.hpp"

namespace cushion::calibration {

/// Data-only noise of a measured indentation record: force noise [N] (RMS and local per sample).
TestNoise indentation_noise(const IndentationCurve& record);

/// Data-only noise of a measured stiffness spectrum: |K*| [N/mm] (in TestNoise::modulus) and phase [deg].
TestNoise stiffness_noise(const StiffnessSpectrum& record);

/// One indentation test against a model curve (already read from the run). Problems of coverage are
/// appended to `warnings`; throws std::runtime_error when a branch has fewer than 2 comparable samples.
TestCompare compare_indentation(const IndentationTest& test, const IndentationCurve& model,
                                std::vector<std::string>& warnings);

/// One dynamic stiffness test against a model spectrum; throws std::runtime_error when no measured
/// frequency lies within the run's frequencies.
TestCompare compare_stiffness(const StiffnessTest& test, const StiffnessSpectrum& model,
                              std::vector<std::string>& warnings);

/// Every structure test of `campaign` against the first folder of `runs` that holds its model file
/// (model_file in compare_structure_data.hpp). A test whose model file is missing or unreadable, or that
/// cannot be compared, is reported with `failure` set; the others are still compared. Indentation tests
/// first, then dynamic stiffness, in campaign order.
std::vector<TestCompare> compare_structure(const Campaign& campaign, const std::vector<std::filesystem::path>& runs,
                                           std::vector<std::string>& warnings);

}  // namespace cushion::calibration
