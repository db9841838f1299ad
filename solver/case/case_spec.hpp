#pragma once
/// Case files: the plain structs a case file (JSON) is parsed into. Nothing is built here; the
/// parser (case_file.hpp) has validated every value before a struct is returned. Internal units:
/// mm, s (the file carries the unit in each key name: "_mm", "_s", "_mm3").
///
/// Case file reference (every key; "?" = optional, default after "="):
/// {
///   "description"?: "free text",
///   "mesh": exactly one of
///     {"generate": {"type": "hex8" | "tet4" | "tet10",          structured block (C3D8 / C3D4 / C3D10)
///                   "box_mm": [x0, x1, y0, y1, z0, z1],        [mm], x0 < x1, y0 < y1, z0 < z1
///                   "elements": [nx, ny, nz],                   integers >= 1 (tets: 6 per hex cell),
///                                                              nx ny nz <= 1e7 cells
///                   "grading"?: {"x"|"y"|"z": {"ratio": r, "focus_mm"?: f}}}}
///                        ratio = h_last/h_first (geometric) or h_coarsest/h_finest (with focus_mm)
///      {"inp": "mesh.inp", "elset"?: "FOAM"}                    ABAQUS input file (nodes, elements, *NSET);
///                        elset: only that element set and its nodes (e.g. a deck with a meshed indenter)
///      {"stl": "part.stl", "max_volume_mm3": v,                 TetGen volume mesh of a closed STL [mm^3]
///       "type"?: "tet4" | "tet10" = "tet4", "max_radius_edge"? = 1.5, "min_dihedral_deg"? = 0}
///     plus "formulation"?: "full" | "fbar" = "full"              hex8 only (F-bar: de Souza Neto 1996)
///   "material": {"file": "foam.json"}                           material file (material_file.hpp)
///   "sets"?: {"name": "selector", ...}                           node sets by selector text, e.g.
///            "z == 0", "x <= 1e-6", "box(x0,y0,z0, x1,y1,z1)", "all" (mesh/selectors.hpp) [mm]
///   "amplitudes"?: {"name": {"time_s": [t0, t1, ...], "value": [a0, a1, ...],
///                            "time"?: "step" | "total" = "step"}}
///            piecewise linear in time, constant outside the table (ABAQUS *AMPLITUDE, TIME=STEP TIME)
///                  or {"type": "sine", "frequency_Hz": f, "start_s"? = 0, "time"?: "step" | "total"}
///            a(t) = sin(2 pi f (t - start_s)) for t >= start_s, 0 before (exact velocity and
///            acceleration for dynamic steps; a harmonic base motion starts from rest at start_s)
///   "steps": [ {                                                 run in order, total time accumulates
///     "name": "load",
///     "type": "static" | "visco",        static: rate-independent; visco: viscous relaxation in time
///                                        "dynamic": implicit Newmark time stepping (inertia, damping)
///                                        with the keys of static/visco steps plus those below
///                                        "steady_state": frequency sweep about the previous step's end
///                                        state; its keys: solver/case/steady_state_spec.hpp
///     "long_term"?: false,               static only: fully relaxed (long-term) moduli (*STATIC, LONG TERM)
///     "time_period_s": T,                > 0 [s]
///     "increment"?: {"initial_s"? = T, "min_s"? = 1e-5 T, "max_s"? = T, "max_increments"? = 100,
///                    "fixed"? = false},  0 < min_s <= initial_s <= max_s, initial_s <= T
///                                        fixed: every increment is initial_s
///                                        (shortened only to end on amplitude corners / frame times),
///                                        no growth, no cut-back: a failed increment ends the run
///     "damping"?: {"rayleigh_alpha_1_s"? = 0, "rayleigh_beta_s"? = 0},   dynamic only, both >= 0:
///                                        C = alpha M + beta K_R(0) (solver/case/damping.hpp)
///     "newmark"?: {"alpha"? = 0, "gamma"? = 0.5, "beta"? = 0.25}, dynamic only; alpha: HHT in [-1/3, 0]
///                                        (ABAQUS ALPHA; gamma, beta then default to (1 - 2 alpha)/2,
///                                        (1 - alpha)^2/4); gamma >= 1/2 and
///                                        beta >= (gamma + 1/2)^2 / 4 (unconditionally stable)
///     "boundary": [                      the complete list for this step (nothing is inherited)
///        {"set": "top", "dof": "x"|"y"|"z"|"xy"|"xz"|"yz"|"xyz", "value_mm": -60, "amplitude"?: "ramp"},
///            prescribed displacement [mm] of every listed component, relative to the reference
///            configuration. Without amplitude it ramps linearly over the step from the value at the
///            end of the previous step (0 in the first step) to value_mm (ABAQUS default for
///            displacements); with an amplitude it is value_mm * a(t).
///        {"set": "sym_x", "type": "symmetry_x" | "symmetry_y" | "symmetry_z"}   u_x (u_y, u_z) = 0
///        {"set": "base",  "type": "fixed"}                                     u = 0 (ENCASTRE)
///     ],
///     "contact"?: [ rigid indenters in contact with node sets: see solver/case/contact_spec.hpp ],
///     "output"?: {"frames_every_s": dt  |  "frame_every_increments": n   (default: every increment),
///                 "history"?: [{"set": "top", "quantities": ["U3", "RF3", ...]}]}
///        A frame (.vtu) is written at the chosen interval and always at the end of the step.
///        History rows are written every converged increment; Ui = mean displacement of the set
///        [mm], RFi = sum of reaction forces over the set [N]; columns "top.U3_mm", "top.RF3_N".
///        The history columns of a run are the union over its steps, in order of first appearance.
///   } ],
///   "solver"?: {"threads"? = 0 (0: all cores), "linear_solver"? = "auto" | "cholmod" | "umfpack" | "petsc",
///               "petsc_options"? = ""   with "petsc" only: PETSc options such as "-ksp_type cg -pc_type
///               gamg" (solver/petsc/petsc_solver.hpp; checked against PETSc before the run starts)
///               "residual_tolerance"? = 0.005   max residual / time-averaged force (ABAQUS R_n)
///               "correction_tolerance"? = 0.01  max correction / max increment of u (ABAQUS C_n)
///               "max_iterations"? = 16, "max_cutbacks"? = 5,
///               "cutback_factor"? = 0.25, "growth_factor"? = 1.5,
///               "newton"? = "full" | "modified" (keep a factorization while it contracts the residual,
///               solver/newton.hpp), "max_contraction"? = 0.5 (modified: refactorize when
///               ||r_k||_2 > max_contraction ||r_k-1||_2)}
/// }
/// Paths are relative to the folder of the case file. Unknown keys, missing keys, wrong types,
/// wrong units (e.g. "time_period_ms"), non-finite numbers and references to undefined sets or
/// amplitudes raise cushion::InputError "case.json: steps[1].boundary[0].amplitude: ..." when the
/// file is parsed (solver/case/case_file.hpp). What needs the mesh and the material (sets of an .inp
/// mesh, empty sets, a mass density for dynamic and steady_state steps) is checked right after they
/// are built, before the first step runs (load_case).
///
/// Example (1/8 of an 80 mm cube compressed 60 mm at 2 mm/s):
/// {
///   "mesh": {"generate": {"type": "hex8", "box_mm": [0, 40, 0, 40, 0, 80], "elements": [4, 4, 8]}},
///   "material": {"file": "../materials/paper_table3.json"},
///   "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 80"},
///   "steps": [{"name": "load", "type": "visco", "time_period_s": 30,
///              "increment": {"initial_s": 0.5, "min_s": 1e-4, "max_s": 1},
///              "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
///                           {"set": "bottom", "type": "symmetry_z"},
///                           {"set": "top", "dof": "z", "value_mm": -60}],
///              "output": {"frames_every_s": 1, "history": [{"set": "top", "quantities": ["U3", "RF3"]}]}}]
/// }
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mesh/structured_hex.hpp"
#include "solver/case/contact_spec.hpp"
#include "solver/case/damping.hpp"
#include "solver/case/steady_state_spec.hpp"

