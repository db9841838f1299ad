// The deck runner's top level (deck_reader.hpp): shared helpers, the keyword table and load_deck.
#include "solver/deck/deck_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/text.hpp"
#include "solver/deck/deck_parts.hpp"

namespace cushion::solver {

namespace deck {

std::string where(const Line& line) { return line.file + ":" + std::to_string(line.number); }

void fail(const Block& block, const Line& line, const std::string& problem) {
  throw InputError(where(line) + ": *" + block.name + ": " + problem);
}

void unsupported_keyword(const Block& block) {
  throw InputError(where(block.keyword) + ": keyword *" + block.name + " is not supported by cushion run");
}

void check_parameters(const Block& block, const std::vector<std::string>& allowed) {
  for (const auto& [key, value] : block.options)
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      throw InputError(where(block.keyword) + ": parameter " + key + " of *" + block.name +
                       " is not supported by cushion run");
}

std::optional<std::string> parameter(const Block& block, const std::string& key) {
  const auto it = block.options.find(key);
  if (it == block.options.end()) return std::nullopt;
  return it->second;
}

std::string required_parameter(const Block& block, const std::string& key) {
  const auto value = parameter(block, key);
  if (!value || value->empty()) fail(block, block.keyword, "missing " + key + "=");
  return *value;
}


double number(const Block& block, const Line& line, const std::string& field) {
  const std::optional<double> value = io::parse_finite_number(field);
  if (!value) fail(block, line, "bad number '" + field + "'");
  return *value;
}

int integer(const Block& block, const Line& line, const std::string& field) {
  const double x = number(block, line, field);
  if (x != std::floor(x) || std::abs(x) > 2147483647.0) fail(block, line, "bad integer '" + field + "'");
  return static_cast<int>(x);
}

std::vector<double> packed_numbers(const Block& block, std::size_t count) {
  std::vector<double> out;
  std::size_t line = 0;
  for (; line < block.data.size() && out.size() < count; ++line) {
    const std::vector<std::string> f = mesh::inp_fields(block.data[line].text);
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (out.size() < count) {
        out.push_back(f[k].empty() ? 0.0 : number(block, block.data[line], f[k]));
      } else if (!f[k].empty()) {
        fail(block, block.data[line], "more than " + std::to_string(count) +
                                          " values: temperature-dependent data is not supported by cushion run");
      }
    }
  }
  if (out.size() < count)
    fail(block, block.data.empty() ? block.keyword : block.data.back(),
         "expected " + std::to_string(count) + " values, found " + std::to_string(out.size()));
  if (line < block.data.size())
    fail(block, block.data[line], "further data lines (temperature dependence) are not supported by cushion run");
  return out;
}

std::string node_target(State& s, const Block& block, const Line& line, const std::string& field) {
  if (field.empty()) fail(block, line, "missing node or node set");
  if (std::isdigit(static_cast<unsigned char>(field[0])) || field[0] == '-') {
    const int label = integer(block, line, field);
    const auto it = s.node_index.find(label);
    if (it == s.node_index.end()) fail(block, line, "undefined node label " + field);
    const std::string name = "#node " + std::to_string(label);
    s.out.mesh.node_sets[name] = {it->second};
    return name;
  }
  const auto it = mesh::find_name(s.out.mesh.node_sets, field);
  if (it == s.out.mesh.node_sets.end()) fail(block, line, "unknown node set '" + field + "'");
  return it->first;
}

std::string element_set(State& s, const Block& block, const Line& line, const std::string& name) {
  const auto it = mesh::find_name(s.out.mesh.element_sets, name);
  if (it == s.out.mesh.element_sets.end()) fail(block, line, "unknown element set '" + name + "'");
  return it->first;
}

}  // namespace deck

