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
/// mid-edge nodes 1-2, 2-3, 3-1, 1-4, 2-4, 3-4).
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
/// Faces are numbered as ABAQUS S1..S6 / S1..S4 (same node sets as the ABAQUS face tables), but the
/// ABAQUS tables list the nodes clockwise seen from outside; here the order is reversed (first node
/// kept): hex8 S1 = 1-4-3-2, S2 = 5-6-7-8, S3 = 1-2-6-5, S4 = 2-3-7-6, S5 = 3-4-8-7, S6 = 4-1-5-8;
/// tets S1 = 1-3-2, S2 = 1-2-4, S3 = 2-3-4, S4 = 3-1-4 (right-hand rule gives the outward normal).
std::vector<int> face_nodes(ElementType type, int face);

/// Faces (element, ABAQUS face number) that belong to exactly one element: the exterior boundary.
/// Faces are matched by their corner nodes; sorted by element then face.
std::vector<Face> boundary_faces(const Mesh& mesh);

/// Volume of element `e` in the reference configuration [mm^3], integrated exactly for straight
/// or curved hex8/tet4/tet10 geometry (det J by Gauss quadrature of sufficient order).
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
