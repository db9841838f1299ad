#pragma once
/// Structure-level measurements of a campaign (SIT-BAR or punch indentation, dynamic stiffness of a
/// seat or block) and the matching outputs of a `cushion run`, read into N, mm, Hz and degrees.
///
/// Campaign manifest entries (in "tests", next to the material-level ones; paths relative to the manifest):
///   {"kind": "indentation", "file": "sitbar_force.csv", "contact": "sitbar"}        model: RUN/contact_sitbar.csv
///   {"kind": "indentation", "file": "punch.csv", "history_set": "top"}              model: RUN/history.csv
///   {"kind": "dynamic_stiffness", "file": "stiffness.csv", "sweep_step": "sweep"}   model: RUN/sweep_sweep.csv
/// optional: "name" (default: the file stem), "axis": "x"|"y"|"z" (travel axis, default "z"),
/// "model_force_factor" (> 0, default 1: multiplies the run's forces and stiffnesses, e.g. 4 for a quarter
/// model without a contact force_factor), "description".
/// Measured indentation CSV: indentation_mm, force_N (optional time_s), rows in time order: loading to the
/// largest indentation, optional hold, unloading; indentation = travel of the indenter into the structure
/// from first touch, force = force of the indenter on the structure, both positive in compression.
/// Measured dynamic stiffness CSV: frequency_Hz (strictly increasing, > 0) with {dynamic_stiffness_N_per_mm,
/// phase_deg} or {storage_stiffness_N_per_mm, loss_stiffness_N_per_mm}; a sweep CSV of `cushion run`
/// is accepted as it is.
/// Model side: indentation = s U_axis, force = s F_axis (contact: columns <name>.U?_mm, <name>.F?_N; history:
/// <set>.U?_mm, <set>.RF?_N), with s = +-1 making the largest travel positive, so that the run's indenter
/// starts touching the structure; the sweep CSV's dynamic_stiffness_N_per_mm and phase_deg.
/// Every problem is an InputError naming the file and line/column or key.
#include <filesystem>
#include <string>
#include <vector>

namespace cushion::calibration {

/// A force-indentation record [mm, N], in time order.
struct IndentationCurve {
  std::vector<double> indentation;  ///< [mm], compression positive
  std::vector<double> force;        ///< [N], compression positive
};

/// Dynamic stiffness vs frequency.
struct StiffnessSpectrum {
  std::vector<double> frequency;  ///< [Hz], strictly increasing
  std::vector<double> amplitude;  ///< |K*| [N/mm]
  std::vector<double> phase;      ///< arg K* [deg]
};

struct IndentationTest {
  std::string name;
  std::filesystem::path file;
  std::string contact;      ///< model source: contact_<contact>.csv (empty: history_set)
  std::string history_set;  ///< model source: history.csv columns <set>.U?_mm, <set>.RF?_N
  int axis = 2;             ///< travel axis 0, 1, 2 (x, y, z)
  double model_force_factor = 1.0;
  IndentationCurve record;
};

struct StiffnessTest {
  std::string name;
  std::filesystem::path file;
  std::string sweep_step;   ///< model source: <sweep_step>_sweep.csv
  double model_force_factor = 1.0;
  StiffnessSpectrum record;
};

/// Reads a measured indentation CSV (indentation_mm, force_N); at least 8 rows.
IndentationCurve read_indentation_csv(const std::filesystem::path& file);

/// Reads a measured dynamic stiffness CSV (either accepted column set); at least 3 frequencies.
StiffnessSpectrum read_stiffness_csv(const std::filesystem::path& file);

/// The model curve of `test` from the run folder `run`: s U_axis, s F_axis x model_force_factor. InputError
/// when the file or its columns are missing.
IndentationCurve read_model_indentation(const std::filesystem::path& run, const IndentationTest& test);

/// The model spectrum of `test` from the run folder `run`: |K*| x model_force_factor and phase.
StiffnessSpectrum read_model_stiffness(const std::filesystem::path& run, const StiffnessTest& test);

/// The file of `run` that holds the model side of the test.
std::filesystem::path model_file(const std::filesystem::path& run, const IndentationTest& test);
std::filesystem::path model_file(const std::filesystem::path& run, const StiffnessTest& test);

}  // namespace cushion::calibration
