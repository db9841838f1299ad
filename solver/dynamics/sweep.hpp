#pragma once
/// Frequency sweep results in the paper's terms (Fig. 12): excitation amplitude from an acceleration
/// amplitude, dynamic stiffness and nominal dynamic modulus, CSV and VTK (.pvd over frequency) output.
#include <complex>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "solver/case/steady_state_spec.hpp"
#include "solver/distribution.hpp"
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

/// Distributed sweeps: response k (and its solve time [s]) was computed on process owner(k) only;
/// afterwards every process holds all of them. Collective.
void share_responses(std::vector<FrequencyResponse>& responses, std::vector<double>& solve_time,
                     const std::function<int(std::size_t)>& owner, const Distribution& d);

/// Writes the sweep CSV (units in the column names; phases in degrees in (-180, 180]); `comment`
/// lines first as "# ...". Throws std::runtime_error if the file cannot be written.
void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows,
                     const std::vector<std::string>& comment);

/// Phase of z in degrees, wrapped into (-180, 180] (0 for z = 0).
double phase_deg(std::complex<double> z);

/// Writes the response `r` as one frame on the DEFORMED base state of `system`, whose "time" is the
/// frequency [Hz] (ParaView's time slider then steps through the frequencies). `component` (0, 1, 2) is
/// the excited displacement component, the phase reference of the scalar phases. Arrays:
///  point data: displacement_mm = base displacement u_base (Warp By Vector, scale 1, shows the preload
///    dent); U_real_mm, U_imag_mm = Re, Im u_hat; U_amplitude_mm = per-component |u_hat_c| (its ParaView
///    "Magnitude" is the complex amplitude |u_hat| = sqrt(sum |u_hat_c|^2)); U_phase_deg = arg u_hat_c of
///    the excited component, in (-180, 180] (0 where u_hat_c = 0), relative to the drive (real, positive).
///  cell data (element averages): the base state's cauchy_stress_kPa, von_mises_kPa, pressure_kPa,
///    log_strain, principal_stretches, J (as the quasi-static frames; stress = the base stress S_geo of
///    the linearisation, relaxed by default); the linearised Cauchy stress perturbation
///    (LinearisedSystem::cauchy_perturbation) as sigma_hat_real_kPa, sigma_hat_imag_kPa,
///    sigma_hat_amplitude_kPa (per-component modulus; 6 components XX YY ZZ XY YZ XZ) and
///    sigma_hat_phase_deg (phase of the excited normal component, e.g. ZZ, in (-180, 180]).
/// The response at time t is then u = u_base + Re(u_hat e^{i w t}), sigma = sigma_base + Re(sigma_hat e^{i w t}).
void write_frequency_frame(ResultSeries& series, const mesh::Mesh& mesh, const LinearisedSystem& system,
                           const LinearisedSystem::ElementBase& base, const FrequencyResponse& r, int component);

}  // namespace cushion::solver::dynamics
