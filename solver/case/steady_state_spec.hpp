#pragma once
/// The "steady_state" step of a case file: plain structs (parsed by parse_steady_state.cpp). A
/// steady-state step is a linear perturbation about the committed end state of the previous step
/// (it leaves that state unchanged); it needs a preceding static or visco step. Units: Hz, mm,
/// mm^2, mm/s^2, 1/s, s.
///
/// {"name": "sweep", "type": "steady_state",
///  "steady_state": {
///    "frequencies": {"start_Hz": 1, "end_Hz": 20, "step_Hz": 1}  |  "frequencies_Hz": [1, 2, 5],   all > 0
///    "excitation": {"set": "base" | "contact": "sitbar", "dof": "x"|"y"|"z",
///                   "acceleration_amplitude_m_s2": 0.25, "amplitude_is"?: "peak_to_peak" | "peak"
///                   | "displacement_amplitude_mm": 0.1},         exactly one amplitude key
///        acceleration a: displacement U = a_peak / (2 pi f)^2, a_peak = a/2 for peak_to_peak (default,
///        the paper's wording), a for peak. Phase reference: the driven displacement (real, > 0).
///    "held"?: [{"set": "top", "dof": "x"|...|"xyz"}],           amplitude 0 (driven DOFs win)
///    "indenters"?: [{"contact": "sitbar", "motion": "held" | "free", "mass_kg"?: m}],
///        rigid indenters of the base state's contacts (solver/dynamics/contact_linearisation.hpp):
///        one translation DOF each, along the excitation's dof; held unless excited or listed
///        "free" (then mass_kg > 0 is required: a seat-occupant mass, transmissibility)
///    "measure": "top" | {"contact": "sitbar"},                   set or indenter whose reaction gives
///        the dynamic stiffness: held (base shaken, K = -R/U), the excited one itself (K = R/U), or
///        a free indenter (K = R_base/U, the driving-point stiffness; transmissibility = w/U)
///    "damping"?: {"rayleigh_alpha_1_s"? = 0, "rayleigh_beta_s"? = 0, "structural"? = 0},   all >= 0
///        (damping.hpp)
///    "base_stress"?: "relaxed" | "as_left" = "relaxed",
///    "area_mm2": A | "contact", "thickness_mm": H,                nominal modulus E = (F/A)/(U/H), > 0;
///        "contact": the tributary area of the measured indenter's closed nodes at the base state
///    "output"?: {"vtk"?: true},                                   one .vtu per frequency + .pvd
///    "linear_solver"?: "iterative" | "direct" = "iterative",      steady_state.hpp (SolveMethod)
///    "gmres_tolerance"?: 1e-10                                    relative residual, in (0, 1e-3]
///  }}
/// Checked when parsed: keys, units, values, set names defined by the case, a preceding step, contact
/// names (contacts of the last static, visco or dynamic step before). Checked once the mesh and the
/// material are built (check_loaded_case, case_file.hpp): the sets exist in the mesh and are not
/// empty, the measured set has a node driven or held in the excitation's dof, the material has a
/// mass density.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "solver/case/damping.hpp"

