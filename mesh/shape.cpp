#include "mesh/shape.hpp"

#include <cmath>
#include <stdexcept>

namespace cushion::mesh {
namespace {

// Corner signs of the C3D8 reference cube: nodes 1-4 at zeta = -1, 5-8 at zeta = +1.
constexpr double kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// Barycentric coordinates L and their constant gradients dL/dxi of the unit tetrahedron.
Eigen::Vector4d barycentric(const Vec3& xi) {
  return {1.0 - xi.sum(), xi.x(), xi.y(), xi.z()};
}
Eigen::Matrix<double, 4, 3> barycentric_gradients() {
  Eigen::Matrix<double, 4, 3> dL;
  dL << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return dL;
}

// Serendipity brick (hex20): node a at reference coordinates c = xi_a, f_j = 1 + c_j xi_j.
// Corner: N = 1/8 f_0 f_1 f_2 (c . xi - 2); mid-edge with c_k = 0: N = 1/4 (1 - xi_k^2) f_i f_j.
int zero_coordinate(const Vec3& c) {
  for (int k = 0; k < 3; ++k)
    if (c(k) == 0.0) return k;
  return -1;
}

double hex20_value(const Vec3& c, const Vec3& xi) {
  const Vec3 f = Vec3::Ones() + c.cwiseProduct(xi);
  const int k = zero_coordinate(c);
  if (k < 0) return 0.125 * f.prod() * (c.dot(xi) - 2.0);
  return 0.25 * (1.0 - xi(k) * xi(k)) * f((k + 1) % 3) * f((k + 2) % 3);
}

// dN/dxi_i: corner 1/8 c_i (prod_{j != i} f_j)(c . xi - 2 + f_i); mid-edge (c_k = 0)
// -1/2 xi_k f_i f_j for i = k and 1/4 (1 - xi_k^2) c_i f_j (j the third direction) otherwise.
Eigen::RowVector3d hex20_gradient(const Vec3& c, const Vec3& xi) {
  const Vec3 f = Vec3::Ones() + c.cwiseProduct(xi);
  const int k = zero_coordinate(c);
  Eigen::RowVector3d g;
  for (int i = 0; i < 3; ++i) {
    const double others = f((i + 1) % 3) * f((i + 2) % 3);
    if (k < 0) {
      g(i) = 0.125 * c(i) * others * (c.dot(xi) - 2.0 + f(i));
    } else if (i == k) {
      g(i) = -0.5 * xi(k) * others;
    } else {
      g(i) = 0.25 * (1.0 - xi(k) * xi(k)) * c(i) * f(3 - i - k);
    }
  }
  return g;
}

const std::vector<Vec3>& hex20_nodes() {
  static const std::vector<Vec3> nodes = node_coordinates(ElementType::hex20);
  return nodes;
}

}  // namespace

Eigen::VectorXd shape_values(ElementType type, const Vec3& xi) {
  Eigen::VectorXd N(nodes_per_element(type));
  switch (type) {
    case ElementType::hex8:
      for (int a = 0; a < 8; ++a)
        N(a) = 0.125 * (1 + kHexSign[a][0] * xi.x()) * (1 + kHexSign[a][1] * xi.y()) *
               (1 + kHexSign[a][2] * xi.z());
      return N;
    case ElementType::tet4:
      return barycentric(xi);
    case ElementType::tet10: {
      const Eigen::Vector4d L = barycentric(xi);
      for (int a = 0; a < 4; ++a) N(a) = L(a) * (2 * L(a) - 1);
      const auto& edges = mid_edge_corners(type);
      for (int m = 0; m < 6; ++m) N(4 + m) = 4 * L(edges[m][0]) * L(edges[m][1]);
      return N;
    }
    case ElementType::hex20:
    case ElementType::hex20r:
      for (int a = 0; a < 20; ++a) N(a) = hex20_value(hex20_nodes()[a], xi);
      return N;
  }
  throw std::logic_error("shape_values: unknown element type");
}

Eigen::MatrixXd shape_gradients(ElementType type, const Vec3& xi) {
  Eigen::MatrixXd dN(nodes_per_element(type), 3);
  switch (type) {
    case ElementType::hex8:
      for (int a = 0; a < 8; ++a) {
        const double* s = kHexSign[a];
        const double fx = 1 + s[0] * xi.x(), fy = 1 + s[1] * xi.y(), fz = 1 + s[2] * xi.z();
        dN.row(a) << 0.125 * s[0] * fy * fz, 0.125 * fx * s[1] * fz, 0.125 * fx * fy * s[2];
      }
      return dN;
    case ElementType::tet4:
      return barycentric_gradients();
    case ElementType::tet10: {
      const Eigen::Vector4d L = barycentric(xi);
      const Eigen::Matrix<double, 4, 3> dL = barycentric_gradients();
      for (int a = 0; a < 4; ++a) dN.row(a) = (4 * L(a) - 1) * dL.row(a);
      const auto& edges = mid_edge_corners(type);
      for (int m = 0; m < 6; ++m) {
        const int i = edges[m][0], j = edges[m][1];
        dN.row(4 + m) = 4 * (L(j) * dL.row(i) + L(i) * dL.row(j));
      }
      return dN;
    }
    case ElementType::hex20:
    case ElementType::hex20r:
      for (int a = 0; a < 20; ++a) dN.row(a) = hex20_gradient(hex20_nodes()[a], xi);
      return dN;
  }
  throw std::logic_error("shape_gradients: unknown element type");
}

std::vector<Vec3> corner_coordinates(ElementType type) {
  if (is_hexahedron(type)) {
    std::vector<Vec3> xi;
    for (const auto& s : kHexSign) xi.emplace_back(s[0], s[1], s[2]);
    return xi;
  }
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
}

std::vector<Vec3> node_coordinates(ElementType type) {
  std::vector<Vec3> xi = corner_coordinates(type);
  for (const auto& edge : mid_edge_corners(type)) xi.push_back(0.5 * (xi[edge[0]] + xi[edge[1]]));
  return xi;
}

std::vector<std::array<double, 2>> gauss_legendre(int n) {
  if (n == 2) {
    const double a = 1.0 / std::sqrt(3.0);
    return {{-a, 1.0}, {a, 1.0}};
  }
  if (n == 3) {
    const double a = std::sqrt(0.6);
    return {{-a, 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {a, 5.0 / 9.0}};
  }
  if (n == 4) {
    const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
    const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
    const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
    return {{-b, wb}, {-a, wa}, {a, wa}, {b, wb}};
  }
  throw std::invalid_argument("gauss_legendre: unsupported order " + std::to_string(n));
}

Eigen::Matrix3d reference_jacobian(const Mesh& mesh, int e, const Vec3& xi) {
  const Element& element = mesh.elements.at(e);
  const Eigen::MatrixXd dN = shape_gradients(element.type, xi);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int a = 0; a < dN.rows(); ++a) J += mesh.nodes.at(element.nodes[a]) * dN.row(a);
  return J;
}

}  // namespace cushion::mesh
