#include "mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <limits>
#include <optional>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/shape.hpp"
#include "mesh/text.hpp"

namespace cushion::mesh {

namespace {


std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? "none" : out;
}

const std::vector<int>& find_element_set(const Mesh& mesh, const std::string& name) {
  const auto it = find_name(mesh.element_sets, name);
  if (it == mesh.element_sets.end()) {
    std::vector<std::string> known;
    for (const auto& entry : mesh.element_sets) known.push_back(entry.first);
    throw InputError("no element set '" + name + "' (element sets: " + join(known) + ")");
  }
  return it->second;
}

// Members mapped by `map` (nullopt: outside the part), in order; names of sets left empty go to `dropped`.
template <class Member, class Map>
std::map<std::string, std::vector<Member>> kept(const std::map<std::string, std::vector<Member>>& sets, Map map,
                                                 std::vector<std::string>& dropped) {
  std::map<std::string, std::vector<Member>> out;
  for (const auto& [name, members] : sets) {
    std::vector<Member> inside;
    for (const Member& m : members)
      if (const auto mapped = map(m)) inside.push_back(*mapped);
    if (inside.empty()) dropped.push_back(name);
    else out[name] = std::move(inside);
  }
  return out;
}

}  // namespace

int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::hex8: return 8;
    case ElementType::tet4: return 4;
    case ElementType::tet10: return 10;
    case ElementType::hex20:
    case ElementType::hex20r: return 20;
  }
  throw std::logic_error("nodes_per_element: unknown element type");
}

bool is_hexahedron(ElementType type) {
  return type == ElementType::hex8 || type == ElementType::hex20 || type == ElementType::hex20r;
}

int faces_per_element(ElementType type) { return is_hexahedron(type) ? 6 : 4; }
int corners_per_face(ElementType type) { return is_hexahedron(type) ? 4 : 3; }
int corners_per_element(ElementType type) { return is_hexahedron(type) ? 8 : 4; }

std::string to_string(ElementType type) {
  switch (type) {
    case ElementType::hex8: return "C3D8";
    case ElementType::tet4: return "C3D4";
    case ElementType::tet10: return "C3D10";
    case ElementType::hex20: return "C3D20";
    case ElementType::hex20r: return "C3D20R";
  }
  throw std::logic_error("to_string: unknown element type");
}

const std::vector<std::array<int, 2>>& mid_edge_corners(ElementType type) {
  // C3D10 nodes 5..10 on edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4; C3D20 nodes 9..20 on edges 1-2, 2-3,
  // 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8 (0-based below).
  static const std::vector<std::array<int, 2>> none, tet10 = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  static const std::vector<std::array<int, 2>> hex20 = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                        {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  if (type == ElementType::tet10) return tet10;
  if (type == ElementType::hex20 || type == ElementType::hex20r) return hex20;
  return none;
}

std::vector<int> face_nodes(ElementType type, int face) {
  // ABAQUS face tables (S1..S6 / S1..S4) with the node order reversed after the first node so that
  // the right-hand rule gives the outward normal; see mesh.hpp. The mid-edge nodes of a quadratic
  // face follow its corners, node k + corners on the edge between corners k and k + 1.
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> hex20 = {
      {0, 3, 2, 1, 11, 10, 9, 8},    {4, 5, 6, 7, 12, 13, 14, 15},  {0, 1, 5, 4, 8, 17, 12, 16},
      {1, 2, 6, 5, 9, 18, 13, 17},   {2, 3, 7, 6, 10, 19, 14, 18},  {3, 0, 4, 7, 11, 16, 15, 19}};
  static const std::vector<std::vector<int>> tet10 = {
      {0, 2, 1, 6, 5, 4}, {0, 1, 3, 4, 8, 7}, {1, 2, 3, 5, 9, 8}, {2, 0, 3, 6, 7, 9}};
  if (face < 0 || face >= faces_per_element(type))
    throw std::out_of_range("face_nodes: face " + std::to_string(face) + " out of range for " +
                            to_string(type));
  switch (type) {
    case ElementType::hex8: return hex[face];
    case ElementType::hex20:
    case ElementType::hex20r: return hex20[face];
    case ElementType::tet10: return tet10[face];
    case ElementType::tet4: break;
  }
  const auto& f = tet10[face];
  return {f[0], f[1], f[2]};
}

std::vector<Face> boundary_faces(const Mesh& mesh) {
  // Key: sorted global corner nodes of a face (padded for triangles); value: first owner and count.
  struct Seen {
    Face face;
    int count = 0;
  };
  std::map<std::array<int, 4>, Seen> faces;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const Element& element = mesh.elements[e];
    for (int f = 0; f < faces_per_element(element.type); ++f) {
      const std::vector<int> local = face_nodes(element.type, f);
      const int corners = corners_per_face(element.type);
      constexpr int kPad = std::numeric_limits<int>::max();
      std::array<int, 4> key{kPad, kPad, kPad, kPad};
      for (int k = 0; k < corners; ++k) key[k] = element.nodes[local[k]];
      std::sort(key.begin(), key.end());
      Seen& seen = faces[key];
      if (seen.count++ == 0) seen.face = Face{e, f};
    }
  }
  std::vector<Face> result;
  for (const auto& [key, seen] : faces)
    if (seen.count == 1) result.push_back(seen.face);
  std::sort(result.begin(), result.end(), [](const Face& a, const Face& b) {
    return a.element != b.element ? a.element < b.element : a.face < b.face;
  });
  return result;
}

