#pragma once
/// Hyperfoam-only campaigns: homogeneous tests in the ABAQUS test modes, each a CSV whose columns the
/// manifest names (units explicit). A campaign is of this kind when its root has "hyperfoam_tests"
/// (README "cushion fit", hyperfoam-only campaigns):
/// {"description": "...",                                                            (optional)
///  "density_kg_m3": 30,                                                             (optional, > 0)
///  "hyperfoam_tests": [
///    {"name": "uniaxial",                                                           (optional; file stem)
///     "mode": "uniaxial" | "equibiaxial" | "planar" | "simple_shear" | "volumetric",
///     "file": "uniaxial_compression.csv",
///     "stretch_column": "stretch",              loaded-direction stretch [-] (> 0); simple_shear instead:
///     "shear_strain_column": "gamma",           shear strain gamma = F12 [-]
///     "stress_column": "nominal_stress_MPa",    nominal stress in the loaded direction (simple shear: P12),
///                                               TENSION POSITIVE; the name ends in _MPa, _kPa or _Pa (its unit)
///     "lateral_stretch_column": "transverse_stretch"}  (optional; uniaxial, equibiaxial, planar: stretch [-]
///                                               of the stress-free direction)
///  ],
///  "hyperfoam_fit": {"terms": 3,                  (optional block; N = 1..6, default 3)
///                    "poisson": "per_term" | "common",   (default per_term: nu_i each fitted)
///                    "lateral_weight": 1.0,       (>= 0; weight of the lateral-stretch residuals)
///                    "stable_stretch": [0.2, 1.5]}  (Drucker-stable stretch range required in all four modes;
///                                               default: per mode, hyperfoam_modes_fit.hpp default_stable_stretch)
/// }
/// Every problem is an InputError naming the file and key or line/column; nothing is fitted before the
/// whole campaign has been read.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibration/hyperfoam_modes.hpp"

namespace cushion::calibration {

struct HyperfoamTest {
  std::string name;
  HyperfoamMode mode = HyperfoamMode::uniaxial;
  std::filesystem::path file;
  std::string control_column, stress_column, lateral_column;  ///< lateral_column empty: not given
  std::vector<double> control;  ///< stretch [-] (simple shear: gamma [-])
  std::vector<double> stress;   ///< nominal stress [MPa], tension positive
  std::vector<double> lateral;  ///< free-direction stretch [-]; empty when not given
};

struct HyperfoamFitSettings {
  int terms = 3;                ///< N, 1..6
  bool per_term_nu = true;      ///< false: one common nu
  double lateral_weight = 1.0;  ///< weight of the lateral residuals (relative to the stress ones)
  std::optional<std::pair<double, double>> stable_stretch;  ///< [min, max] stretch, every mode; empty: per mode from the data
  double alpha_min = 0.2, alpha_max = 50.0;  ///< alpha_min <= |alpha_i| <= alpha_max
  double nu_max = 0.45;         ///< 0 <= nu_i <= nu_max
  int polished = 8;             ///< best grid starts polished, of each kind (mu >= 0; free mu)
};

struct HyperfoamCampaign {
  std::filesystem::path manifest;
  std::string description;
  double density = 0.0;  ///< [t/mm^3]; 0: not given
  std::vector<HyperfoamTest> tests;
  HyperfoamFitSettings settings;
};

/// true when the manifest's root object has the key "hyperfoam_tests" (InputError on unreadable JSON).
bool is_hyperfoam_campaign(const std::filesystem::path& manifest);

/// Reads and validates the manifest and every CSV it names.
HyperfoamCampaign read_hyperfoam_campaign(const std::filesystem::path& manifest);

}  // namespace cushion::calibration
