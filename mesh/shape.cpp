#include "mesh/shape.hpp"

#include <stdexcept>

namespace cushion::mesh {
namespace {

// Corner signs of the C3D8 reference cube: nodes 1-4 at zeta = -1, 5-8 at zeta = +1.
constexpr double kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
// C3D10 mid-edge nodes 5..10 join corners (1-2, 2-3, 3-1, 1-4, 2-4, 3-4), 0-based here.
constexpr int kTetEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// Barycentric coordinates L and their constant gradients dL/dxi of the unit tetrahedron.
Eigen::Vector4d barycentric(const Vec3& xi) {
  return {1.0 - xi.sum(), xi.x(), xi.y(), xi.z()};
}
Eigen::Matrix<double, 4, 3> barycentric_gradients() {
  Eigen::Matrix<double, 4, 3> dL;
  dL << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return dL;
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
      for (int m = 0; m < 6; ++m) N(4 + m) = 4 * L(kTetEdge[m][0]) * L(kTetEdge[m][1]);
      return N;
    }
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
      for (int m = 0; m < 6; ++m) {
        const int i = kTetEdge[m][0], j = kTetEdge[m][1];
        dN.row(4 + m) = 4 * (L(j) * dL.row(i) + L(i) * dL.row(j));
      }
      return dN;
    }
  }
  throw std::logic_error("shape_gradients: unknown element type");
}

std::vector<Vec3> corner_coordinates(ElementType type) {
  if (type == ElementType::hex8) {
    std::vector<Vec3> xi;
    for (const auto& s : kHexSign) xi.emplace_back(s[0], s[1], s[2]);
    return xi;
  }
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
}

Eigen::Matrix3d reference_jacobian(const Mesh& mesh, int e, const Vec3& xi) {
  const Element& element = mesh.elements.at(e);
  const Eigen::MatrixXd dN = shape_gradients(element.type, xi);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int a = 0; a < dN.rows(); ++a) J += mesh.nodes.at(element.nodes[a]) * dN.row(a);
  return J;
}

}  // namespace cushion::mesh
