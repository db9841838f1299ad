#pragma once
/// The solver's own model of the calibration tests (hyperfoam + finite-strain Prony, material-point
/// driver), used to judge a fitted material on every test of a campaign and by the consistency refit.
///
/// Dynamic test, frequency domain (paper 2.3; small amplitude about a relaxed preload):
/// with F_b = diag(l, l2, l3) the long-term equilibrium at the preload (lateral PK2 stress zero for a
/// free specimen), the complex tangent C*(w) = dS/dE* of Material::complex_tangent is condensed to
/// uniaxial stress (dS22 = dS33 = 0 when free; dE22 = dE33 = 0 when constrained), C*_c, and the
/// nominal (P11 = l S11) modulus per nominal strain is
///   E*(w) = dP11/dl = S11(F_b) + l^2 C*_c(w),
/// compression-positive strain and stress have the same modulus. S11 is the (compressive, negative)
/// geometric term, not relaxed by the Prony series, so with C*_c = (1 + sum a_i iw tau_i/(1 + iw tau_i)) C_c:
///   E*(0) = K_hf = S11 + l^2 C_c  (long-term nominal tangent),  E* - K_hf = K_v sum a_i iw tau_i/(1 + iw tau_i),
///   K_v = l^2 C_c = K_hf - S11 (the part the Prony series scales).
#include <memory>
#include <string>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/lab.hpp"
#include "calibration/uniaxial_model.hpp"
#include "material/io/material_file.hpp"