namespace {

using deck::Block;
using deck::State;

using Handler = void (*)(State&, const Block&);

/// Mesh keywords: read by mesh::mesh_from_inp_blocks; here only their parameters are checked.
const std::map<std::string, std::vector<std::string>>& mesh_keywords() {
  static const std::map<std::string, std::vector<std::string>> table = {{"NODE", {"NSET"}},
                                                                        {"ELEMENT", {"TYPE", "ELSET"}},
                                                                        {"NSET", {"NSET", "GENERATE", "ELSET"}},
                                                                        {"ELSET", {"ELSET", "GENERATE"}},
                                                                        {"SURFACE", {"NAME", "TYPE"}}};
  return table;
}

/// Keywords of the analysis, each with its handler.
const std::map<std::string, Handler>& handlers() {
  static const std::map<std::string, Handler> table = {
      {"MATERIAL", deck::material},       {"HYPERFOAM", deck::hyperfoam},   {"HYPERELASTIC", deck::hyperelastic},
      {"VISCOELASTIC", deck::viscoelastic}, {"DENSITY", deck::density},   {"SOLID SECTION", deck::solid_section},
      {"AMPLITUDE", deck::amplitude},     {"BOUNDARY", deck::boundary},     {"CLOAD", deck::cload},
      {"DLOAD", deck::dload},
      {"STEP", deck::step},               {"STATIC", deck::static_procedure}, {"VISCO", deck::visco_procedure},
      {"END STEP", deck::end_step},       {"NODE PRINT", deck::node_print}, {"EL PRINT", deck::el_print},
      {"NODE FILE", deck::result_file},   {"EL FILE", deck::result_file},   {"ELASTIC", deck::elastic},
      {"RIGID BODY", deck::rigid_body},   {"SURFACE INTERACTION", deck::surface_interaction},
      {"SURFACE BEHAVIOR", deck::surface_behavior}, {"FRICTION", deck::friction},
      {"CONTACT PAIR", deck::contact_pair}, {"TIME POINTS", deck::time_points},
      {"FREQUENCY", deck::frequency_procedure}, {"DYNAMIC", deck::dynamic_procedure}, {"STEADY STATE DYNAMICS", deck::steady_state_procedure},
      {"DAMPING", deck::damping}};
  return table;
}

/// Output-only keywords: skipped with a warning (they change no result cushion computes).
bool output_only(const std::string& name) {
  static const std::vector<std::string> names = {
      "HEADING",     "PREPRINT",       "RESTART",    "OUTPUT",       "NODE OUTPUT", "ELEMENT OUTPUT",
      "CONTACT OUTPUT", "ENERGY OUTPUT", "MONITOR",  "FILE FORMAT",  "CONTACT PRINT", "CONTACT FILE",
      "SECTION PRINT", "PRINT"};
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// Material option keywords: they keep the current *MATERIAL open; any other keyword closes it.
bool material_option(const std::string& name) {
  return name == "HYPERFOAM" || name == "HYPERELASTIC" || name == "VISCOELASTIC" || name == "DENSITY" ||
         name == "ELASTIC" || name == "DAMPING";
}

/// Solution controls: skipped with a warning (cushion's own increment and convergence control decide
/// how the answer is reached, not what it is).
bool solution_control(const std::string& name) { return name == "CONTROLS"; }

void dispatch(State& s, const Block& b, std::map<std::string, int>& skipped) {
  if (!material_option(b.name) && b.name != "MATERIAL") s.current_material.clear();
  if (b.name != "SURFACE BEHAVIOR" && b.name != "FRICTION") s.current_interaction.clear();
  const auto mesh_keyword = mesh_keywords().find(b.name);
  if (mesh_keyword != mesh_keywords().end()) {
    deck::check_parameters(b, mesh_keyword->second);
    if (s.step) deck::fail(b, b.keyword, "mesh keywords must come before the first *STEP");
    return;
  }
  const auto handler = handlers().find(b.name);
  if (handler != handlers().end()) return handler->second(s, b);
  if (solution_control(b.name)) {
    if (skipped[b.name]++ == 0)
      s.out.warnings.push_back(deck::where(b.keyword) + ": keyword *" + b.name +
                               " skipped (solution controls: cushion's increment and convergence control apply; "
                               "case-file keys \"solver\" and \"increment\")");
    return;
  }
  if (!output_only(b.name)) deck::unsupported_keyword(b);
  if (skipped[b.name]++ == 0)
    s.out.warnings.push_back(deck::where(b.keyword) + ": keyword *" + b.name +
                             " skipped (output only; cushion writes its own outputs: README \"Runs your deck\")");
}

}  // namespace

LoadedCase load_deck(const std::filesystem::path& file, const DeckUnits& units) {
  const std::vector<Block> blocks = mesh::read_inp_blocks(file.string());
  State s;
  s.file = file;
  s.units = units;
  s.out.spec.file = file;
  s.out.spec.mesh.source = MeshSpec::Source::inp;
  s.out.spec.mesh.inp_file = file;
  // The mesh first (sets may be defined after the keywords that use them, as ABAQUS allows for *NSET).
  s.out.mesh = mesh::mesh_from_inp_blocks(blocks, file.string(), &s.out.warnings, false);
  for (mesh::Vec3& x : s.out.mesh.nodes) x *= units.length;
  for (std::size_t i = 0; i < s.out.mesh.node_labels.size(); ++i)
    s.node_index[s.out.mesh.node_labels[i]] = static_cast<int>(i);
  std::map<std::string, int> skipped;
  for (const Block& b : blocks) dispatch(s, b, skipped);
  if (s.step) deck::fail(blocks.back(), blocks.back().keyword, "the last *STEP has no *END STEP");
  if (s.out.spec.steps.empty()) throw InputError(file.string() + ": the deck has no *STEP: nothing to run");
  deck::finish_contacts(s);
  deck::finish_steps(s);
  deck::finish_material(s);
  std::set<std::string> node_sets;
  for (const auto& [name, nodes] : s.out.mesh.node_sets) node_sets.insert(name);
  check_set_names(s.out.spec, node_sets);
  check_loaded_case(s.out);
  return std::move(s.out);
}

}  // namespace cushion::solver
