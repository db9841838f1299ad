#pragma once
/// Reading case files (format: solver/case/case_spec.hpp) and turning a parsed case into the
/// mesh and material the solver runs on. Parsing validates everything first; building comes after.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "material/io/material_file.hpp"
#include "mesh/mesh.hpp"
#include "solver/case/case_spec.hpp"

namespace cushion::solver {

/// Parses case JSON text. `file` names the case in messages and anchors relative paths (mesh and
/// material files must exist). Throws cushion::InputError "<file>: <key.path>: <problem>".
CaseSpec parse_case_json(const std::string& text, const std::filesystem::path& file);

/// Reads and parses a case file (InputError if it cannot be read).
CaseSpec read_case_file(const std::filesystem::path& file);

/// Builds the mesh the case describes (generator, .inp reader or TetGen on an STL), then adds the
/// case's selector sets to mesh.node_sets (a case set replaces a mesh set of the same name; an
/// empty selection is an InputError) and checks that every set a step names exists. Warnings that do
/// not stop the run (keywords an .inp reader skipped, sets outside mesh.elset) go to `warnings`.
mesh::Mesh build_case_mesh(const CaseSpec& spec, std::vector<std::string>* warnings = nullptr);

/// Throws InputError naming the first step key that refers to a node set absent from `node_sets`
/// (boundary, history, contact and steady-state sets).
void check_set_names(const CaseSpec& spec, const std::set<std::string>& node_sets);

/// A case ready to run: spec, mesh with its node sets, material.
struct LoadedCase {
  CaseSpec spec;
  mesh::Mesh mesh;
  material::MaterialDefinition material;
  std::vector<std::string> warnings;  ///< from building the mesh; `cushion run` prints them on stderr
};

/// The checks that need the built mesh and material, run before the first step (nothing is written
/// yet): the sets of steady-state steps are not empty and the measured set has a node driven or held
/// in the excitation's dof; dynamic and steady-state steps have a material with a mass density; a steady-state step's
/// material has a small-amplitude complex tangent (not a power-law air flow).
/// Throws InputError "<case>: <key.path>: <problem>".
void check_loaded_case(const LoadedCase& loaded);

/// read_case_file, then the material file (its errors are prefixed "<case>: material.file: "),
/// then build_case_mesh, then check_loaded_case.
LoadedCase load_case(const std::filesystem::path& file);

}  // namespace cushion::solver
