// Unit systems of decks (deck_reader.hpp).
#include <algorithm>
#include <cctype>
#include <vector>

#include "io/input_error.hpp"
#include "solver/deck/deck_reader.hpp"

namespace cushion::solver {

namespace {

/// Consistent systems: stress = force / length^2, mass = force s^2 / length.
const std::vector<DeckUnits>& systems() {
  static const std::vector<DeckUnits> all = {{"mm-N-MPa", 1.0, 1.0},
                                             {"m-N-Pa", 1000.0, 1.0},
                                             {"m-kN-kPa", 1000.0, 1000.0},
                                             {"mm-kN-GPa", 1.0, 1000.0},
                                             {"in-lbf-psi", 25.4, 4.4482216152605}};
  return all;
}

}  // namespace

std::string deck_unit_names() {
  std::string names;
  for (const DeckUnits& u : systems()) names += (names.empty() ? "" : ", ") + u.name;
  return names;
}

DeckUnits deck_units(const std::string& name) {
  for (const DeckUnits& u : systems())
    if (u.name == name) return u;
  throw InputError("--units: unknown unit system '" + name + "' (choose one of " + deck_unit_names() + ")");
}

bool is_deck_file(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".inp";
}

}  // namespace cushion::solver
