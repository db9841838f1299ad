#include "mesh/quadratic.hpp"

#include <algorithm>
#include <stdexcept>

namespace cushion::mesh {

Mesh to_tet10(const Mesh& mesh) {
  // C3D10 mid-edge nodes 5..10 on edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
  static constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  Mesh out = mesh;
  int next_label = 0;
  for (int label : mesh.node_labels) next_label = std::max(next_label, label);
  std::map<std::pair<int, int>, int> mid;  // sorted edge ends -> new node index
  for (Element& element : out.elements) {
    if (element.type != ElementType::tet4)
      throw std::invalid_argument("to_tet10: element " + std::to_string(element.label) + " is " +
                                  to_string(element.type) + ", expected C3D4");
    element.type = ElementType::tet10;
    for (int m = 0; m < 6; ++m) {
      const int a = element.nodes[kEdge[m][0]], b = element.nodes[kEdge[m][1]];
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace({key.first, key.second}, static_cast<int>(out.nodes.size()));
      if (inserted) {
        out.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
        out.node_labels.push_back(++next_label);
      }
      element.nodes[4 + m] = it->second;
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

}  // namespace cushion::mesh
