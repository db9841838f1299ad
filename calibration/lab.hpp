#pragma once
/// The virtual lab: runs the material-point model through the paper's test protocols in the time
/// domain, "measures" like a test machine (sine fits for the dynamic test, a platen that only pushes),
/// adds seeded noise, and writes a campaign (manifest JSON + CSV) in the calibration format.
///
/// Truth file (JSON; every key documented in the README "Virtual lab"):
/// {
///   "description": "...",                                   (optional)
///   "material": "../materials/paper_table3.json",           (material file, relative to the truth file)
///   "specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
///   "noise": {"seed": 1, "force_relative": 0.005, "force_floor_N": 0.02},   (optional; default none)
///   "quasi_static": [{"name": "qs_120", "rate_mm_min": 120, "max_strain": 0.75, "hold_s": 2,
///                     "sample_hz": 10, "preload_cycle": true, "rest_s": 300, "lateral": "free",
///                     "use": "calibration"}],
///   "dynamic": [{"name": "dyn_25", "preload_strain": 0.25, "preload_rate_mm_min": 30,
///                "acceleration_amplitude_m_s2": 0.25, "amplitude_is": "peak_to_peak",
///                "frequencies_Hz": [1, 2, ..., 20], "cycles": 20, "fit_cycles": 10,
///                "steps_per_cycle": 64, "use": "calibration"}]
/// }
/// Both kinds also take the campaign's protocol keys (protocol.hpp: preflex_cycles, preflex_strain,
/// rest_between_tests_s, lift_off; dynamic: dwell_before_sweep_s, amplitude_convention); quasi-static
/// "preload_cycle" (older, default true) is one preflex cycle to max_strain, "rest_s" the rest after it.
/// The campaign written records every protocol key the lab simulated, so that compare and diagnose model
/// the tests as they were run.
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/protocol.hpp"
#include "io/output_folder.hpp"
#include "material/io/material_file.hpp"
#include "material/point_driver.hpp"

namespace cushion::calibration {

struct LabSpecimen {
  double length = 80.0, width = 80.0, thickness = 80.0;  ///< [mm]
  double density_kg_m3 = 65.0;                           ///< as written to the manifest
  double area() const { return length * width; }       ///< loaded area [mm^2]
};

struct LabNoise {
  unsigned long long seed = 1;
  /// Standard deviation as a fraction [-] of the force reading (quasi-static), or of the amplitude of the
  /// oscillating force (dynamic: a load cell's error on the dynamic reading, not on the static preload).
  double force_relative = 0.0;
  double force_floor = 0.0;     ///< additional absolute standard deviation [N]
};

/// Quasi-static load/unload protocol (ISO 2439 method E style, paper section 2.2).
struct QuasiStaticProtocol {
  std::string name = "quasistatic";
  double rate_mm_min = 120.0;  ///< crosshead speed, loading and unloading
  double max_strain = 0.75;    ///< nominal compression at the turn [-]
  double hold_s = 2.0;         ///< hold at the maximum [s]
  double sample_hz = 10.0;     ///< recorded samples per second
  PriorLoading prior;          ///< preflex cycles at the test's rate, then rest (default: none)
  bool lift_off = true;        ///< a platen that only pushes (force clipped at zero), else bonded platens
  material::LoadMode lateral = material::LoadMode::uniaxial_free;
  std::string use;             ///< "calibration", "validation" or empty (manifest default)
};

/// Dynamic test protocol (paper section 2.3): preflex and rest (if any), preload ramp, dwell, then sines at
/// each frequency in one continuous history.
struct DynamicProtocol {
  std::string name = "dynamic";
  double preload_strain = 0.25;        ///< nominal compression [-]
  double preload_rate_mm_min = 30.0;   ///< crosshead speed of the preload ramp and of any preflex
  double dwell_s = 0.0;                ///< hold at the preload before the first frequency [s]
  PriorLoading prior;                  ///< preflex cycles and rest before the preload (default: none)
  bool lift_off = false;               ///< a platen that only pushes (force clipped at zero), else bonded
  double acceleration_amplitude = 0.25;  ///< [m/s^2]
  bool amplitude_peak_to_peak = true;    ///< the paper writes "peak-to-peak value of 0.25 m/s^2"
  std::vector<double> frequencies_Hz;
  int cycles = 20;           ///< cycles run at each frequency
  int fit_cycles = 10;       ///< last cycles used by the sine fit
  int steps_per_cycle = 64;  ///< time steps a cycle of the fitted cycles (of all if transient_steps_per_cycle is 0)
  /// Time steps a cycle of the cycles before the fitted ones, which only set the state the fitted cycles start from
  /// (0: steps_per_cycle). compare and diagnose run them coarser (CompareOptions); the lab keeps every cycle fine.
  int transient_steps_per_cycle = 0;
  std::string use;
  /// Displacement amplitude [mm] at frequency f: U = a_peak / (2 pi f)^2.
  double displacement_amplitude_mm(double f_Hz) const;
};

struct LabTruth {
  std::filesystem::path file;  ///< the truth file read (empty if built in code)
  std::string description;
  std::filesystem::path material_file;
  LabSpecimen specimen;
  LabNoise noise;
  std::vector<QuasiStaticProtocol> quasi_static;
  std::vector<DynamicProtocol> dynamic;
};

/// Reads and validates a truth file (InputError naming the file and key).
LabTruth read_lab_truth(const std::filesystem::path& file);

/// A recorded quasi-static test: compression-positive displacement and force, as a machine writes them.
struct QuasiStaticRecord {
  std::vector<double> time_s, displacement_mm, force_N;
};
/// A measured dynamic test: complex modulus per frequency (nominal stress over nominal strain).
struct DynamicRecord {
  std::vector<double> frequency_Hz, dynamic_modulus_kPa, phase_deg;
};

/// Runs one quasi-static protocol on the material (no noise).
QuasiStaticRecord run_quasi_static(const material::Material& model, const LabSpecimen& specimen,
                                   const QuasiStaticProtocol& protocol);
/// Runs one dynamic protocol: THE forward model of a dynamic test (the lab, compare and diagnose all call
/// it); noise (if any) is added to the force samples before the sine fit. The sines take
/// protocol.steps_per_cycle time steps a cycle (the cycles before the last fit_cycles:
/// protocol.transient_steps_per_cycle when non-zero); |E*| and phase from sine + cosine + offset + drift fits to
/// stress and strain over the last fit_cycles cycles of each frequency.
DynamicRecord run_dynamic(const material::Material& model, const LabSpecimen& specimen,
                          const DynamicProtocol& protocol, const LabNoise& noise, unsigned long long stream);

/// Adds seeded Gaussian noise to a quasi-static record's force (portable Box-Muller on mt19937_64).
void add_force_noise(QuasiStaticRecord& record, const LabNoise& noise, unsigned long long stream);

/// The output-folder policy of `cushion lab` (io/output_folder.hpp): an earlier output holds campaign.json,
/// the truth file and its material file are inputs, the outputs are staged in DIR.partial.
io::OutputFolder lab_output_folder(const std::filesystem::path& dir, bool overwrite, const LabTruth& truth);

/// Runs every protocol of the truth and writes DIR/campaign.json plus one CSV per test; prints one
/// line per test to `log`. Outputs are written to a temporary folder and renamed at the end, so a
/// failure leaves no partial campaign. Replaces an earlier campaign in DIR; refuses any other non-empty
/// DIR (InputError, lab_output_folder with overwrite).
void run_lab(const LabTruth& truth, const std::filesystem::path& out_dir, std::ostream& log);

}  // namespace cushion::calibration
