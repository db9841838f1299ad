#pragma once
/// The "steady_state" step of a case file: plain structs and their parser. A steady-state step is a
/// linear perturbation about the committed end state of the previous step (it leaves that state
/// unchanged); it needs a preceding static or visco step. Units: Hz, mm, mm^2, mm/s^2, 1/s, s.
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
///    "base_stress"?: "relaxed" | "as_left" = "relaxed",
///    "area_mm2": A | "contact", "thickness_mm": H,                nominal modulus E = (F/A)/(U/H), > 0;
///        "contact": the tributary area of the measured indenter's closed nodes at the base state
///    "output"?: {"vtk"?: true},                                   one .vtu per frequency + .pvd
///    "linear_solver"?: "iterative" | "direct" = "iterative",      steady_state.hpp (SolveMethod)
///    "gmres_tolerance"?: 1e-10                                    relative residual, in (0, 1e-3]
///  }}
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cushion::solver::dynamics {

/// Node set and components (x, y, z) of a steady-state boundary entry.
struct SetDofs {
  std::string set;
  std::array<bool, 3> dofs{false, false, false};
  std::string key;  ///< "steps[1].steady_state.held[0]", for messages
};

/// Motion of a rigid indenter (a contact of the base state) during the sweep.
struct IndenterMotion {
  std::string contact;  ///< contact name
  bool free = false;    ///< free with `mass` (else held)
  double mass = 0.0;    ///< [t]
  std::string key;      ///< "steps[2].steady_state.indenters[0]", for messages
};

struct SteadyStateSpec {
  std::vector<double> frequencies;  ///< [Hz], > 0, in sweep order
  SetDofs excitation;               ///< exactly one component; set empty if a contact is excited
  std::string excitation_contact;   ///< excited indenter (contact name) or empty
  bool from_acceleration = true;    ///< amplitude given as an acceleration
  double acceleration = 0.0;        ///< [mm/s^2] as given (peak or peak-to-peak)
  bool peak_to_peak = true;         ///< reading of `acceleration`
  double displacement = 0.0;        ///< [mm] peak displacement (from_acceleration false)
  std::vector<SetDofs> held;
  std::vector<IndenterMotion> indenters;
  std::string measure;              ///< set of the measured reaction (empty if measure_contact)
  std::string measure_contact;      ///< measured indenter (contact name) or empty
  double alpha = 0.0;               ///< Rayleigh mass-proportional [1/s]
  double beta = 0.0;                ///< Rayleigh stiffness-proportional [s]
  double structural = 0.0;          ///< structural loss factor [-]
  bool relaxed_base = true;         ///< base stress: relaxed (true) or as_left
  double area = 0.0;                ///< [mm^2] (0 with area_from_contact)
  bool area_from_contact = false;   ///< area = closed area of the measured indenter
  double thickness = 0.0;           ///< [mm]
  bool vtk = true;                  ///< write a .vtu per frequency
  bool iterative = true;            ///< GMRES + real Cholesky preconditioner (else complex LU)
  double gmres_tolerance = 1e-10;   ///< [-]
  std::string key;                  ///< "steps[1].steady_state"
};

/// Parses the object "steady_state" of a step (path e.g. "steps[1].steady_state") of the case file
/// `source`. `set_exists` says whether a set name is defined; `first_step`: no previous step (error).
/// Throws cushion::InputError "source: path.key: problem" on unknown keys, missing keys, wrong
/// values (frequencies <= 0, unknown sets, ...). Contact names are checked by the step when it runs
/// (before it writes anything): they must be contacts of the previous step.
SteadyStateSpec parse_steady_state_spec(const nlohmann::json& value, const std::string& source,
                                        const std::string& path,
                                        const std::function<bool(const std::string&)>& set_exists, bool first_step);

}  // namespace cushion::solver::dynamics
