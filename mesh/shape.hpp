#pragma once
/// Isoparametric shape functions of the mesh element types, in ABAQUS node order. Reference
/// coordinates xi: hex8 in [-1,1]^3, tets in the unit simplex (xi, eta, zeta >= 0, sum <= 1) with
/// node 1 at the origin and nodes 2, 3, 4 on the xi, eta, zeta axes.
#include <Eigen/Dense>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// Shape function values N_a(xi), a = 0..nodes_per_element-1 [-].
Eigen::VectorXd shape_values(ElementType type, const Vec3& xi);

/// Shape function gradients dN_a/dxi (row a, column = reference direction) [-].
Eigen::MatrixXd shape_gradients(ElementType type, const Vec3& xi);

/// Reference coordinates of the corner nodes (8 for hex8, 4 for tets) [-].
std::vector<Vec3> corner_coordinates(ElementType type);

/// Jacobian dX/dxi (3x3, column j = dX/dxi_j) of element `e` at xi, reference configuration [mm].
Eigen::Matrix3d reference_jacobian(const Mesh& mesh, int e, const Vec3& xi);

}  // namespace cushion::mesh
