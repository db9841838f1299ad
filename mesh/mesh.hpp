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

/// Element types. Node order follows ABAQUS: hex8 = C3D8, nodes 1-4 on the bottom face (zeta = -1)
/// and 5-8 on the top face (zeta = +1), each face counter-clockwise seen from +zeta, node 4+i above
/// node i; tet4 = C3D4 with (x2-x1) x (x3-x1) . (x4-x1) > 0; tet10 = C3D10 (corners 1-4, then
/// mid-edge nodes 1-2, 2-3, 3-1, 1-4, 2-4, 3-4); hex20 = C3D20 and hex20r = C3D20R, the 20-node
/// serendipity brick: corners 1-8 as hex8, then mid-edge nodes 9-20 on the edges 1-2, 2-3, 3-4, 4-1,
/// 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8 (CalculiX ccx manual, "Twenty-node brick element (C3D20)",
/// and its face table ifaceq; VTK's vtkQuadraticHexahedron uses the same order). hex20 and hex20r
/// share nodes and shape functions and differ only in the solver's integration rule (3x3x3 / 2x2x2).
enum class ElementType { hex8, tet4, tet10, hex20, hex20r };
int nodes_per_element(ElementType type);
int faces_per_element(ElementType type);
/// Corner nodes of each face: 4 for the hexahedra (quadrilateral faces), 3 for the tetrahedra.
int corners_per_face(ElementType type);
/// True for hex8, hex20 and hex20r (reference cube [-1,1]^3).
bool is_hexahedron(ElementType type);
std::string to_string(ElementType type);
/// Number of corner (vertex) nodes: 8 for the hexahedra, 4 for the tetrahedra.
int corners_per_element(ElementType type);
/// The two corner nodes (0-based local indices) of every mid-edge node of a quadratic type, in node
/// order: entry m belongs to node corners_per_element + m (tet10: 6 entries, hex20/hex20r: 12);
/// empty for hex8 and tet4.
const std::vector<std::array<int, 2>>& mid_edge_corners(ElementType type);

struct Element {
  ElementType type = ElementType::hex8;
  std::array<int, 20> nodes{};  ///< first nodes_per_element(type) entries used (0-based node indices)
  int label = 0;                ///< user label (1-based in generated meshes)
};

/// An element face, ABAQUS numbering: face = 0..5 for S1..S6 (hexahedra), 0..3 for S1..S4 (tets).
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
/// nodes first (tet10 faces: 3 corners then 3 mid-edge nodes; hex20 faces: 4 corners then the 4
/// mid-edge nodes of the edges c0-c1, c1-c2, c2-c3, c3-c0), ordered so the normal points out.
/// Faces are numbered as ABAQUS S1..S6 / S1..S4 (same node sets as the ABAQUS face tables), but the
/// ABAQUS tables list the nodes clockwise seen from outside; here the order is reversed (first node
/// kept): hex8 S1 = 1-4-3-2, S2 = 5-6-7-8, S3 = 1-2-6-5, S4 = 2-3-7-6, S5 = 3-4-8-7, S6 = 4-1-5-8;
/// tets S1 = 1-3-2, S2 = 1-2-4, S3 = 2-3-4, S4 = 3-1-4 (right-hand rule gives the outward normal).
std::vector<int> face_nodes(ElementType type, int face);

/// Faces (element, ABAQUS face number) that belong to exactly one element: the exterior boundary.
/// Faces are matched by their corner nodes; sorted by element then face.
std::vector<Face> boundary_faces(const Mesh& mesh);

/// Area of an element face from its corner nodes in the reference configuration [mm^2]:
/// quadrilaterals half the cross product of the diagonals (exact for planar faces with straight
/// edges), triangles half the cross product of two edges. Mid-edge nodes are ignored (a curved
/// quadratic face gets the area of its corner polygon).
double face_area(const Mesh& mesh, const Face& face);

/// Volume of element `e` in the reference configuration [mm^3], integrated exactly for straight
/// or curved geometry of every type (det J by Gauss quadrature of sufficient order).
double element_volume(const Mesh& mesh, int e);

/// Smallest det(dX/dxi) over the corner nodes of element `e` (reference coordinates xi of
/// ABAQUS: hex [-1,1]^3, tet unit simplex) [mm^3 per unit reference volume].
double min_corner_jacobian(const Mesh& mesh, int e);

/// Throws cushion::InputError naming the first element (by label) whose corner Jacobian is not
/// positive (inverted or degenerate element) or that references a missing node; `where` prefixes
/// the message (e.g. the file name).
void check_elements(const Mesh& mesh, const std::string& where = "mesh");

/// The part of `mesh` made of the elements of element set `elset` (name matched exactly, else
/// ignoring case as ABAQUS does) and the nodes they use, in their original order and with their
/// labels. Node sets, element sets and surfaces keep their members inside that part; sets and
/// surfaces left empty are dropped, named in one line appended to `notes` (if given). Throws
/// cushion::InputError "no element set 'X' (element sets: A, B)" for an unknown set.
Mesh element_set_part(const Mesh& mesh, const std::string& elset, std::vector<std::string>* notes = nullptr);

}  // namespace cushion::mesh
