#pragma once
/// Internal to solver/deck: the translation state and the keyword handlers (one per keyword, after
/// CalculiX's reader). deck_reader.cpp dispatches, deck_material.cpp reads materials and sections,
/// deck_step.cpp steps, boundary conditions, loads and output requests.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mesh/inp_reader.hpp"
#include "solver/deck/deck_reader.hpp"

namespace cushion::solver::deck {

using Block = mesh::InpBlock;
using Line = mesh::InpLine;

/// "<file>:<line>"
std::string where(const Line& line);
/// InputError "<file>:<line>: *KEY: problem".
[[noreturn]] void fail(const Block& block, const Line& line, const std::string& problem);
/// InputError "<file>:<line>: keyword *KEY is not supported by cushion run".
[[noreturn]] void unsupported_keyword(const Block& block);
/// InputError "<file>:<line>: parameter P of *KEY is not supported by cushion run" for the first
/// parameter of `block` not in `allowed`.
void check_parameters(const Block& block, const std::vector<std::string>& allowed);
/// Value of parameter `key` ("" if given without value), or nullopt.
std::optional<std::string> parameter(const Block& block, const std::string& key);
/// Value of a required parameter (InputError "missing KEY=" otherwise).
std::string required_parameter(const Block& block, const std::string& key);
/// Finite number / whole number of one field of a data line (InputError naming the line otherwise).
double number(const Block& block, const Line& line, const std::string& field);
int integer(const Block& block, const Line& line, const std::string& field);
/// The first `count` numbers of the block's data lines read in order across lines (ABAQUS: 8 per
/// line); empty fields read as 0. A further non-empty field (temperature) or a further data line
/// (temperature dependence) is refused.
std::vector<double> packed_numbers(const Block& block, std::size_t count);

/// A material being read (*MATERIAL and the option keywords after it).
struct DeckMaterial {
  std::string name;  ///< as written
  Line defined;      ///< the *MATERIAL line
  material::MaterialSpec spec;
  bool has_base = false;    ///< a *HYPERFOAM or *HYPERELASTIC was read
  bool has_prony = false;   ///< a *VISCOELASTIC was read
  std::optional<Line> moduli;  ///< where MODULI= was given (with *VISCOELASTIC only)
  std::optional<Line> elastic; ///< where *ELASTIC gave the base (read as its small-strain neo-Hooke)
  std::optional<Line> damping; ///< where *DAMPING gave `damping` (used by steady-state steps)
  Damping damping_values;      ///< *DAMPING ALPHA (mass), BETA (stiffness), STRUCTURAL
};

/// Everything read so far.
struct State {
  std::filesystem::path file;
  DeckUnits units;
  LoadedCase out;  ///< spec (steps, amplitudes, prints), mesh (read first), material (at the end)
  std::map<std::string, DeckMaterial> materials;  ///< by upper-case name
  std::string current_material;                   ///< upper-case name while material options may follow
  struct Section {
    Line defined;
    std::string elset, material;  ///< canonical element set, upper-case material name
  };
  std::vector<Section> sections;
  std::vector<BoundarySpec> boundary;  ///< in effect (model data, then changed by each step)
  std::vector<LoadSpec> loads;         ///< in effect
  std::vector<PressureSpec> pressures; ///< in effect (start_value: at the start of the open step)
  std::optional<std::size_t> step;     ///< index in out.spec.steps of the open *STEP
  bool procedure = false;              ///< the open step has its *STATIC / *VISCO
  std::map<int, int> node_index;       ///< node label -> index
  /// *RIGID BODY: the elements of `elset` move rigidly with node `ref` (labels); `rot` holds rotations.
  struct RigidBody {
    Line defined;
    std::string elset;
    int ref = 0, rot = 0;  ///< node labels (rot 0: not given)
  };
  std::vector<RigidBody> rigid_bodies;
  std::map<std::string, std::vector<double>> time_points;  ///< *TIME POINTS by upper-case name [s of step time]
  /// *SURFACE INTERACTION with its *SURFACE BEHAVIOR and *FRICTION.
  struct Interaction {
    Line defined;
    ContactParameters parameters;
  };
  std::map<std::string, Interaction> interactions;  ///< by upper-case name
  std::string current_interaction;                  ///< upper-case name while its options may follow
  /// *CONTACT PAIR: slave (foam) surface, master (rigid) surface, interaction (upper case).
  struct ContactPair {
    Line defined;
    std::string slave, master, interaction;
  };
  std::vector<ContactPair> contact_pairs;
};

/// Node-set name for a data-line entry: a node label (a one-node set "#node <label>" is added to the
/// mesh) or the name of a node set (case-insensitive, its name as defined).
std::string node_target(State& s, const Block& block, const Line& line, const std::string& field);
/// Element set by name, case-insensitive (its name as defined).
std::string element_set(State& s, const Block& block, const Line& line, const std::string& name);

// Handlers (deck_material.cpp).
void material(State& s, const Block& b);
void hyperfoam(State& s, const Block& b);
void hyperelastic(State& s, const Block& b);
void viscoelastic(State& s, const Block& b);
void density(State& s, const Block& b);
void solid_section(State& s, const Block& b);
/// The case's material after every block: the one material of the sections, covering every element.
void finish_material(State& s);
void elastic(State& s, const Block& b);
void damping(State& s, const Block& b);

// Handlers (deck_contact.cpp).
void rigid_body(State& s, const Block& b);
void surface_interaction(State& s, const Block& b);
void surface_behavior(State& s, const Block& b);
void friction(State& s, const Block& b);
void contact_pair(State& s, const Block& b);
/// After every block, before finish_material: the rigid bodies' elements and reference nodes leave the
/// mesh, each contact pair becomes a contact of every step (the master surface's facets as a rigid
/// indenter moved by the reference node's prescribed displacement), sections on rigid bodies are dropped.
void finish_contacts(State& s);

// Handlers (deck_step.cpp).
void amplitude(State& s, const Block& b);
void boundary(State& s, const Block& b);
void cload(State& s, const Block& b);
void dload(State& s, const Block& b);
void step(State& s, const Block& b);
void static_procedure(State& s, const Block& b);
void visco_procedure(State& s, const Block& b);
void dynamic_procedure(State& s, const Block& b);
void frequency_procedure(State& s, const Block& b);
void steady_state_procedure(State& s, const Block& b);
void end_step(State& s, const Block& b);
void node_print(State& s, const Block& b);
void el_print(State& s, const Block& b);
void result_file(State& s, const Block& b);
void time_points(State& s, const Block& b);
/// After finish_contacts: a steady-state step holds the DOFs of the conditions in effect in it.
void finish_steps(State& s);

}  // namespace cushion::solver::deck