namespace cushion::solver {

/// Which stress enters the geometric stiffness of the linearisation (solver/dynamics/linearised_system.hpp).
enum class BaseStress {
  relaxed,  ///< long-term stress at the base deformation (ABAQUS convention, default)
  as_left   ///< committed total stress at the end of the previous step
};

/// How an acceleration amplitude is read. The paper writes "0.25 m/s^2 peak-to-peak"; cushion's
/// default is peak_to_peak (the paper's words), i.e. a peak acceleration of a / 2.
enum class AccelerationReading { peak, peak_to_peak };

/// Node set and components (x, y, z) of a steady-state boundary entry.
struct SetDofs {
  std::string set;                                ///< node set name
  std::array<bool, 3> dofs{false, false, false};  ///< components x, y, z
  std::string key;  ///< "steps[1].steady_state.held[0]", for messages
};

/// Motion of a rigid indenter (a contact of the base state) during the sweep.
struct IndenterMotion {
  std::string contact;  ///< contact name
  bool free = false;    ///< free with `mass` (else held)
  double mass = 0.0;    ///< [t]
  std::string key;      ///< "steps[2].steady_state.indenters[0]", for messages
};

/// A harmonic nodal force of a steady-state step (decks: *CLOAD inside *STEADY STATE DYNAMICS): every node
/// of `set` gets the real amplitude `force` [N] in `component` (0, 1, 2), in phase with the others.
struct HarmonicLoad {
  std::string set;
  int component = 0;
  double force = 0.0;  ///< [N] per node
  std::string key;     ///< "deck.inp:42", for messages
};

/// Frequencies placed around the resonances (decks: modal *STEADY STATE DYNAMICS, as ABAQUS/CalculiX
/// place them): the natural frequencies in [low, high] split the range into intervals, each interval
/// gets `points` frequencies clustered towards its ends by `bias` (dynamics::frequency_points).
struct ResonancePoints {
  double low = 0.0, high = 0.0;  ///< [Hz]
  int points = 20;               ///< per interval, >= 2
  double bias = 3.0;             ///< >= 1
};

/// The "steady_state" object of a step.
struct SteadyStateSpec {
  std::vector<double> frequencies;  ///< [Hz], > 0, in sweep order
  SetDofs excitation;               ///< exactly one component; set empty if a contact is excited
  std::string excitation_contact;   ///< excited indenter (contact name) or empty
  bool from_acceleration = true;    ///< amplitude given as an acceleration
  double acceleration = 0.0;        ///< [mm/s^2] as given (peak or peak-to-peak)
  AccelerationReading reading = AccelerationReading::peak_to_peak;  ///< reading of `acceleration`
  double displacement = 0.0;        ///< [mm] peak displacement (from_acceleration false)
  std::vector<SetDofs> held;        ///< components held at zero
  std::vector<IndenterMotion> indenters;  ///< indenters listed as held or free
  std::string measure;              ///< set of the measured reaction (empty if measure_contact)
  std::string measure_contact;      ///< measured indenter (contact name) or empty
  Damping damping;                  ///< Rayleigh [1/s], [s] and structural [-] damping
  BaseStress base_stress = BaseStress::relaxed;  ///< stress of the geometric stiffness
  double area = 0.0;                ///< [mm^2] (0 with area_from_contact)
  bool area_from_contact = false;   ///< area = closed area of the measured indenter
  double thickness = 0.0;           ///< [mm]
  bool vtk = true;                  ///< write a .vtu per frequency
  bool iterative = true;            ///< GMRES + real Cholesky preconditioner (else complex LU)
  double gmres_tolerance = 1e-10;   ///< [-]
  std::string key;                  ///< "steps[1].steady_state"
  /// Decks only: harmonic forces instead of a driven set (then no excitation set or contact and no
  /// measure; the response is reported by `prints`), node sets whose complex displacements are written
  /// per frequency (<step>_node_print_<set>.csv), and frequencies placed at run time around the
  /// resonances (then `frequencies` is empty).
  std::vector<HarmonicLoad> loads;
  std::vector<std::string> prints;
  std::optional<ResonancePoints> resonance_points;
  /// The excitation's component: 0, 1, 2 for x, y, z.
  int component() const { return excitation.dofs[0] ? 0 : excitation.dofs[1] ? 1 : 2; }
};

/// A "frequency" step (decks: *FREQUENCY): the lowest natural frequencies of the model linearised about
/// the carried state (long-term tangent, consistent mass), with the DOFs of the step's boundary
/// conditions held; written to <step>_frequencies.csv. A linear perturbation: the state is unchanged.
struct FrequencySpec {
  int modes = 10;              ///< how many, >= 1
  double low = 0.0;            ///< [Hz] report only frequencies >= low
  double high = 0.0;           ///< [Hz] and <= high (0: no upper bound)
  std::string key;             ///< "deck.inp:12", for messages
};

}  // namespace cushion::solver