double face_area(const Mesh& mesh, const Face& face) {
  const Element& element = mesh.elements.at(face.element);
  const std::vector<int> local = face_nodes(element.type, face.face);
  auto X = [&](int k) -> const Vec3& { return mesh.nodes[element.nodes[local[k]]]; };
  if (corners_per_face(element.type) == 4) return 0.5 * (X(2) - X(0)).cross(X(3) - X(1)).norm();
  return 0.5 * (X(1) - X(0)).cross(X(2) - X(0)).norm();
}

double element_volume(const Mesh& mesh, int e) {
  const ElementType type = mesh.elements.at(e).type;
  double volume = 0.0;
  if (is_hexahedron(type)) {
    // det J of a trilinear map (hex8) has degree <= 2 per direction: 2-point Gauss is exact. For
    // the serendipity map (hex20) dX/dxi_k has degree <= 1 in xi_k and <= 2 in the others, so
    // det J has degree <= 5 per direction: 3-point Gauss is exact.
    const auto rule = gauss_legendre(type == ElementType::hex8 ? 2 : 3);
    for (const auto& a : rule)
      for (const auto& b : rule)
        for (const auto& c : rule)
          volume += a[1] * b[1] * c[1] * reference_jacobian(mesh, e, Vec3(a[0], b[0], c[0])).determinant();
    return volume;
  }
  if (type == ElementType::tet4)
    return reference_jacobian(mesh, e, Vec3(0.25, 0.25, 0.25)).determinant() / 6.0;
  // tet10: det J is a cubic polynomial; the 5-point degree-3 rule (Keast) integrates it exactly.
  volume = -0.8 * reference_jacobian(mesh, e, Vec3(0.25, 0.25, 0.25)).determinant();
  const double p = 1.0 / 6.0, q = 0.5;
  for (const Vec3& xi : {Vec3(p, p, p), Vec3(q, p, p), Vec3(p, q, p), Vec3(p, p, q)})
    volume += 0.45 * reference_jacobian(mesh, e, xi).determinant();
  return volume / 6.0;
}

double min_corner_jacobian(const Mesh& mesh, int e) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Vec3& xi : corner_coordinates(mesh.elements.at(e).type))
    smallest = std::min(smallest, reference_jacobian(mesh, e, xi).determinant());
  return smallest;
}

void check_elements(const Mesh& mesh, const std::string& where) {
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const Element& element = mesh.elements[e];
    const std::string name = where + ": element " + std::to_string(element.label) + " (" +
                             to_string(element.type) + ")";
    for (int a = 0; a < nodes_per_element(element.type); ++a)
      if (element.nodes[a] < 0 || element.nodes[a] >= n_nodes)
        throw InputError(name + ": node index " + std::to_string(element.nodes[a]) +
                         " out of range");
    // Scale-free test: det J relative to the cube of a typical edge length.
    const Vec3 span = mesh.nodes[element.nodes[0]] - mesh.nodes[element.nodes[1]];
    const double scale = std::pow(span.norm(), 3);
    const double detJ = min_corner_jacobian(mesh, e);
    if (!(detJ > 1e-12 * scale))
      throw InputError(name + ": non-positive Jacobian det(dX/dxi) = " + std::to_string(detJ) +
                       " mm^3 at a corner (inverted, degenerate or wrongly ordered nodes)");
  }
}

Mesh element_set_part(const Mesh& mesh, const std::string& elset, std::vector<std::string>* notes) {
  const std::vector<int>& chosen = find_element_set(mesh, elset);
  std::vector<int> element_index(mesh.elements.size(), -1), node_index(mesh.nodes.size(), -1);
  for (int e : chosen) {
    element_index[e] = 0;
    for (int a = 0; a < nodes_per_element(mesh.elements[e].type); ++a) node_index[mesh.elements[e].nodes[a]] = 0;
  }
  Mesh part;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    if (node_index[n] == 0) {
      node_index[n] = static_cast<int>(part.nodes.size());
      part.nodes.push_back(mesh.nodes[n]);
      part.node_labels.push_back(mesh.node_labels[n]);
    }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    if (element_index[e] == 0) {
      element_index[e] = static_cast<int>(part.elements.size());
      Element element = mesh.elements[e];
      for (int a = 0; a < nodes_per_element(element.type); ++a) element.nodes[a] = node_index[element.nodes[a]];
      part.elements.push_back(element);
    }
  auto inside = [](const std::vector<int>& index) {
    return [&index](int i) { return index[i] >= 0 ? std::optional<int>(index[i]) : std::nullopt; };
  };
  std::vector<std::string> dropped;
  part.node_sets = kept(mesh.node_sets, inside(node_index), dropped);
  part.element_sets = kept(mesh.element_sets, inside(element_index), dropped);
  part.surfaces = kept(mesh.surfaces, [&](const Face& f) {
    return element_index[f.element] >= 0 ? std::optional<Face>(Face{element_index[f.element], f.face}) : std::nullopt;
  }, dropped);
  if (notes && !dropped.empty())
    notes->push_back("element set '" + elset + "' kept (" + std::to_string(part.elements.size()) + " of " +
                     std::to_string(mesh.elements.size()) + " elements, " + std::to_string(part.nodes.size()) +
                     " of " + std::to_string(mesh.nodes.size()) + " nodes); sets and surfaces outside it dropped: " +
                     join(dropped));
  return part;
}

}  // namespace cushion::mesh
