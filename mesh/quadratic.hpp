#pragma once
/// Conversion of a linear tetrahedral mesh (C3D4) to quadratic C3D10 by mid-edge nodes.
#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// Returns a copy of `mesh` with every tet4 turned into a straight-sided tet10: one new node at the
/// midpoint of each edge, shared by all elements around the edge (labels continue after the
/// largest node label). A mid-edge node joins a node set when both edge ends are in it; element
/// sets and surfaces (element, face) are unchanged. Throws std::invalid_argument for non-tet4 input.
Mesh to_tet10(const Mesh& mesh);

}  // namespace cushion::mesh
