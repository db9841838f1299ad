// Checks of a case against its built mesh and material (case_file.hpp): everything that depends only
// on the input files, raised before the first step runs.
#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "solver/case/case_file.hpp"

namespace cushion::solver {

namespace {

/// Every (set, key) a step names.
std::vector<std::pair<std::string, std::string>> step_set_names(const StepSpec& step, std::size_t s) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const BoundarySpec& bc : step.boundary) out.emplace_back(bc.set, bc.key + ".set");
  const auto& history = step.output.history;
  for (std::size_t h = 0; h < history.size(); ++h)
    out.emplace_back(history[h].set, "steps[" + std::to_string(s) + "].output.history[" + std::to_string(h) + "].set");
  for (const ContactSpec& c : step.contact) out.emplace_back(c.set, c.key + ".set");
  if (step.type != StepSpec::Type::steady_state) return out;
  const SteadyStateSpec& ss = step.steady_state;
  if (!ss.excitation.set.empty()) out.emplace_back(ss.excitation.set, ss.excitation.key + ".set");
  for (const SetDofs& h : ss.held) out.emplace_back(h.set, h.key + ".set");
  if (!ss.measure.empty()) out.emplace_back(ss.measure, ss.key + ".measure");
  return out;
}

/// Nodes of a set of `mesh` (checked by check_set_names); InputError at `key` if it has none.
const std::vector<int>& set_nodes(const LoadedCase& c, const std::string& set, const std::string& key) {
  const std::vector<int>& nodes = c.mesh.node_sets.at(set);
  if (nodes.empty()) throw InputError(c.spec.file.string() + ": " + key + ": set \"" + set + "\" has no nodes");
  return nodes;
}

/// The sets of a steady-state step are not empty and the measured set has a node driven or held in
/// the excitation's component (driven nodes are never held).
void check_steady_state_sets(const LoadedCase& c, const SteadyStateSpec& s) {
  std::vector<int> driven;
  if (!s.excitation.set.empty()) driven = set_nodes(c, s.excitation.set, s.excitation.key + ".set");
  std::vector<int> held;  // in the excitation's component
  for (const SetDofs& h : s.held) {
    const std::vector<int>& nodes = set_nodes(c, h.set, h.key + ".set");
    if (h.dofs[s.component()]) held.insert(held.end(), nodes.begin(), nodes.end());
  }
  if (s.measure.empty()) return;
  const std::vector<int>& measured = set_nodes(c, s.measure, s.key + ".measure");
  if (s.measure == s.excitation.set) return;
  std::sort(driven.begin(), driven.end());
  std::sort(held.begin(), held.end());
  for (int n : measured)
    if (std::binary_search(held.begin(), held.end(), n) && !std::binary_search(driven.begin(), driven.end(), n)) return;
  throw InputError(c.spec.file.string() + ": " + s.key + ".measure: set \"" + s.measure +
                   "\" is neither driven nor held in the excitation's dof");
}

/// Dynamic and steady-state steps need the material's mass density.
void check_density(const LoadedCase& c, const StepSpec& step) {
  if (c.material.spec.density > 0.0) return;
  const bool dynamic = step.type == StepSpec::Type::dynamic, frequency = step.type == StepSpec::Type::frequency;
  if (!dynamic && !step.perturbation()) return;
  const std::string& key = dynamic ? step.dynamic.key : frequency ? step.frequency.key : step.steady_state.key;
  throw InputError(c.spec.file.string() + ": " + key + ": a " +
                   (dynamic ? "dynamic" : frequency ? "frequency" : "steady_state") +
                   " step needs the mass density of material \"" + c.material.spec.name + "\" (give density_kg_m3 in " +
                   c.spec.material_file.string() + ")");
}

/// A steady-state step linearises the material about its preload (Material::complex_tangent); a material without a
/// small-amplitude tangent (a power-law air flow) is refused here, before anything is written.
void check_linearisable(const LoadedCase& c, const StepSpec& step) {
  if (step.type != StepSpec::Type::steady_state) return;
  try {
    c.material.model->complex_tangent(Mat3::Identity(), 2.0 * std::numbers::pi);
  } catch (const std::invalid_argument& e) {
    throw InputError(c.spec.file.string() + ": " + step.steady_state.key + ": the steady_state step cannot linearise "
                     "material \"" + c.material.spec.name + "\" (" + c.spec.material_file.string() + "): " + e.what());
  }
}

}  // namespace

void check_set_names(const CaseSpec& spec, const std::set<std::string>& node_sets) {
  const std::vector<std::string> known(node_sets.begin(), node_sets.end());
  for (std::size_t s = 0; s < spec.steps.size(); ++s)
    for (const auto& [set, key] : step_set_names(spec.steps[s], s))
      if (!node_sets.count(set))
        throw InputError(spec.file.string() + ": " + key + ": unknown node set \"" + set + "\"" +
                         io::did_you_mean(set, known));
}

void check_loaded_case(const LoadedCase& loaded) {
  std::set<std::string> names;
  for (const auto& [name, ignored] : loaded.mesh.node_sets) names.insert(name);
  check_set_names(loaded.spec, names);
  for (const StepSpec& step : loaded.spec.steps) {
    check_density(loaded, step);
    check_linearisable(loaded, step);
    if (step.type == StepSpec::Type::steady_state) check_steady_state_sets(loaded, step.steady_state);
  }
}

}  // namespace cushion::solver
