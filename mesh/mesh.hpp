#pragma once
/// Mesh data: nodes, elements, node sets, element sets and element-face surfaces. Lengths in mm,
/// reference configuration. Node and element numbering is 0-based internally; readers keep the
/// user's labels for messages and output.
#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace cushion::mesh {

using Vec3 = Eigen::Vector3d;

/// Element types. Node order follows ABAQUS: hex8 = C3D8 (bottom face 1-2-3-4 counter-clockwise seen
/// from outside... i.e. nodes 1-4 at zeta = -1, 5-8 at zeta = +1), tet4 = C3D4, tet10 = C3D10
/// (corners 1-4, then mid-edge nodes 1-2, 2-3, 3-1, 1-4, 2-4, 3-4).
enum class ElementType { hex8, tet4, tet10 };
int nodes_per_element(ElementType type);
int faces_per_element(ElementType type);
std::string to_string(ElementType type);

struct Element {
  ElementType type = ElementType::hex8;
  std::array<int, 10> nodes{};  ///< first nodes_per_element(type) entries used (0-based node indices)
  int label = 0;                ///< user label (1-based in generated meshes)
};

/// An element face, ABAQUS numbering: face = 0..5 for S1..S6 (hex8), 0..3 for S1..S4 (tets).
struct Face {
  int element = 0;
  int face = 0;
};

struct Mesh {
  std::vector<Vec3> nodes;              ///< reference coordinates [mm]
  std::vector<int> node_labels;         ///< user labels, same size as nodes
  std::vector<Element> elements;
  std::map<std::string, std::vector<int>> node_sets;     ///< sorted, unique node indices
  std::map<std::string, std::vector<int>> element_sets;  ///< sorted, unique element indices
  std::map<std::string, std::vector<Face>> surfaces;

  std::size_t num_nodes() const { return nodes.size(); }
  std::size_t num_elements() const { return elements.size(); }
};

/// Local node indices (0-based, into Element::nodes) of face `face` of an element type; corner
/// nodes first (for tet10 faces: 3 corners then 3 mid-edge nodes), ordered so the normal points out.
std::vector<int> face_nodes(ElementType type, int face);

}  // namespace cushion::mesh
