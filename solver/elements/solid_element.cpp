#include "solver/elements/solid_element.hpp"

#include <cmath>
#include <stdexcept>

namespace cushion::solver {
namespace {

using material::Status;
using StrainMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, max_element_dofs>;

/// Deformation gradient F = I + sum_a u_a (x) dN_a/dX [-].
Mat3 deformation_gradient(const NodeMatrix& u, const NodeMatrix& dN_dX) {
  return Mat3::Identity() + u * dN_dX.transpose();
}

/// B such that dE_voigt = B du (engineering shear): dE = sym(F^T Grad du).
StrainMatrix strain_displacement(const Mat3& F, const NodeMatrix& dN_dX) {
  const int n = static_cast<int>(dN_dX.cols());
  StrainMatrix B(6, 3 * n);
  for (int a = 0; a < n; ++a) {
    const Vec3 g = dN_dX.col(a);
    for (int i = 0; i < 3; ++i) {
      const int c = 3 * a + i;
      B(0, c) = F(i, 0) * g(0);
      B(1, c) = F(i, 1) * g(1);
      B(2, c) = F(i, 2) * g(2);
      B(3, c) = F(i, 0) * g(1) + F(i, 1) * g(0);
      B(4, c) = F(i, 1) * g(2) + F(i, 2) * g(1);
      B(5, c) = F(i, 0) * g(2) + F(i, 2) * g(0);
    }
  }
  return B;
}

/// Spatial gradients h_a = F^{-T} g_a flattened node-major: d(det F)/du = det F * h.
ElementVector flattened_spatial_gradients(const Mat3& F, const NodeMatrix& dN_dX) {
  const NodeMatrix h = F.inverse().transpose() * dN_dX;
  return Eigen::Map<const ElementVector>(h.data(), h.size());
}

ElementOutput failure(ElementOutput out, int point, std::string message) {
  out.status = Status::failed;
  out.failed_point = point;
  out.message = std::move(message);
  return out;
}

}  // namespace

int num_points(mesh::ElementType type) { return static_cast<int>(stiffness_quadrature(type).size()); }

ElementOutput integrate_element(const ElementInput& in, bool want_tangent, std::span<PointOutput> points) {
  const bool fbar = in.formulation == Formulation::fbar;
  if (fbar && in.type != mesh::ElementType::hex8)
    throw std::invalid_argument("F-bar formulation is available for hex8 elements only");
  const int n = mesh::nodes_per_element(in.type);
  const int ndof = 3 * n;
  const auto& rule = stiffness_quadrature(in.type);
  const std::size_t ns = in.material->state_size();

  ElementOutput out;
  out.f_int.setZero(ndof);
  if (want_tangent) out.K.setZero(ndof, ndof);

  // F-bar: J0 = det F at the centre (old and new), and d(ln J0)/du.
  double J0_new = 1.0, J0_old = 1.0;
  ElementVector h0;
  if (fbar) {
    const auto centre = reference_gradients(in.X, centre_point(in.type));
    const Mat3 F0_new = deformation_gradient(in.u_new, centre.dN_dX);
    J0_new = F0_new.determinant();
    J0_old = deformation_gradient(in.u_old, centre.dN_dX).determinant();
    if (!(J0_new > 0.0) || !(J0_old > 0.0)) return failure(out, 0, "F-bar: det F <= 0 at the element centre");
    h0 = flattened_spatial_gradients(F0_new, centre.dN_dX);
  }

  for (std::size_t q = 0; q < rule.size(); ++q) {
    const auto grad = reference_gradients(in.X, rule[q]);
    if (!(grad.det_J > 0.0)) return failure(out, static_cast<int>(q), "inverted or degenerate reference element");
    const double dV0 = rule[q].weight * grad.det_J;
    const Mat3 F_new = deformation_gradient(in.u_new, grad.dN_dX);
    const Mat3 F_old = deformation_gradient(in.u_old, grad.dN_dX);

    // alpha = (J0/J)^(1/3): F_bar = alpha F (alpha = 1 for the full formulation).
    double alpha = 1.0, alpha_old = 1.0;
    if (fbar) {
      const double J_new = F_new.determinant(), J_old = F_old.determinant();
      if (!(J_new > 0.0) || !(J_old > 0.0)) return failure(out, static_cast<int>(q), "det F <= 0");
      alpha = std::cbrt(J0_new / J_new);
      alpha_old = std::cbrt(J0_old / J_old);
    }
    const Mat3 Fm_new = alpha * F_new;

    const auto state_old = in.state_old.subspan(q * ns, ns);
    const auto state_new = in.state_new.subspan(q * ns, ns);
    const auto response = in.material->integrate(alpha_old * F_old, Fm_new, in.dt, state_old, state_new);
    if (response.status == Status::failed) return failure(out, static_cast<int>(q), response.message);
    if (response.status == Status::unreliable && out.status == Status::ok) {
      out.status = Status::unreliable;
      out.message = response.message;
    }
    out.dt_factor = std::min(out.dt_factor, response.dt_factor);

    // f_a = int (1/alpha) F S g_a dV0 = int (1/alpha) B_a^T S dV0.
    const StrainMatrix B = strain_displacement(F_new, grad.dN_dX);
    const ElementVector BtS = B.transpose() * response.S;
    out.f_int.noalias() += (dV0 / alpha) * BtS;

    if (!points.empty()) {
      PointOutput& p = points[q];
      p.F = Fm_new;
      p.S = response.S;
      p.sigma = to_voigt_stress(cauchy_from_pk2(Fm_new, from_voigt_stress(response.S)));
      p.X = in.X * rule[q].N;
      p.dV0 = dV0;
    }
    if (!want_tangent) continue;

    // Material part alpha B^T C B and geometric part (1/alpha) (g_a . S g_b) I.
    const Eigen::Matrix<double, Eigen::Dynamic, 6, 0, max_element_dofs, 6> BtC = B.transpose() * response.dS_dE;
    out.K.noalias() += (alpha * dV0) * BtC * B;
    const Mat3 S = from_voigt_stress(response.S);
    const ElementMatrix G = grad.dN_dX.transpose() * S * grad.dN_dX;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int i = 0; i < 3; ++i) out.K(3 * a + i, 3 * b + i) += dV0 / alpha * G(a, b);

    if (fbar) {
      // d alpha / alpha = (1/3) (h0 - h) . du; the F-bar terms are
      // (1/(3 alpha)) B^T (C : C_bar - S) (x) (h0 - h), with C_bar = F_bar^T F_bar (strain Voigt).
      const ElementVector d = h0 - flattened_spatial_gradients(F_new, grad.dN_dX);
      const Vec6 C_bar = to_voigt_strain(Fm_new.transpose() * Fm_new);
      const ElementVector w = BtC * C_bar - BtS;
      out.K.noalias() += (dV0 / (3.0 * alpha)) * w * d.transpose();
    }
  }
  return out;
}

ElementMatrix consistent_mass(mesh::ElementType type, const NodeMatrix& X, double rho) {
  const int n = mesh::nodes_per_element(type);
  ElementMatrix M = ElementMatrix::Zero(3 * n, 3 * n);
  for (const auto& qp : mass_quadrature(type)) {
    const ShapeValues& N = qp.N;
    const double dm = rho * qp.weight * reference_gradients(X, qp).det_J;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int i = 0; i < 3; ++i) M(3 * a + i, 3 * b + i) += dm * N(a) * N(b);
  }
  return M;
}

double element_volume(mesh::ElementType type, const NodeMatrix& X) {
  double V = 0.0;
  for (const auto& qp : mass_quadrature(type)) V += qp.weight * reference_gradients(X, qp).det_J;
  return V;
}

}  // namespace cushion::solver
