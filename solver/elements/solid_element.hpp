#pragma once
/// Total-Lagrangian solid element kernels (hex8, hex8 F-bar, tet4, tet10, hex20 = C3D20 with 3x3x3
/// and hex20r = C3D20R with 2x2x2 Gauss points; the rule comes with the element type). A kernel knows nothing of
/// assembly: it maps reference coordinates, nodal displacements, a material and the committed
/// quadrature-point state to the internal force and its consistent tangent. Element DOF order is
/// node-major: dof 3a + i is component i of node a.
///
/// Weak form (reference frame): f_int,a = int_V0 P g_a dV0, g_a = dN_a/dX, P = F S (PK1).
/// F-bar (de Souza Neto et al. 1996): F_bar = (J0/J)^(1/3) F with J0 = det F at the element centre;
/// the material sees F_bar, and the virtual work int sigma(F_bar) : grad(eta) dv gives
/// P = (J/J0)^(1/3) F S(F_bar). Its consistent tangent is unsymmetric.
#include <span>
#include <string>

#include "material/material.hpp"
#include "solver/elements/quadrature.hpp"

namespace cushion::solver {

/// Element vector (3 x nodes entries) and matrix, fixed capacity (no heap allocation).
using ElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_element_dofs, 1>;
using ElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_element_dofs, max_element_dofs>;

/// Kinematic formulation of a solid element.
enum class Formulation {
  full,  ///< standard total Lagrangian, full integration
  fbar   ///< F-bar (hex8 only): volumetric part of F taken at the element centre (locking-free)
};

/// Post-processing values at one quadrature point (at u_new).
struct PointOutput {
  Mat3 F = Mat3::Identity();  ///< deformation gradient seen by the material [-] (F_bar for F-bar)
  Vec6 S = Vec6::Zero();      ///< PK2 stress [MPa], reference frame, Voigt stress order
  Vec6 sigma = Vec6::Zero();  ///< Cauchy stress [MPa], current frame, Voigt stress order
  Vec3 X = Vec3::Zero();      ///< reference position of the point [mm]
  double dV0 = 0.0;           ///< reference volume weight of the point [mm^3]
};

/// Everything one element needs for one evaluation (element DOFs node-major).
struct ElementInput {
  mesh::ElementType type = mesh::ElementType::hex8;
  Formulation formulation = Formulation::full;
  NodeMatrix X;      ///< reference nodal coordinates [mm], column a = node a
  NodeMatrix u_old;  ///< nodal displacements at the start of the increment [mm]
  NodeMatrix u_new;  ///< nodal displacements at the end of the increment [mm]
  const material::Material* material = nullptr;
  std::span<const double> state_old;  ///< committed state, points x state_size doubles (read only)
  std::span<double> state_new;        ///< receives the updated state, same size
  double dt = 0.0;                    ///< time increment [s]
};

/// Internal force, tangent and status of one element.
struct ElementOutput {
  ElementVector f_int;  ///< internal nodal forces [N], node-major
  ElementMatrix K;      ///< consistent tangent d f_int / d u_new [N/mm] (empty if not requested)
  material::Status status = material::Status::ok;  ///< worst point status
  double dt_factor = 1.0;                          ///< smallest point proposal
  int failed_point = -1;                           ///< first failed quadrature point, -1 if none
  std::string message;                             ///< reason of the failure
};

/// Number of stiffness quadrature points of an element type.
int num_points(mesh::ElementType type);

/// Evaluates one element at u_new: f_int [N] and (if want_tangent) K [N/mm]; writes state_new and,
/// if `points` is non-empty (size num_points), the point outputs. Stops at the first failed point.
/// Throws std::invalid_argument for F-bar on a non-hex element.
ElementOutput integrate_element(const ElementInput& in, bool want_tangent, std::span<PointOutput> points = {});

/// Consistent mass matrix M_ab = int rho N_a N_b dV0 I [t], rho in t/mm^3, node-major DOFs.
ElementMatrix consistent_mass(mesh::ElementType type, const NodeMatrix& X, double rho);

/// Reference volume of the element [mm^3].
double element_volume(mesh::ElementType type, const NodeMatrix& X);

}  // namespace cushion::solver
