#include <algorithm>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/inp_reader.hpp"
#include "mesh/quadratic.hpp"
#include "mesh/selectors.hpp"
#include "mesh/stl.hpp"
#include "mesh/tetgen_mesher.hpp"
#include "solver/case/case_file.hpp"

namespace cushion::solver {

namespace {

// The .inp mesh, or the part of it in mesh.elset; warnings (ignored keywords, dropped sets) to `warnings`.
mesh::Mesh read_inp_mesh(const CaseSpec& spec, std::vector<std::string>* warnings) {
  const MeshSpec& m = spec.mesh;
  mesh::Mesh all = mesh::read_inp(m.inp_file.string(), warnings);
  if (m.inp_elset.empty()) return all;
  try {
    return mesh::element_set_part(all, m.inp_elset, warnings);
  } catch (const InputError& e) {
    throw InputError(spec.file.string() + ": mesh.elset: " + e.what() + " in " + m.inp_file.string());
  }
}

mesh::Mesh build_raw_mesh(const CaseSpec& spec, std::vector<std::string>* warnings) {
  const MeshSpec& m = spec.mesh;
  switch (m.source) {
    case MeshSpec::Source::generate: {
      mesh::BlockSpec block;
      block.low = m.generate.low;
      block.high = m.generate.high;
      block.n = m.generate.elements;
      block.grading = m.generate.grading;
      block.type = m.generate.type == mesh::ElementType::hex8 ? mesh::ElementType::hex8 : mesh::ElementType::tet4;
      mesh::Mesh out = mesh::structured_block(block);
      return m.generate.type == mesh::ElementType::tet10 ? mesh::to_tet10(out) : out;
    }
    case MeshSpec::Source::inp:
      return read_inp_mesh(spec, warnings);
    case MeshSpec::Source::stl: {
      mesh::TetgenOptions options;
      options.max_volume = m.stl.max_volume;
      options.quadratic = m.stl.quadratic;
      options.max_radius_edge = m.stl.max_radius_edge;
      options.min_dihedral = m.stl.min_dihedral;
      return mesh::tetgen_surface(mesh::read_stl(m.stl.file.string()), options,
                                  spec.file.string() + ": mesh.stl");
    }
  }
  throw std::logic_error("build_raw_mesh: unknown mesh source");
}

}  // namespace

mesh::Mesh build_case_mesh(const CaseSpec& spec, std::vector<std::string>* warnings) {
  mesh::Mesh out = build_raw_mesh(spec, warnings);
  if (spec.mesh.formulation == HexFormulation::fbar &&
      std::any_of(out.elements.begin(), out.elements.end(),
                  [](const mesh::Element& e) { return e.type != mesh::ElementType::hex8; }))
    throw InputError(spec.file.string() + ": mesh.formulation: \"fbar\" needs a mesh of hex8 elements only");
  for (const auto& [name, text] : spec.sets) {
    const std::string where = spec.file.string() + ": sets." + name;
    std::vector<int> nodes = mesh::select_nodes(out, mesh::parse_selector(text, where));
    if (nodes.empty()) throw InputError(where + ": selector '" + text + "' selects no node");
    out.node_sets[name] = std::move(nodes);
  }
  std::set<std::string> names;
  for (const auto& [name, ignored] : out.node_sets) names.insert(name);
  check_set_names(spec, names);
  return out;
}

LoadedCase load_case(const std::filesystem::path& file) {
  LoadedCase loaded;
  loaded.spec = read_case_file(file);
  try {
    loaded.material = material::read_material_file(loaded.spec.material_file);
  } catch (const InputError& e) {
    throw InputError(file.string() + ": material.file: " + e.what());
  }
  loaded.mesh = build_case_mesh(loaded.spec, &loaded.warnings);
  check_loaded_case(loaded);
  return loaded;
}

}  // namespace cushion::solver
