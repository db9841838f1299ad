#pragma once
/// Quadrature rules of the solid elements, with the shape functions (mesh/shape.hpp, ABAQUS node
/// order) tabulated once at every point. Natural coordinates: hexahedra xi in [-1, 1]^3, tets the
/// unit simplex with node 1 at the origin.
#include <vector>

#include <Eigen/Dense>

#include "material/tensor.hpp"
#include "mesh/mesh.hpp"

namespace cushion::solver {

constexpr int max_element_nodes = 20;  ///< hex20
constexpr int max_element_dofs = 3 * max_element_nodes;

/// Per-node column data of one element: column a holds a 3-vector for node a (coordinates [mm],
/// displacements [mm] or shape-function gradients).
using NodeMatrix = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, max_element_nodes>;
/// Shape-function values N_a [-], one entry per element node.
using ShapeValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_element_nodes, 1>;

/// One quadrature point with its tabulated shape functions. Weights sum to the natural volume
/// (8 for the hexahedra, 1/6 for tets).
struct QuadraturePoint {
  Vec3 xi = Vec3::Zero();  ///< natural coordinates
  double weight = 0.0;     ///< natural-volume weight
  ShapeValues N;           ///< N_a(xi) [-]
  NodeMatrix dN_dxi;       ///< column a = dN_a/dxi [-]
};

/// Rule for internal force and stiffness: hex8 2x2x2 Gauss, tet4 1 point, tet10 4 points (degree 2),
/// hex20 (C3D20) 3x3x3 Gauss (full integration), hex20r (C3D20R) 2x2x2 Gauss (reduced integration,
/// as ABAQUS and CalculiX; no hourglass control: a single element has 6 spurious zero-energy modes, a
/// column one element wide 5, a mesh two elements wide in two directions none; tests/solver/test_hex20.cpp).
const std::vector<QuadraturePoint>& stiffness_quadrature(mesh::ElementType type);

/// Rule for the consistent mass matrix: hex8 3x3x3 Gauss; hex20/hex20r 4x4x4 Gauss (N_a N_b has
/// degree 4 per direction, det J up to 5 on curved elements); tets a 4x4x4 collapsed (Duffy) Gauss
/// product rule, exact to polynomial degree 5 (N_a N_b of tet10 is degree 4).
const std::vector<QuadraturePoint>& mass_quadrature(mesh::ElementType type);

/// The element centre (hexahedra xi = 0, tets xi = 1/4), weight 0 (used by F-bar).
const QuadraturePoint& centre_point(mesh::ElementType type);

/// Reference-frame gradients at one point.
struct ReferenceGradients {
  NodeMatrix dN_dX;  ///< column a = dN_a/dX [1/mm], reference frame
  double det_J = 0;  ///< det(dX/dxi) [mm^3 per natural volume]; <= 0 means an inverted element
};

/// dN_a/dX and det(dX/dxi) for reference nodal coordinates X [mm] (column a = node a).
ReferenceGradients reference_gradients(const NodeMatrix& X, const QuadraturePoint& point);

}  // namespace cushion::solver
