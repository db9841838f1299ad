#pragma once
/// Contact of a rigid indenter frozen at the base state, for steady-state dynamics (small harmonic
/// perturbations about a converged contact state, solver/contact/contact_set.hpp for the forces).
///
/// Every node k that is CLOSED at the base state (normal force t_N > 0 at the last evaluation)
/// keeps its contact: the force on the node is linearised about the base state,
///   dF_k = -K_k (du_k - e dw),   K_k = eps_k grad g grad g^T - t_N H_g   [N/mm]
/// (eps_k = penalty x tributary area, g the gap, H_g its Hessian at the base position: the exact
/// derivative of the static contact force, so the normal direction "sticks" through a spring eps_k),
/// dw the indenter's translation along the unit direction e (one appended DOF). Open nodes stay open.
/// Tangentially (choice, documented): frictionless contact slides freely (no tangential stiffness
/// beyond the curvature term); with friction (mu > 0) every closed node STICKS, adding the
/// tangential penalty spring eps_T P (P = I - n n^T, n = grad g / |grad g|, eps_T = tangential
/// penalty x area), whether it was sticking or slipping at the base state: the vibration amplitude
/// (micrometres) is assumed below the slip limit mu t_N / eps_T. Contact is not Rayleigh damped.
///
/// The reaction on the indenter DOF of the linear system is the e-component of the summed spring
/// forces on the foam, sum_k e . K_k (e w - u_k) [N], i.e. the force the support applies to the
/// indenter (negative when the foam pushes the indenter back along +e).
#include <complex>
#include <vector>

#include "solver/contact/contact_set.hpp"

namespace cushion::solver::dynamics {

/// The frozen contact of one indenter.
struct ContactLinearisation {
  std::vector<Eigen::Triplet<double>> stiffness;  ///< contributions to the n x n stiffness [N/mm]
  std::vector<int> closed;                        ///< indices k (into set.nodes()) of closed nodes
  std::vector<Mat3> node_stiffness;               ///< K_k per closed node [N/mm], base-state frame
  double closed_area = 0.0;                       ///< tributary area of the closed nodes [mm^2]
};

/// Linearises `set` (built on `mesh`) at its last evaluation (the converged base state; u_base =
/// full displacements [mm] of that state). indenter_dof: index of the appended DOF of the indenter translation along
/// the unit vector `e` (< 0: indenter fixed, node blocks only). Throws std::runtime_error if the
/// stored gaps do not belong to u_base and the set's position (the contact was not part of the
/// base state's equilibrium).
ContactLinearisation linearise_contact(const mesh::Mesh& mesh, const ContactSet& set, const Eigen::VectorXd& u_base,
                                       int indenter_dof, const Vec3& e);

/// Summed force of the frozen springs on the foam [N] for nodal displacements u (full, complex) and
/// indenter translation w along e [mm]: sum_k -K_k (u_k - e w).
Eigen::Vector3cd contact_spring_force(const ContactSet& set, const ContactLinearisation& lin,
                                      const Eigen::VectorXcd& u, std::complex<double> w, const Vec3& e);

}  // namespace cushion::solver::dynamics
