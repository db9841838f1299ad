#pragma once
/// The parts of the case-file grammar (internal to solver/case; the format: case_spec.hpp). Each
/// parser reads one object through case_parse::Obj and returns a validated plain struct; names of
/// sets and amplitudes are checked against what the case defines before the step.
#include <string>

#include "solver/case/case_object.hpp"
#include "solver/case/case_spec.hpp"

namespace cushion::solver::case_parse {

/// "mesh" (generate | inp | stl, formulation).
MeshSpec parse_mesh(const Obj& o);

/// "sets": name -> selector text, syntax checked (mesh/selectors.hpp).
std::map<std::string, std::string> parse_sets(const Obj& top);

/// "amplitudes": tabular or sine amplitudes by name.
std::map<std::string, Amplitude> parse_amplitudes(const Obj& top);

/// One element of "steps" (`spec` holds the sets, amplitudes and the steps before it).
StepSpec parse_step(const Obj& o, const CaseSpec& spec);

/// One element of a step's "contact" list (`step` holds the contacts before it).
ContactSpec parse_contact(const Obj& o, const CaseSpec& spec, const StepSpec& step);

/// The "damping" and "newmark" keys of a "dynamic" step.
DynamicSpec parse_dynamic(const Obj& step);

/// The optional "damping" object of a step (dynamic: `structural_allowed` false; steady_state: true).
Damping parse_damping(const Obj& step, bool structural_allowed);

/// The "steady_state" object of a "steady_state" step.
SteadyStateSpec parse_steady_state(const Obj& o, const CaseSpec& spec);

/// "solver" options.
SolverSpec parse_solver(const Obj& o);

/// Throws InputError at `o.key` unless `set` is a set of the case (a mesh read from .inp may define
/// more: its *NSET names are checked once the mesh is built). `hint` ends the message.
void check_set_defined(const Obj& o, const std::string& key, const std::string& set, const CaseSpec& spec,
                       const std::string& hint = "define it under \"sets\"");

/// Throws InputError at `o.key` unless `name` is an amplitude of the case.
void check_amplitude_defined(const Obj& o, const std::string& key, const std::string& name, const CaseSpec& spec);

}  // namespace cushion::solver::case_parse