namespace cushion::solver {

/// Structured block ("mesh.generate"). `type` may be tet10 (block built as tet4, then to_tet10).
struct GenerateMeshSpec {
  mesh::ElementType type = mesh::ElementType::hex8;
  mesh::Vec3 low = mesh::Vec3::Zero();   ///< (x0, y0, z0) [mm]
  mesh::Vec3 high = mesh::Vec3::Ones();  ///< (x1, y1, z1) [mm]
  std::array<int, 3> elements{1, 1, 1};  ///< nx, ny, nz
  std::array<mesh::AxisGrading, 3> grading{};
};

/// TetGen mesh of a closed STL surface ("mesh.stl").
struct StlMeshSpec {
  std::filesystem::path file;       ///< resolved against the case folder
  double max_volume = 0.0;          ///< [mm^3]
  bool quadratic = false;           ///< tet10 instead of tet4
  double max_radius_edge = 1.5;     ///< [-], TetGen -q
  double min_dihedral = 0.0;        ///< [deg]
};

enum class HexFormulation { full, fbar };

struct MeshSpec {
  enum class Source { generate, inp, stl } source = Source::generate;
  GenerateMeshSpec generate;        ///< source == generate
  std::filesystem::path inp_file;   ///< source == inp, resolved against the case folder
  std::string inp_elset;            ///< source == inp: keep only this element set (empty: all elements)
  StlMeshSpec stl;                  ///< source == stl
  HexFormulation formulation = HexFormulation::full;  ///< hex8 elements only
};

/// Amplitude a(t) [-]: piecewise linear (tabular, constant beyond the first and last points) or a
/// sine a(t) = sin(2 pi f (t - start)) for t >= start, 0 before.
struct Amplitude {
  std::vector<double> time;   ///< [s], strictly increasing (tabular)
  std::vector<double> value;  ///< [-], same size as time (tabular)
  bool total_time = false;    ///< false: t is the step time; true: the total time
  enum class Kind { tabular, sine } kind = Kind::tabular;
  double frequency = 0.0;     ///< sine: f [Hz] > 0
  double start = 0.0;         ///< sine: start time [s] on the amplitude's clock
  /// a(t) [-]; t in [s] on the amplitude's own clock (tabular: linear interpolation).
  double at(double t) const;
  /// da/dt [1/s]: sine exact; tabular the slope of the segment ending at t (left derivative; 0 at and
  /// before the first point and after the last).
  double rate(double t) const;
  /// d2a/dt2 [1/s^2]: sine exact; tabular 0 (the velocity jumps at corners are not represented).
  double second_rate(double t) const;
};

/// One boundary condition of a step. Components not listed in `dofs` are free.
struct BoundarySpec {
  std::string set;
  enum class Kind { displacement, symmetry, fixed } kind = Kind::displacement;
  std::array<bool, 3> dofs{false, false, false};  ///< constrained components x, y, z
  double value = 0.0;                    ///< prescribed displacement [mm] (0 for symmetry/fixed)
  std::optional<std::string> amplitude;  ///< name in CaseSpec::amplitudes; none: linear ramp
  std::string key;                       ///< "steps[0].boundary[2]", for messages
};

/// Prescribed displacement [mm] of one constrained component at step time `t_step` [s] of a step of
/// length `period` [s] starting at total time `t_start` [s]. `start_value` [mm]: that component's
/// value at the end of the previous step (0 in the first step); used by the default linear ramp.
double prescribed_value(const BoundarySpec& bc, const std::map<std::string, Amplitude>& amplitudes,
                        double start_value, double t_step, double period, double t_start);

/// Concentrated force on every node of a set (ABAQUS *CLOAD; from decks, static and visco steps only).
/// Like a displacement it ramps linearly over the step from the value at the end of the previous
/// step (0 at first), or follows value * a(t) with an amplitude. Dead load (fixed direction).
struct LoadSpec {
  std::string set;                       ///< node set (each node gets `value`)
  int component = 0;                     ///< 0, 1, 2: x, y, z
  double value = 0.0;                    ///< [N] per node
  std::optional<std::string> amplitude;  ///< name in CaseSpec::amplitudes; none: linear ramp
  std::string key;                       ///< "FILE:LINE", for messages
};

/// Pressure on one element face (ABAQUS *DLOAD Pn; from decks, static and visco steps only): a
/// follower load on the current (deformed) face, positive pushing into the solid.
struct PressureSpec {
  mesh::Face face;
  double value = 0.0;                    ///< [MPa] at the end of the step
  double start_value = 0.0;              ///< [MPa] at the start of the step (linear ramp; unused with an amplitude)
  std::optional<std::string> amplitude;  ///< name in CaseSpec::amplitudes; none: linear ramp
  std::string key;                       ///< "FILE:LINE", for messages
};

/// Value at step time `t_step` [s] of a quantity with end value `value` and optional amplitude
/// (value * a(t)); without amplitude a linear ramp from `start_value` over `period` [s] (ABAQUS).
double ramped_value(double value, const std::optional<std::string>& amplitude,
                    const std::map<std::string, Amplitude>& amplitudes, double start_value, double t_step,
                    double period, double t_start);

/// Prescribed displacement [mm], velocity [mm/s] and acceleration [mm/s^2] of one component.
struct PrescribedMotion {
  double u = 0.0, v = 0.0, a = 0.0;
};
/// As prescribed_value, with the time derivatives of the history (Amplitude::rate, second_rate; the
/// default linear ramp: constant velocity over the step, zero acceleration; 0 for symmetry/fixed).
PrescribedMotion prescribed_motion(const BoundarySpec& bc, const std::map<std::string, Amplitude>& amplitudes,
                                   double start_value, double t_step, double period, double t_start);

/// ABAQUS-style automatic increment control of a step [s].
struct IncrementSpec {
  double initial = 0.0, min = 0.0, max = 0.0;  ///< [s]
  int max_increments = 100;
  bool fixed = false;  ///< constant increment `initial`, no growth, no cut-back
};

/// Keys of a "dynamic" step (Newmark time integration, solver/analysis/dynamic_step.hpp).
struct DynamicSpec {
  Damping damping;              ///< Rayleigh damping [1/s], [s] (structural 0)
  double gamma = 0.5;           ///< Newmark gamma [-]
  double beta = 0.25;           ///< Newmark beta [-]
  double hht_alpha = 0.0;       ///< HHT alpha [-] in [-1/3, 0] (solver/dynamics/newmark.hpp)
  std::string key;              ///< "steps[2]", for messages
};

enum class HistoryQuantity { U1, U2, U3, RF1, RF2, RF3 };
std::string to_string(HistoryQuantity q);  ///< "U3"

/// History column name with unit, e.g. "top.U3_mm", "top.RF3_N".
std::string history_column(const std::string& set, HistoryQuantity q);

struct HistoryRequest {
  std::string set;
  std::vector<HistoryQuantity> quantities;
};

struct OutputSpec {
  std::optional<double> frames_every;           ///< [s] of step time
  int frame_every_increments = 1;               ///< used when frames_every and frame_times are empty
  std::vector<double> frame_times;              ///< [s of step time], ascending (decks: *TIME POINTS)
  std::vector<HistoryRequest> history;
};

struct StepSpec {
  std::string name;
  enum class Type { static_, visco, steady_state, dynamic, frequency } type = Type::static_;
  bool long_term = false;     ///< static only: long-term (relaxed) response
  double period = 0.0;        ///< time period [s]
  IncrementSpec increment;
  std::vector<BoundarySpec> boundary;
  std::vector<ContactSpec> contact;  ///< rigid indenters (contact_spec.hpp)
  std::vector<LoadSpec> loads;       ///< concentrated forces, static/visco/dynamic (decks); the complete
                                     ///< list: a load of the previous step not listed ramps to 0
  std::vector<PressureSpec> pressures;  ///< face pressures, static/visco/dynamic (decks): the complete list
  OutputSpec output;
  SteadyStateSpec steady_state;      ///< type steady_state only (steady_state_spec.hpp)
  DynamicSpec dynamic;               ///< type dynamic only
  FrequencySpec frequency;           ///< type frequency only (decks: *FREQUENCY)
  /// A linear perturbation step (steady_state, frequency): it leaves the carried state unchanged.
  bool perturbation() const { return type == Type::steady_state || type == Type::frequency; }
};

struct SolverSpec {
  int threads = 0;  ///< 0: all hardware threads
  enum class LinearSolver { automatic, cholmod, umfpack, petsc } linear_solver = LinearSolver::automatic;
  std::string petsc_options;           ///< "petsc" only: "-name value" pairs or flags, whitespace separated
  double residual_tolerance = 0.005;   ///< [-] largest residual / time-averaged force
  double correction_tolerance = 0.01;  ///< [-] largest correction / largest increment of u
  int max_iterations = 16;
  int max_cutbacks = 5;
  double cutback_factor = 0.25;        ///< dt multiplier after a failed attempt
  double growth_factor = 1.5;          ///< largest dt multiplier after an easy increment
  bool tangent_reuse = false;          ///< "newton": "modified" (solver/newton.hpp TangentReuse)
  double max_contraction = 0.5;        ///< [-] a reused factorization is kept while ||r_k|| <= this ||r_k-1||
};

/// Per-node or per-element values written at every frame to a CSV (ABAQUS *NODE PRINT / *EL PRINT of
/// a deck): `<prefix>_<set>.csv`, one row per node (element) and frame. Node: U [mm] and/or RF [N];
/// element: S = Cauchy stress averaged over the element's integration points [kPa].
struct PrintRequest {
  enum class Kind { node, element } kind = Kind::node;
  std::string set;                      ///< node set (node) or element set (element)
  std::vector<std::string> quantities;  ///< node: "U", "RF"; element: "S"
};

/// A parsed, validated case file.
struct CaseSpec {
  std::filesystem::path file;           ///< the case file as given (for messages)
  std::string description;
  MeshSpec mesh;
  std::filesystem::path material_file;  ///< resolved against the case folder
  std::map<std::string, std::string> sets;  ///< set name -> selector text (syntax checked)
  std::map<std::string, Amplitude> amplitudes;
  std::vector<StepSpec> steps;
  SolverSpec solver;
  std::vector<PrintRequest> prints;  ///< decks only (*NODE PRINT, *EL PRINT)
};

/// History columns of a run (union over steps, in order of first appearance), without "time_s".
std::vector<std::string> history_columns(const CaseSpec& spec);

}  // namespace cushion::solver
