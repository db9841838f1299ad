#pragma once
/// Isoparametric shape functions of the mesh element types, in ABAQUS node order. Reference
/// coordinates xi: hexahedra in [-1,1]^3, tets in the unit simplex (xi, eta, zeta >= 0, sum <= 1)
/// with node 1 at the origin and nodes 2, 3, 4 on the xi, eta, zeta axes.
///
/// hex20 / hex20r (20-node serendipity brick, Zienkiewicz & Taylor, The Finite Element Method,
/// vol. 1, sec. "Serendipity family"; CalculiX's shape20h): with xi_a the reference coordinates of
/// node a,
///   corner a:        N_a = 1/8 (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a)(xi xi_a + eta eta_a + zeta zeta_a - 2)
///   mid-edge a with xi_a = 0 (likewise for eta, zeta):
///                    N_a = 1/4 (1 - xi^2)(1 + eta eta_a)(1 + zeta zeta_a).
#include <array>
#include <vector>

#include <Eigen/Dense>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// Shape function values N_a(xi), a = 0..nodes_per_element-1 [-].
Eigen::VectorXd shape_values(ElementType type, const Vec3& xi);

/// Shape function gradients dN_a/dxi (row a, column = reference direction) [-].
Eigen::MatrixXd shape_gradients(ElementType type, const Vec3& xi);

/// Reference coordinates of the corner nodes (8 for the hexahedra, 4 for tets) [-].
std::vector<Vec3> corner_coordinates(ElementType type);

/// Reference coordinates of all nodes, in node order (corners, then mid-edge nodes at the middle of
/// their edge) [-].
std::vector<Vec3> node_coordinates(ElementType type);

/// n-point Gauss-Legendre rule on [-1, 1] (n = 2, 3, 4): {abscissa, weight}; exact for polynomials
/// of degree 2n - 1.
std::vector<std::array<double, 2>> gauss_legendre(int n);

/// Jacobian dX/dxi (3x3, column j = dX/dxi_j) of element `e` at xi, reference configuration [mm].
Eigen::Matrix3d reference_jacobian(const Mesh& mesh, int e, const Vec3& xi);

}  // namespace cushion::mesh
