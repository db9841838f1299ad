#pragma once
/// Frequency sweep results in the paper's terms (Fig. 12): excitation amplitude from an acceleration
/// amplitude, dynamic stiffness and nominal dynamic modulus, CSV and VTK (.pvd over frequency) output.
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/case/steady_state_spec.hpp"
#include "solver/dynamics/steady_state.hpp"
#include "solver/output/vtu_writer.hpp"

namespace cushion::solver::dynamics {

/// Peak displacement amplitude U = a_peak / (2 pi f)^2 [mm] for an acceleration amplitude a [mm/s^2]
/// read as `reading` (AccelerationReading, solver/case/steady_state_spec.hpp) at frequency f [Hz] (> 0).
/// Phase reference: displacement (U real, positive).
double displacement_amplitude(double acceleration, AccelerationReading reading, double frequency);

/// Nominal geometry of the dynamic modulus E = (F / area) / (U / thickness).
struct NominalGeometry {
  double area = 0.0;       ///< loaded area [mm^2] (indenter footprint, or the specimen's top face)
  double thickness = 0.0;  ///< undeformed specimen thickness [mm]
};

/// One sweep line. Reactions are forces the supports apply to the model [N].
struct SweepRow {
  double frequency = 0.0;                ///< [Hz]
  std::complex<double> amplitude;        ///< driven displacement [mm]
  std::complex<double> indenter_force;   ///< summed reaction on the indenter group [N] (0 if free)
  std::complex<double> base_force;       ///< summed reaction on the base group [N] (0 if free)
  std::complex<double> indenter_motion;  ///< mean indenter displacement [mm]
  std::complex<double> stiffness;        ///< dynamic stiffness [N/mm] (see make_row)
  std::complex<double> modulus;          ///< nominal dynamic modulus [MPa]
};

/// Builds a row from a response whose groups are {indenter, base}. Dynamic stiffness: the force on
/// the MEASURING group per driven amplitude, signed so that a static compression is positive:
/// K = -R_indenter / U when the indenter is held (base shaken: force transmitted to the indenter),
/// K = R_indenter / U when the indenter is driven, K = R_base / U when the indenter is free (the
/// driving-point stiffness of the base). Modulus E = K thickness / area (nominal, undeformed).
enum class Measure { indenter_held, indenter_driven, indenter_free };
SweepRow make_row(const FrequencyResponse& r, Measure measure, const NominalGeometry& geometry);

/// Writes the sweep CSV (units in the column names; phases in degrees in (-180, 180]); `comment`
/// lines first as "# ...". Throws std::runtime_error if the file cannot be written.
void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows,
                     const std::vector<std::string>& comment);

/// Writes the complex displacement field of the first 3 x nodes DOFs of `r` as one frame whose
/// "time" is the frequency [Hz]: displacement = real part, plus point arrays U_real_mm, U_imag_mm,
/// U_amplitude_mm (per component |u^|) and U_phase_deg.
void write_frequency_frame(ResultSeries& series, const mesh::Mesh& mesh, const FrequencyResponse& r);

}  // namespace cushion::solver::dynamics
