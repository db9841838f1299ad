#include "mesh/quadratic.hpp"

#include <algorithm>
#include <stdexcept>

namespace cushion::mesh {
namespace {

// Adds the mid-edge nodes of `to` (mid_edge_corners) to every element of type `from`.
Mesh add_mid_edge_nodes(const Mesh& mesh, ElementType from, ElementType to) {
  const auto& edges = mid_edge_corners(to);
  const int corners = corners_per_element(to);
  Mesh out = mesh;
  int next_label = 0;
  for (int label : mesh.node_labels) next_label = std::max(next_label, label);
  std::map<std::pair<int, int>, int> mid;  // sorted edge ends -> new node index
  for (Element& element : out.elements) {
    if (element.type != from)
      throw std::invalid_argument("to_" + std::string(to == ElementType::tet10 ? "tet10" : "hex20") + ": element " +
                                  std::to_string(element.label) + " is " + to_string(element.type) + ", expected " +
                                  to_string(from));
    element.type = to;
    for (std::size_t m = 0; m < edges.size(); ++m) {
      const int a = element.nodes[edges[m][0]], b = element.nodes[edges[m][1]];
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace({key.first, key.second}, static_cast<int>(out.nodes.size()));
      if (inserted) {
        out.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
        out.node_labels.push_back(++next_label);
      }
      element.nodes[corners + m] = it->second;
    }
  }
  for (auto& [name, nodes] : out.node_sets) {
    std::vector<char> member(mesh.nodes.size(), 0);
    for (int n : nodes) member[n] = 1;
    for (const auto& [edge, node] : mid)
      if (member[edge.first] && member[edge.second]) nodes.push_back(node);
    std::sort(nodes.begin(), nodes.end());
  }
  return out;
}

}  // namespace

Mesh to_tet10(const Mesh& mesh) { return add_mid_edge_nodes(mesh, ElementType::tet4, ElementType::tet10); }

Mesh to_hex20(const Mesh& mesh, ElementType type) {
  if (type != ElementType::hex20 && type != ElementType::hex20r)
    throw std::invalid_argument("to_hex20: target type must be C3D20 or C3D20R, got " + to_string(type));
  return add_mid_edge_nodes(mesh, ElementType::hex8, type);
}

}  // namespace cushion::mesh
