// Contact of a deck with rigid bodies (deck_parts.hpp): *RIGID BODY, *SURFACE INTERACTION, *SURFACE
// BEHAVIOR, *FRICTION, *CONTACT PAIR, and finish_contacts, which turns them into the contacts of a case:
// the elements of a rigid body leave the mesh, its master surface's element faces become a rigid
// facet surface (IndenterSpec::Type::facets) that translates with the prescribed displacement of the
// reference node, and the slave surface's nodes are the contact's node set. cushion's contact is
// node-to-rigid-surface, so every pair needs a rigid master; rigid bodies only translate.
#include <algorithm>
#include <map>
#include <set>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/text.hpp"
#include "solver/deck/deck_parts.hpp"

namespace cushion::solver::deck {

namespace {

State::Interaction& current_interaction(State& s, const Block& b) {
  if (s.current_interaction.empty()) fail(b, b.keyword, "must follow a *SURFACE INTERACTION");
  return s.interactions.at(s.current_interaction);
}

void model_data_only(const State& s, const Block& b) {
  if (s.step) fail(b, b.keyword, "must come before the first *STEP (contact is model data in cushion run)");
}

/// Node index of a label that must exist (the label is checked when the keyword is read).
int node_of(const State& s, int label) { return s.node_index.at(label); }

/// Reference and rotation nodes of the rigid bodies: node index -> (body, is the reference node).
using RigidNodes = std::map<int, std::pair<int, bool>>;

RigidNodes rigid_nodes(const State& s) {
  RigidNodes out;
  for (std::size_t r = 0; r < s.rigid_bodies.size(); ++r) {
    out[node_of(s, s.rigid_bodies[r].ref)] = {static_cast<int>(r), true};
    if (s.rigid_bodies[r].rot) out[node_of(s, s.rigid_bodies[r].rot)] = {static_cast<int>(r), false};
  }
  return out;
}

/// Per element: the rigid body whose element set holds it, or -1.
std::vector<int> rigid_body_of_elements(const State& s) {
  std::vector<int> out(s.out.mesh.num_elements(), -1);
  for (std::size_t r = 0; r < s.rigid_bodies.size(); ++r)
    for (int e : s.out.mesh.element_sets.at(s.rigid_bodies[r].elset)) out[e] = static_cast<int>(r);
  return out;
}

/// The facets of surface `faces` (corner nodes; quadrilaterals split along the diagonal c0-c2), in mm,
/// normals pointing out of the elements (mesh::face_nodes order).
mesh::TriangleSurface facets(const mesh::Mesh& mesh, const std::vector<mesh::Face>& faces) {
  mesh::TriangleSurface out;
  std::map<int, int> vertex;
  auto v = [&](int node) {
    const auto [it, fresh] = vertex.try_emplace(node, static_cast<int>(out.vertices.size()));
    if (fresh) out.vertices.push_back(mesh.nodes[node]);
    return it->second;
  };
  for (const mesh::Face& f : faces) {
    const mesh::Element& e = mesh.elements[f.element];
    const std::vector<int> local = mesh::face_nodes(e.type, f.face);
    std::vector<int> c;
    for (int k = 0; k < mesh::corners_per_face(e.type); ++k) c.push_back(v(e.nodes[local[k]]));
    out.triangles.push_back({c[0], c[1], c[2]});
    if (c.size() == 4) out.triangles.push_back({c[0], c[2], c[3]});
  }
  return out;
}

/// Sorted, unique nodes of the faces (corner and mid-edge nodes).
std::vector<int> face_node_set(const mesh::Mesh& mesh, const std::vector<mesh::Face>& faces) {
  std::set<int> nodes;
  for (const mesh::Face& f : faces)
    for (int k : mesh::face_nodes(mesh.elements[f.element].type, f.face)) nodes.insert(mesh.elements[f.element].nodes[k]);
  return {nodes.begin(), nodes.end()};
}

/// Motion of one rigid body in one step, from the *BOUNDARY conditions on its reference node.
struct Motion {
  Vec3 translation = Vec3::Zero();
  std::optional<std::string> amplitude;
  std::array<bool, 3> given{false, false, false};
};

/// Removes from `step` the conditions on the rigid bodies' reference and rotation nodes and returns the
/// motion of each body; InputError where a body is not driven by displacement or would rotate.
std::vector<Motion> take_rigid_motions(const State& s, StepSpec& step, const mesh::Mesh& mesh,
                                       const RigidNodes& special) {
  std::vector<Motion> out(s.rigid_bodies.size());
  std::vector<std::array<bool, 3>> rotation_held(s.rigid_bodies.size(), {false, false, false});
  std::vector<BoundarySpec> kept;
  for (const BoundarySpec& bc : step.boundary) {
    const std::vector<int>& nodes = mesh.node_sets.at(bc.set);
    const auto n_special = std::count_if(nodes.begin(), nodes.end(), [&](int n) { return special.count(n); });
    if (n_special == 0) {
      kept.push_back(bc);
      continue;
    }
    if (n_special != static_cast<long>(nodes.size()))
      throw InputError(bc.key + ": *BOUNDARY: node set " + bc.set +
                       " mixes reference nodes of rigid bodies with other nodes; give them separate conditions");
    for (int n : nodes) {
      const auto [r, is_ref] = special.at(n);
      for (int c = 0; c < 3; ++c) {
        if (!bc.dofs[c]) continue;
        if (is_ref) {
          Motion& m = out[r];
          if (m.given[c] && m.amplitude != bc.amplitude)
            throw InputError(bc.key + ": *BOUNDARY: the translations of rigid body " + s.rigid_bodies[r].elset +
                             " use different amplitudes; cushion moves a rigid body along one amplitude");
          if (bc.amplitude) m.amplitude = bc.amplitude;
          m.translation[c] = bc.value, m.given[c] = true;
        } else {
          if (bc.value != 0.0)
            throw InputError(bc.key + ": *BOUNDARY: a rotation of rigid body " + s.rigid_bodies[r].elset +
                             " is prescribed; cushion's rigid bodies only translate (hold ROT NODE at 0)");
          rotation_held[r][c] = true;
        }
      }
    }
  }
  step.boundary = kept;
  for (std::size_t r = 0; r < s.rigid_bodies.size(); ++r) {
    const State::RigidBody& rb = s.rigid_bodies[r];
    const bool driven = out[r].given[0] && out[r].given[1] && out[r].given[2];
    const bool held = rb.rot && rotation_held[r][0] && rotation_held[r][1] && rotation_held[r][2];
    if (!driven || !held)
      throw InputError(where(rb.defined) + ": *RIGID BODY: in step " + step.name + " the three translations of REF NODE " + std::to_string(rb.ref) +
               " must be prescribed by *BOUNDARY and the three dofs of ROT NODE held at 0: cushion moves rigid "
               "bodies by prescribed displacement only (no free or rotating rigid bodies)");
  }
  for (const LoadSpec& load : step.loads)
    for (int n : mesh.node_sets.at(load.set))
      if (special.count(n))
        throw InputError(load.key + ": *CLOAD: a force on a rigid body's node; cushion moves rigid bodies by "
                                    "prescribed displacement only");
  return out;
}

/// Print requests of sets made of rigid bodies' nodes only are dropped with a note (the contact CSV holds the
/// motion and force); other sets print their deformable nodes.
void drop_rigid_prints(State& s, const RigidNodes& special) {
  auto& prints = s.out.spec.prints;
  for (auto it = prints.begin(); it != prints.end();) {
    const std::vector<int>* nodes = it->kind == PrintRequest::Kind::node ? &s.out.mesh.node_sets.at(it->set) : nullptr;
    if (nodes && std::all_of(nodes->begin(), nodes->end(), [&](int n) { return special.count(n); })) {
      s.out.warnings.push_back(s.file.string() + ": *NODE PRINT of set " + it->set +
                               " (a rigid body's node): its motion and contact force are in contact_<surface>.csv "
                               "(force of the indenter on the foam, equal to CalculiX's RF at the reference node)");
      it = prints.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace

void rigid_body(State& s, const Block& b) {
  check_parameters(b, {"ELSET", "REF NODE", "ROT NODE"});
  model_data_only(s, b);
  State::RigidBody rb;
  rb.defined = b.keyword;
  rb.elset = element_set(s, b, b.keyword, required_parameter(b, "ELSET"));
  for (const State::RigidBody& other : s.rigid_bodies)
    if (other.elset == rb.elset) fail(b, b.keyword, "element set " + rb.elset + " is already a rigid body");
  auto label = [&](const std::string& key) {
    const int n = integer(b, b.keyword, required_parameter(b, key));
    if (!s.node_index.count(n)) fail(b, b.keyword, key + " " + std::to_string(n) + " is not a defined node");
    return n;
  };
  rb.ref = label("REF NODE");
  if (parameter(b, "ROT NODE")) rb.rot = label("ROT NODE");
  s.rigid_bodies.push_back(rb);
}

void surface_interaction(State& s, const Block& b) {
  check_parameters(b, {"NAME"});
  model_data_only(s, b);
  const std::string name = io::upper_case(required_parameter(b, "NAME"));
  if (s.interactions.count(name)) fail(b, b.keyword, "interaction " + name + " is defined twice");
  s.interactions[name] = {b.keyword, {}};
  s.current_interaction = name;
}

void surface_behavior(State& s, const Block& b) {
  check_parameters(b, {"PRESSURE-OVERCLOSURE"});
  ContactParameters& p = current_interaction(s, b).parameters;
  const std::string law = io::upper_case(parameter(b, "PRESSURE-OVERCLOSURE").value_or("HARD"));
  if (law == "HARD") {
    if (!b.data.empty()) fail(b, b.data.front(), "HARD takes no data line");
    p.augmented = true;
    return;
  }
  if (law != "LINEAR") fail(b, b.keyword, "PRESSURE-OVERCLOSURE must be HARD or LINEAR in cushion run");
  // slope K [stress/length], then CalculiX's tension at large clearance and its c0 (cushion's law carries no tension).
  if (b.data.size() != 1) fail(b, b.keyword, "expected one data line 'slope K[, sigma_inf, c0]'");
  const std::vector<std::string> f = mesh::inp_fields(b.data.front().text);
  const double K = number(b, b.data.front(), f.front());
  if (!(K > 0.0)) fail(b, b.data.front(), "the slope K must be > 0");
  p.penalty = K * s.units.stress() / s.units.length;
  p.tangential_penalty = 0.1 * p.penalty;
  p.augmented = false;
}

void friction(State& s, const Block& b) {
  check_parameters(b, {});
  ContactParameters& p = current_interaction(s, b).parameters;
  if (b.data.size() != 1) fail(b, b.keyword, "expected one data line 'mu[, stick slope]'");
  const std::vector<std::string> f = mesh::inp_fields(b.data.front().text);
  if (f.size() > 2) fail(b, b.data.front(), "expected 'mu[, stick slope]'");
  p.friction = number(b, b.data.front(), f[0]);
  if (!(p.friction >= 0.0)) fail(b, b.data.front(), "mu must be >= 0");
  if (f.size() == 2 && !f[1].empty()) {
    const double slope = number(b, b.data.front(), f[1]);
    if (!(slope > 0.0)) fail(b, b.data.front(), "the stick slope must be > 0");
    p.tangential_penalty = slope * s.units.stress() / s.units.length;
  }
}

void contact_pair(State& s, const Block& b) {
  check_parameters(b, {"INTERACTION", "TYPE"});
  model_data_only(s, b);
  const std::string interaction = io::upper_case(required_parameter(b, "INTERACTION"));
  if (!s.interactions.count(interaction)) fail(b, b.keyword, "unknown interaction " + interaction);
  const std::string type = io::upper_case(parameter(b, "TYPE").value_or("NODE TO SURFACE"));
  if (type != "NODE TO SURFACE" && type != "SURFACE TO SURFACE")
    fail(b, b.keyword, "TYPE must be NODE TO SURFACE or SURFACE TO SURFACE");
  if (type == "SURFACE TO SURFACE")
    s.out.warnings.push_back(where(b.keyword) + ": *CONTACT PAIR: TYPE=SURFACE TO SURFACE solved node to surface "
                                                "(cushion's contact is node to rigid surface)");
  if (b.data.empty()) fail(b, b.keyword, "no data line 'slave surface, master surface'");
  for (const Line& line : b.data) {
    const std::vector<std::string> f = mesh::inp_fields(line.text);
    if (f.size() != 2 || f[0].empty() || f[1].empty()) fail(b, line, "expected 'slave surface, master surface'");
    for (const std::string& name : f)
      if (mesh::find_name(s.out.mesh.surfaces, name) == s.out.mesh.surfaces.end())
        fail(b, line, "unknown surface '" + name + "' (give it with *SURFACE, TYPE=ELEMENT)");
    s.contact_pairs.push_back({line, mesh::find_name(s.out.mesh.surfaces, f[0])->first,
                               mesh::find_name(s.out.mesh.surfaces, f[1])->first, interaction});
  }
}

void finish_contacts(State& s) {
  if (s.rigid_bodies.empty() && s.contact_pairs.empty()) return;
  const mesh::Mesh& whole = s.out.mesh;
  const std::vector<int> body_of = rigid_body_of_elements(s);
  const RigidNodes special = rigid_nodes(s);
  // Each pair: a rigid master surface (one body), a deformable slave surface.
  std::vector<int> body_of_pair;
  std::vector<std::shared_ptr<const mesh::TriangleSurface>> pair_facets;
  for (const State::ContactPair& pair : s.contact_pairs) {
    const Block block{pair.defined, "CONTACT PAIR", {}, {}};
    int body = -2;
    for (const mesh::Face& f : whole.surfaces.at(pair.master)) {
      const int r = body_of[f.element];
      if (r < 0 || (body >= 0 && r != body))
        fail(block, pair.defined, "the master surface " + pair.master +
                                      " must lie on the elements of one *RIGID BODY: cushion's contact is against "
                                      "rigid surfaces only");
      body = r;
    }
    for (const mesh::Face& f : whole.surfaces.at(pair.slave))
      if (body_of[f.element] >= 0)
        fail(block, pair.defined, "the slave surface " + pair.slave + " lies on a rigid body");
    body_of_pair.push_back(body);
    pair_facets.push_back(std::make_shared<const mesh::TriangleSurface>(facets(whole, whole.surfaces.at(pair.master))));
  }
  // Motions (from conditions on the reference nodes), before the mesh loses those nodes.
  std::vector<std::vector<Motion>> motions;
  for (StepSpec& step : s.out.spec.steps) motions.push_back(take_rigid_motions(s, step, whole, special));
  drop_rigid_prints(s, special);
  // Sections on rigid bodies carry no material into the run.
  std::vector<State::Section> sections;
  for (const State::Section& section : s.sections) {
    const std::vector<int>& els = whole.element_sets.at(section.elset);
    const auto n_rigid = std::count_if(els.begin(), els.end(), [&](int e) { return body_of[e] >= 0; });
    if (n_rigid == 0) sections.push_back(section);
    else if (n_rigid != static_cast<long>(els.size()))
      throw InputError(where(section.defined) + ": *SOLID SECTION: element set " + section.elset +
                       " mixes rigid-body and deformable elements");
  }
  s.sections = sections;
  // The deformable part.
  std::vector<int> deformable;
  for (std::size_t e = 0; e < body_of.size(); ++e)
    if (body_of[e] < 0) deformable.push_back(static_cast<int>(e));
  if (deformable.empty()) throw InputError(s.file.string() + ": every element belongs to a *RIGID BODY: nothing deforms");
  for (int e : deformable)
    for (int k = 0; k < mesh::nodes_per_element(whole.elements[e].type); ++k) {
      const int node = whole.elements[e].nodes[k];
      const auto it = special.find(node);
      if (it != special.end())
        throw InputError(where(s.rigid_bodies[it->second.first].defined) +
                         ": *RIGID BODY: its reference or rotation node " + std::to_string(whole.node_labels[node]) +
                         " belongs to the deformable element " + std::to_string(whole.elements[e].label) +
                         "; give the rigid body nodes of its own");
    }
  s.out.mesh.element_sets["#deformable"] = deformable;
  std::vector<std::string> notes;
  mesh::Mesh part = mesh::element_set_part(s.out.mesh, "#deformable", &notes);
  part.element_sets.erase("#deformable");
  s.out.mesh = std::move(part);
  for (const std::string& n : notes) s.out.warnings.push_back(s.file.string() + ": rigid bodies removed from the mesh: " + n);
  // One contact per pair in every static, visco and dynamic step.
  for (std::size_t k = 0; k < s.contact_pairs.size(); ++k) {
    const State::ContactPair& pair = s.contact_pairs[k];
    const std::string set = "#contact " + pair.slave;
    s.out.mesh.node_sets[set] = face_node_set(s.out.mesh, s.out.mesh.surfaces.at(pair.slave));
    for (std::size_t i = 0; i < s.out.spec.steps.size(); ++i) {
      StepSpec& step = s.out.spec.steps[i];
      if (step.perturbation()) continue;
      const Motion& m = motions[i][body_of_pair[k]];
      ContactSpec c;
      c.name = pair.master;
      c.set = set;
      c.indenter.type = IndenterSpec::Type::facets;
      c.indenter.facets = pair_facets[k];
      c.indenter.facets_name = "surface " + pair.master + " of rigid body " + s.rigid_bodies[body_of_pair[k]].elset;
      c.motion = m.translation;
      c.amplitude = m.amplitude;
      c.parameters = s.interactions.at(pair.interaction).parameters;
      c.key = where(pair.defined);
      step.contact.push_back(std::move(c));
    }
  }
}

}  // namespace cushion::solver::deck
