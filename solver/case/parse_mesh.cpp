// The "mesh" part of the case grammar (case_spec.hpp): structured block, ABAQUS .inp or TetGen STL.
#include <cmath>

#include "io/text_support.hpp"
#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

constexpr double kMaxGeneratedCells = 1e7;  ///< case_spec.hpp: generate.elements

mesh::ElementType element_type(const std::string& name) {
  if (name == "hex8") return mesh::ElementType::hex8;
  if (name == "tet4") return mesh::ElementType::tet4;
  return mesh::ElementType::tet10;
}

mesh::AxisGrading parse_axis_grading(const Obj& o) {
  mesh::AxisGrading g;
  g.ratio = o.positive("ratio");
  g.kind = mesh::AxisGrading::Kind::geometric;
  if (o.has("focus_mm")) {
    g.kind = mesh::AxisGrading::Kind::focus;
    g.focus = o.number("focus_mm");
  }
  return g;
}

void parse_grading(const Obj& o, GenerateMeshSpec& g) {
  const Obj grading = o.child("grading", {"x", "y", "z"});
  const char* axes[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    if (!grading.has(axes[axis])) continue;
    const Obj a = grading.child(axes[axis], {"ratio", "focus_mm"});
    g.grading[axis] = parse_axis_grading(a);
    if (g.grading[axis].kind == mesh::AxisGrading::Kind::focus &&
        (g.grading[axis].focus < g.low[axis] || g.grading[axis].focus > g.high[axis]))
      a.fail("focus_mm", "must lie inside the box along " + std::string(axes[axis]));
  }
}

GenerateMeshSpec parse_generate(const Obj& o) {
  GenerateMeshSpec g;
  g.type = element_type(o.choice("type", {"hex8", "tet4", "tet10"}));
  const auto box = o.numbers("box_mm", 6, 6);
  for (int axis = 0; axis < 3; ++axis) {
    g.low[axis] = box[2 * axis];
    g.high[axis] = box[2 * axis + 1];
    if (!(g.low[axis] < g.high[axis]))
      o.fail("box_mm", "must be [x0, x1, y0, y1, z0, z1] with x0 < x1, y0 < y1, z0 < z1");
  }
  const io::JsonNode n = o.at("elements");
  n.expect_array(3, 3);
  for (int axis = 0; axis < 3; ++axis) {
    const double x = n[axis].number();
    if (x != std::floor(x) || x < 1 || x > 1e6) n[axis].fail("must be an integer >= 1");
    g.elements[axis] = static_cast<int>(x);
  }
  // Bounded so that a case file cannot ask for a mesh that exhausts memory (1e6^3 cells was accepted).
  const double cells = double(g.elements[0]) * g.elements[1] * g.elements[2];
  if (cells > kMaxGeneratedCells)
    o.fail("elements", "nx * ny * nz must be <= 1e7 cells, found " + io::format_double(cells));
  if (o.has("grading")) parse_grading(o, g);
  return g;
}

StlMeshSpec parse_stl(const Obj& o) {
  StlMeshSpec stl;
  stl.file = o.file("stl");
  stl.max_volume = o.positive("max_volume_mm3");
  stl.quadratic = o.choice_or("type", {"tet4", "tet10"}, "tet4") == "tet10";
  stl.max_radius_edge = o.positive_or("max_radius_edge", 1.5);
  stl.min_dihedral = o.has("min_dihedral_deg") ? o.number("min_dihedral_deg") : 0.0;
  if (stl.min_dihedral < 0.0 || stl.min_dihedral >= 70.0) o.fail("min_dihedral_deg", "must be in [0, 70) degrees");
  return stl;
}

}  // namespace

MeshSpec parse_mesh(const Obj& o) {
  MeshSpec m;
  const int sources = int(o.has("generate")) + int(o.has("inp")) + int(o.has("stl"));
  if (sources != 1) o.fail_here("must contain exactly one of \"generate\", \"inp\", \"stl\"");
  bool hex_possible = true;
  if (o.has("generate")) {
    m.source = MeshSpec::Source::generate;
    m.generate = parse_generate(o.child("generate", {"type", "box_mm", "elements", "grading"}));
    hex_possible = m.generate.type == mesh::ElementType::hex8;
  } else if (o.has("inp")) {
    m.source = MeshSpec::Source::inp;
    m.inp_file = o.file("inp");
    if (o.has("elset")) m.inp_elset = o.string("elset");
    if (o.has("elset") && m.inp_elset.empty()) o.fail("elset", "must name an element set of the .inp file");
  } else {
    m.source = MeshSpec::Source::stl;
    hex_possible = false;
    m.stl = parse_stl(o);
  }
  if (o.has("elset") && !o.has("inp")) o.fail("elset", "is an option of \"inp\" meshes only");
  if (o.has("type") && !o.has("stl")) o.fail("type", "is an option of \"stl\" meshes (use generate.type)");
  for (const char* k : {"max_volume_mm3", "max_radius_edge", "min_dihedral_deg"})
    if (o.has(k) && !o.has("stl")) o.fail(k, "is an option of \"stl\" meshes only");
  m.formulation = o.choice_or("formulation", {"full", "fbar"}, "full") == "fbar" ? HexFormulation::fbar
                                                                                 : HexFormulation::full;
  if (m.formulation == HexFormulation::fbar && !hex_possible)
    o.fail("formulation", "\"fbar\" applies to hex8 elements only");
  return m;
}

}  // namespace cushion::solver::case_parse
