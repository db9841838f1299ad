#pragma once
/// `cushion run DECK.inp`: an ABAQUS/CalculiX input deck translated into the same LoadedCase (case
/// spec, mesh, material) that a case file gives, so that both run through one analysis path. The
/// supported subset, what is skipped with a warning and what is refused: README "Runs your deck".
/// Every keyword or parameter outside the subset is an InputError
/// "<file>:<line>: keyword *X is not supported by cushion run" (or "parameter P of *X ..."), before
/// anything is built; output-only keywords (*OUTPUT, *NODE OUTPUT, ...) are skipped with a warning.
#include <filesystem>
#include <string>

#include "solver/case/case_file.hpp"

namespace cushion::solver {

/// The consistent unit system a deck is written in (decks carry no units) and its factors to cushion's
/// internal units (mm, N, s, MPa, t/mm^3). Time is in seconds in every system.
struct DeckUnits {
  std::string name = "mm-N-MPa";  ///< "mm-N-MPa" | "m-N-Pa" | "m-kN-kPa" | "mm-kN-GPa" | "in-lbf-psi"
  double length = 1.0;            ///< [mm] per deck length unit
  double force = 1.0;             ///< [N] per deck force unit
  double stress() const { return force / (length * length); }               ///< [MPa] per deck stress unit
  double density() const { return force / length / (length * length * length); }  ///< [t/mm^3] per deck density unit
};

/// The unit system named `name` (one of DeckUnits::name's choices); InputError "--units: ..." otherwise.
DeckUnits deck_units(const std::string& name);

/// Names of every supported unit system, comma separated (for help texts).
std::string deck_unit_names();

/// True if `file` is read as a deck (extension .inp, any case).
bool is_deck_file(const std::filesystem::path& file);

/// Reads the deck `file` (with its *INCLUDEs) in `units` and returns the case it describes, its
/// warnings (skipped output keywords, reinterpreted elements) in LoadedCase::warnings. Runs the same
/// checks as load_case (check_loaded_case). Throws InputError "<file>:<line>: ..." on the first problem.
LoadedCase load_deck(const std::filesystem::path& file, const DeckUnits& units);

}  // namespace cushion::solver
