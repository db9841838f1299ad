#pragma once
/// Test campaigns: a JSON manifest naming the specimen and the test files (CSV with units in the
/// column names), read into internal units. Format (README "Campaign format"):
/// {"description": "...",                                                   (optional)
///  "specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
///  "tests": [ {"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120},
///             {"kind": "dynamic", "file": "dyn_25.csv", "preload_strain": 0.25,
///              "acceleration_amplitude_m_s2": 0.25} ]}
/// Optional per test: "name", "use": "calibration" | "validation" (default: the first test of each kind
/// calibrates, the rest validate; several quasi-static tests may be marked "calibration": the first one
/// listed carries the paper's method (steps 1-5), all of them the consistency refit; one dynamic
/// calibration test at most), "lateral": "free" | "constrained" (quasi-static only, default free).
/// File paths are relative to the manifest. Quasi-static CSV: time_s,displacement_mm,force_N
/// (compression positive). Dynamic CSV: frequency_Hz plus one of {dynamic_modulus_kPa, phase_deg},
/// {storage_modulus_kPa, loss_modulus_kPa}, {dynamic_stiffness_N_per_mm, phase_deg}
/// (E = k thickness / area).
/// Protocol keys (how the test was run; each optional, with the default a forward model assumes; README
/// "Protocol keys"): every material test: "preflex_cycles" (0: none; whole number in [0, 100]),
/// "preflex_strain" (nominal compression of the preflex, in (0, 0.95); default 0.75; only with
/// preflex_cycles > 0), "rest_between_tests_s" (unloaded rest after the preflex, >= 0, default 300),
/// "lift_off" (true: a platen that only pushes, the force is clipped at zero and the foam may lose contact;
/// false: specimen bonded to the platens; default true quasi-static, false dynamic). Dynamic tests:
/// "preload_rate_mm_min" (> 0; default: the reader's, 30 mm/min in compare), "dwell_before_sweep_s" (hold at
/// the preload before the first frequency, >= 0, default 0), "amplitude_convention": "peak_to_peak" (default,
/// the paper's words) | "peak" (how acceleration_amplitude_m_s2 is read; older name "amplitude_is"),
/// "cycles" (per frequency, whole number in [1, 100000], default 20), "fit_cycles" (last cycles the modulus and
/// phase are fitted on, in [1, cycles], default 10).
/// Structure-level tests ("kind": "indentation" | "dynamic_stiffness", never used for calibration):
/// compare_structure_data.hpp. Every problem is an InputError naming the file and line/column or key.
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/compare_structure_data.hpp"
#include "calibration/hyperfoam_fit.hpp"
#include "calibration/prony_fit.hpp"
#include "calibration/protocol.hpp"
#include "calibration/segments.hpp"

namespace cushion::calibration {

enum class TestUse { calibration, validation };

struct QuasiStaticTest {
  std::string name;                  ///< "name" or the file stem
  std::filesystem::path file;        ///< resolved path
  TestUse use = TestUse::validation;
  Lateral lateral = Lateral::free;
  double rate = 0.0;                 ///< crosshead speed [mm/s] (file: rate_mm_min)
  PriorLoading prior;                ///< preflex and rest before the test
  bool lift_off = true;              ///< platen that only pushes (file: lift_off)
  std::vector<std::string> unrecorded;  ///< protocol keys the manifest leaves out (their defaults are assumed)
  StressStrainRecord record;         ///< nominal, compression positive, MPa
};

struct DynamicTest {
  std::string name;
  std::filesystem::path file;
  TestUse use = TestUse::validation;
  double preload_strain = 0.0;          ///< nominal preload [-] in [0, 1)
  double acceleration_amplitude = 0.0;  ///< excitation amplitude [mm/s^2] (file: m/s^2)
  bool amplitude_peak_to_peak = true;   ///< acceleration_amplitude is peak-to-peak (file: amplitude_convention)
  double preload_rate_mm_min = 0.0;     ///< preload ramp speed [mm/min]; 0: not given (reader's default)
  double dwell_s = 0.0;                 ///< hold at the preload before the sweep [s] (file: dwell_before_sweep_s)
  int cycles = 20;                      ///< sine cycles run per frequency (file: cycles)
  int fit_cycles = 10;                  ///< last cycles fitted for |E*| and phase (file: fit_cycles)
  PriorLoading prior;                   ///< preflex and rest before the preload
  bool lift_off = false;                ///< platen that only pushes (file: lift_off)
  std::vector<std::string> unrecorded;  ///< protocol keys the manifest leaves out (their defaults are assumed)
  DynamicModuli moduli;                 ///< E', E'' [MPa] vs frequency [Hz], increasing
};

struct Campaign {
  std::filesystem::path manifest;
  std::string description;
  Specimen specimen;
  std::vector<QuasiStaticTest> quasi_static;
  std::vector<DynamicTest> dynamic;
  std::vector<IndentationTest> indentation;  ///< structure level: force vs indentation
  std::vector<StiffnessTest> stiffness;      ///< structure level: dynamic stiffness vs frequency
  /// The (first) calibration test of each kind (nullptr when the campaign has none of that kind).
  const QuasiStaticTest* quasi_static_calibration() const;
  /// Every quasi-static test marked for calibration, in manifest order (the first is quasi_static_calibration()).
  std::vector<const QuasiStaticTest*> quasi_static_calibration_tests() const;
  const DynamicTest* dynamic_calibration() const;
};

/// Reads and validates the manifest and every test file it names.
Campaign read_campaign(const std::filesystem::path& manifest);

/// File line (1-based) of each data row of a CSV, with the CSV reader's rule: blank lines and '#' lines are
/// skipped, the first remaining line is the header.
std::vector<int> data_row_lines(const std::filesystem::path& file);

/// "source:LINE, column COLUMN: " for data row `row` (0-based) of a CSV whose rows are on `lines`.
std::string at_line(const std::string& source, const std::vector<int>& lines, std::size_t row, const std::string& column);

/// Reads one quasi-static CSV (time_s, displacement_mm, force_N) for a specimen.
StressStrainRecord read_quasi_static_csv(const std::filesystem::path& file, const Specimen& specimen);

/// Reads one dynamic CSV (any accepted column set) for a specimen: E', E'' in MPa.
DynamicModuli read_dynamic_csv(const std::filesystem::path& file, const Specimen& specimen);

}  // namespace cushion::calibration
