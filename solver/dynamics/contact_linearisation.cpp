#include "solver/dynamics/contact_linearisation.hpp"

#include <cmath>
#include <stdexcept>

namespace cushion::solver::dynamics {

ContactLinearisation linearise_contact(const mesh::Mesh& mesh, const ContactSet& set, const Eigen::VectorXd& u_base,
                                       int indenter_dof, const Vec3& e) {
  ContactLinearisation lin;
  const auto& nodes = set.nodes();
  const auto& t_N = set.normal_force_magnitudes();
  const auto& gaps = set.gaps();
  const auto& areas = set.areas();
  const ContactParameters& p = set.parameters();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (!(t_N[k] > 0.0)) continue;
    const int a = nodes[k];
    const Vec3 y = mesh.nodes[a] + u_base.segment<3>(3 * a) - set.position();
    const GapPoint gp = set.surface().gap(y);
    if (std::abs(gp.g - gaps[k]) > 1e-8 * (1.0 + std::abs(gaps[k])))
      throw std::runtime_error("contact '" + set.name() + "': its last evaluation is not the base state (gap " +
                               std::to_string(gaps[k]) + " mm stored, " + std::to_string(gp.g) + " mm now)");
    const double eps = p.penalty * areas[k];
    Mat3 K = eps * gp.grad * gp.grad.transpose() - t_N[k] * gp.hess;
    if (p.friction > 0.0) {
      const Vec3 n = gp.grad.normalized();
      K += p.tangential_penalty * areas[k] * (Mat3::Identity() - n * n.transpose());
    }
    lin.closed.push_back(static_cast<int>(k));
    lin.node_stiffness.push_back(K);
    lin.closed_area += areas[k];
    const Vec3 Ke = K * e;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        if (K(i, j) != 0.0) lin.stiffness.emplace_back(3 * a + i, 3 * a + j, K(i, j));
      if (indenter_dof < 0 || Ke(i) == 0.0) continue;
      lin.stiffness.emplace_back(3 * a + i, indenter_dof, -Ke(i));
      lin.stiffness.emplace_back(indenter_dof, 3 * a + i, -(e.transpose() * K)(i));
    }
    if (indenter_dof >= 0) lin.stiffness.emplace_back(indenter_dof, indenter_dof, e.dot(Ke));
  }
  return lin;
}

Eigen::Vector3cd contact_spring_force(const ContactSet& set, const ContactLinearisation& lin,
                                      const Eigen::VectorXcd& u, std::complex<double> w, const Vec3& e) {
  Eigen::Vector3cd F = Eigen::Vector3cd::Zero();
  for (std::size_t i = 0; i < lin.closed.size(); ++i) {
    const int a = set.nodes()[lin.closed[i]];
    const Eigen::Vector3cd du = u.segment<3>(3 * a) - w * e.cast<std::complex<double>>();
    F -= lin.node_stiffness[i].cast<std::complex<double>>() * du;
  }
  return F;
}

}  // namespace cushion::solver::dynamics
