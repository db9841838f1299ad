#pragma once
/// Conversion of linear meshes to quadratic ones by mid-edge nodes: tet4 (C3D4) to C3D10, hex8 (C3D8)
/// to the 20-node serendipity brick C3D20 / C3D20R.
#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// Returns a copy of `mesh` with every tet4 turned into a straight-sided tet10: one new node at the
/// midpoint of each edge, shared by all elements around the edge (labels continue after the
/// largest node label). A mid-edge node joins a node set when both edge ends are in it; element
/// sets and surfaces (element, face) are unchanged. Throws std::invalid_argument for non-tet4 input.
Mesh to_tet10(const Mesh& mesh);

/// Same for hexahedra: every hex8 becomes a straight-sided `type` (hex20 = C3D20 or hex20r =
/// C3D20R) with its 12 mid-edge nodes in ABAQUS order. Throws std::invalid_argument for non-hex8
/// input or a `type` that is not hex20/hex20r.
Mesh to_hex20(const Mesh& mesh, ElementType type = ElementType::hex20);

}  // namespace cushion::mesh