namespace cushion::calibration {

/// A visco-hyperfoam material in the solver's parameters.
struct ViscoHyperfoam {
  std::vector<material::HyperfoamTerm> terms;  ///< long-term hyperfoam (ABAQUS MODULI=LONG TERM): mu [MPa], alpha, nu
  std::vector<material::PronyTerm> prony;      ///< relative moduli g_i (ABAQUS) and tau_i [s]
};

/// The material spec (long-term convention) and the built solver model.
material::MaterialSpec to_spec(const ViscoHyperfoam& m, const std::string& name, const std::string& description,
                               double density);
std::shared_ptr<const material::Material> build_model(const ViscoHyperfoam& m);
/// Empty if a material file of `m` would be accepted by the reader, else the reader's reason.
std::string material_problem(const ViscoHyperfoam& m);

/// Relative moduli from moduli relative to the long-term modulus: g_i = a_i / (1 + sum a), and back.
std::vector<material::PronyTerm> prony_from_long_term_ratios(const std::vector<double>& a, const std::vector<double>& tau);
std::vector<double> long_term_ratios(const std::vector<material::PronyTerm>& prony);

material::LoadMode load_mode(Lateral lateral);

/// Long-term state of the elastic base at a compression-positive nominal preload strain.
struct PreloadTangent {
  double preload = 0.0;     ///< nominal compression [-]
  double stretch = 1.0;     ///< l = 1 - preload
  double lateral_stretch = 1.0;  ///< l2 = l3
  double S11 = 0.0;         ///< PK2 stress [MPa], tension positive (negative in compression)
  double stress = 0.0;      ///< nominal stress [MPa], compression positive
  double K_hf = 0.0;        ///< long-term nominal tangent dP11/dl [MPa]
  double K_v = 0.0;         ///< l^2 C_c [MPa]: the part scaled by the Prony series
};
PreloadTangent preload_tangent(const material::Hyperelastic& base, double preload, Lateral lateral = Lateral::free);

/// When the sines run after the preload ramp (paper 2.3: indent at 30 mm/min, then at least 20 cycles
/// per frequency, frequencies in increasing order), the preload has not relaxed: the geometric term uses
/// the TOTAL stress S11(t) at each frequency's measuring window (the complex tangent of the Prony model
/// does not depend on the relaxation state). Times from the start of the preload ramp.
struct DynamicSchedule {
  double preload_rate_mm_min = 30.0;  ///< crosshead speed of the preload ramp
  double thickness = 80.0;            ///< specimen [mm]
  int cycles = 20;                    ///< cycles per frequency
  int fit_cycles = 10;                ///< last cycles measured (window centre = end - fit_cycles/(2 f))
  double dwell_s = 0.0;               ///< hold at the preload before the sweep [s]
};

/// The base path of the dynamic test along `schedule` (the sampling model_dynamic_moduli runs): the preload
/// ramp in ceil(5 ramp seconds) increments, then one sample at each frequency's window centre; about a
/// relaxed preload (`schedule` null) the single preload sample. Prony times tau [s] for the weights.
/// `amplitude`: nominal strain amplitude per frequency (empty: the small-amplitude limit).
DynamicPath dynamic_path(double preload, const std::vector<double>& frequency, const DynamicSchedule* schedule,
                         const std::vector<double>& tau, const std::vector<double>& amplitude = {});

/// Nominal strain amplitude [-] of the dynamic test's sine at each frequency: displacement a/(2 pi f)^2 over
/// the thickness, a the PEAK acceleration = half the campaign's peak-to-peak acceleration_amplitude.
std::vector<double> strain_amplitudes(const DynamicTest& test, double thickness);

/// The in-contact part of a quasi-static record as a path from the start of loading: samples
/// [load_begin, unload_end], without unload_end when the unloading was truncated at a ~zero force there
/// (after a lift-off the platen no longer sets the strain), times from the start of loading, preceded by a
/// relaxed zero-strain sample if the record starts compressed.
struct ContactSamples {
  std::vector<double> time;    ///< [s] from the start of loading
  std::vector<double> strain;  ///< nominal compression [-]
  std::vector<double> stress;  ///< measured nominal stress [MPa], compression positive (NaN at an added start)
};
ContactSamples contact_samples(const QuasiStaticTest& test, const Segments& segments, const Specimen& specimen);

/// Storage and loss moduli [MPa] (nominal, per nominal strain) of `model` about the preload at
/// frequencies [Hz], from Material::complex_tangent (see above): about the relaxed long-term state of
/// `base` when `schedule` is null, else about the state the point driver reaches along the schedule.
DynamicModuli model_dynamic_moduli(const material::Material& model, const material::Hyperelastic& base,
                                   double preload, const std::vector<double>& frequency,
                                   Lateral lateral = Lateral::free, const DynamicSchedule* schedule = nullptr);

/// The protocol of a recorded quasi-static test: crosshead rate, the record's peak strain and hold, the
/// campaign's preflex, rest and lift-off keys (the record starts after the rest), sampled at `sample_hz`.
QuasiStaticProtocol protocol_of(const QuasiStaticTest& test, const Segments& segments, double sample_hz);

/// The protocol of a dynamic test as its campaign describes it (preflex, rest, preload ramp at the test's
/// preload_rate_mm_min or `default_preload_rate_mm_min` when it gives none, dwell, amplitude convention,
/// cycles and fit_cycles per frequency, lift-off), run at `steps_per_cycle` time steps a cycle of the fitted cycles and
/// `transient_steps_per_cycle` of the cycles before them (0: steps_per_cycle).
DynamicProtocol protocol_of(const DynamicTest& test, int steps_per_cycle, int transient_steps_per_cycle,
                            double default_preload_rate_mm_min);

/// Median sampling rate of a record [Hz].
double sampling_rate(const StressStrainRecord& record);

/// Model prediction of a quasi-static test: nominal stress [MPa], compression positive, at the
/// record's sample times (from the start of loading), from calibration::run_quasi_static (platen control).
struct QuasiStaticPrediction {
  std::vector<double> time;    ///< record times [s]
  std::vector<double> strain;  ///< record strains [-]
  std::vector<double> measured, model;  ///< [MPa]
  double rms_error = 0.0;      ///< RMS(model - measured) / peak measured [-]
  double max_error = 0.0;      ///< max|model - measured| / peak measured [-]
};
QuasiStaticPrediction predict_quasi_static(const material::Material& model, const Specimen& specimen,
                                           const QuasiStaticTest& test, const Segments& segments, double sample_hz);

/// Model vs measured complex modulus of a dynamic test.
struct DynamicPrediction {
  DynamicModuli measured, model;
  double magnitude_rms = 0.0;  ///< RMS of |E*|_model/|E*|_measured - 1 [-]
  double phase_rms = 0.0;      ///< RMS of the phase difference [deg]
  double storage_rms = 0.0, loss_rms = 0.0;  ///< RMS relative errors of E', E'' [-]
};
DynamicPrediction predict_dynamic(const material::Material& model, const material::Hyperelastic& base,
                                  const DynamicTest& test, const DynamicSchedule* schedule = nullptr);

}  // namespace cushion::calibration
