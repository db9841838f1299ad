#include "solver/elements/quadrature.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "mesh/shape.hpp"

namespace cushion::solver {
namespace {

using mesh::ElementType;

using mesh::gauss_legendre;

QuadraturePoint tabulate(ElementType type, const Vec3& xi, double weight) {
  QuadraturePoint p;
  p.xi = xi;
  p.weight = weight;
  p.N = mesh::shape_values(type, xi);
  p.dN_dxi = mesh::shape_gradients(type, xi).transpose();
  return p;
}

// n x n x n Gauss product rule on [-1, 1]^3, xi fastest.
std::vector<QuadraturePoint> hex_product_rule(ElementType type, int n) {
  std::vector<QuadraturePoint> rule;
  const auto g = gauss_legendre(n);
  for (const auto& c : g)
    for (const auto& b : g)
      for (const auto& a : g) rule.push_back(tabulate(type, Vec3(a[0], b[0], c[0]), a[1] * b[1] * c[1]));
  return rule;
}

// Collapsed (Duffy) product rule on the unit tet: xi1 = s, xi2 = t(1 - s), xi3 = r(1 - s)(1 - t),
// Jacobian (1 - s)^2 (1 - t); n Gauss points per direction on [0, 1].
std::vector<QuadraturePoint> tet_collapsed_rule(ElementType type, int n) {
  std::vector<QuadraturePoint> rule;
  const auto g = gauss_legendre(n);
  for (const auto& a : g)
    for (const auto& b : g)
      for (const auto& c : g) {
        const double s = 0.5 * (a[0] + 1), t = 0.5 * (b[0] + 1), r = 0.5 * (c[0] + 1);
        const double w = a[1] * b[1] * c[1] / 8.0 * (1 - s) * (1 - s) * (1 - t);
        rule.push_back(tabulate(type, Vec3(s, t * (1 - s), r * (1 - s) * (1 - t)), w));
      }
  return rule;
}

// Degree-2 rule with 4 points: a = (5 + 3 sqrt 5)/20, b = (5 - sqrt 5)/20, weights 1/24.
std::vector<QuadraturePoint> tet_four_point_rule(ElementType type) {
  const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
  return {tabulate(type, Vec3(b, b, b), 1.0 / 24.0), tabulate(type, Vec3(a, b, b), 1.0 / 24.0),
          tabulate(type, Vec3(b, a, b), 1.0 / 24.0), tabulate(type, Vec3(b, b, a), 1.0 / 24.0)};
}

}  // namespace

const std::vector<QuadraturePoint>& stiffness_quadrature(ElementType type) {
  static const std::vector<QuadraturePoint> hex8 = hex_product_rule(ElementType::hex8, 2);
  static const std::vector<QuadraturePoint> tet4 = {tabulate(ElementType::tet4, Vec3::Constant(0.25), 1.0 / 6.0)};
  static const std::vector<QuadraturePoint> tet10 = tet_four_point_rule(ElementType::tet10);
  static const std::vector<QuadraturePoint> hex20 = hex_product_rule(ElementType::hex20, 3);
  static const std::vector<QuadraturePoint> hex20r = hex_product_rule(ElementType::hex20r, 2);
  switch (type) {
    case ElementType::hex8: return hex8;
    case ElementType::tet4: return tet4;
    case ElementType::tet10: return tet10;
    case ElementType::hex20: return hex20;
    case ElementType::hex20r: return hex20r;
  }
  throw std::invalid_argument("stiffness_quadrature: unknown element type");
}

const std::vector<QuadraturePoint>& mass_quadrature(ElementType type) {
  static const std::vector<QuadraturePoint> hex8 = hex_product_rule(ElementType::hex8, 3);
  static const std::vector<QuadraturePoint> tet4 = tet_collapsed_rule(ElementType::tet4, 4);
  static const std::vector<QuadraturePoint> tet10 = tet_collapsed_rule(ElementType::tet10, 4);
  static const std::vector<QuadraturePoint> hex20 = hex_product_rule(ElementType::hex20, 4);
  switch (type) {
    case ElementType::hex8: return hex8;
    case ElementType::tet4: return tet4;
    case ElementType::tet10: return tet10;
    case ElementType::hex20:
    case ElementType::hex20r: return hex20;
  }
  throw std::invalid_argument("mass_quadrature: unknown element type");
}

const QuadraturePoint& centre_point(ElementType type) {
  static const QuadraturePoint hex8 = tabulate(ElementType::hex8, Vec3::Zero(), 0.0);
  static const QuadraturePoint tet4 = tabulate(ElementType::tet4, Vec3::Constant(0.25), 0.0);
  static const QuadraturePoint tet10 = tabulate(ElementType::tet10, Vec3::Constant(0.25), 0.0);
  static const QuadraturePoint hex20 = tabulate(ElementType::hex20, Vec3::Zero(), 0.0);
  switch (type) {
    case ElementType::hex8: return hex8;
    case ElementType::tet4: return tet4;
    case ElementType::tet10: return tet10;
    case ElementType::hex20:
    case ElementType::hex20r: return hex20;
  }
  throw std::invalid_argument("centre_point: unknown element type");
}

ReferenceGradients reference_gradients(const NodeMatrix& X, const QuadraturePoint& point) {
  const Mat3 J = X * point.dN_dxi.transpose();  // J_ij = dX_i / dxi_j
  ReferenceGradients g;
  g.det_J = J.determinant();
  g.dN_dX = J.transpose().inverse() * point.dN_dxi;  // dN/dX = J^{-T} dN/dxi
  return g;
}

}  // namespace cushion::solver
