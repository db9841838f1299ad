// Requirement: a follower pressure on an element face (ABAQUS *DLOAD Pn) shall give the force p x area
// against the outward normal, CalculiX's equivalent nodal forces on a C3D20 face (corners -1/12, mid-edges
// +1/3 of p A), and a tangent equal to the finite difference of its residual.
#include <gtest/gtest.h>

#include <random>

#include "solver/analysis/pressure_contributor.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

using mesh::ElementType;

/// Residual of pressure p on `face` at u, all DOFs free; optionally the tangent.
Eigen::VectorXd residual(const mesh::Mesh& m, const mesh::Face& face, double p, const Eigen::VectorXd& u,
                         SparseMatrix* K = nullptr) {
  const DofMap dofs(m.num_nodes(), std::vector<bool>(3 * m.num_nodes(), false));
  Eigen::VectorXd r = Eigen::VectorXd::Zero(u.size());
  add_face_pressure(m, face, p, u, dofs, r, K);
  return r;
}

TEST(Pressure, ResultantIsPressureTimesAreaAndQuadraticFacesShareItAsCalculix) {
  // Undistorted unit-spaced block [0,2]^3 with one element: face S2 (top, z = 2) has area 4, outward +z.
  // r = -f_ext = +p A n: 1e-13 relative. C3D20: corner nodes -1/12, mid-edge +1/3 of p A.
  for (ElementType type : {ElementType::hex8, ElementType::hex20, ElementType::hex20r, ElementType::tet10}) {
    const mesh::Mesh m = test::distorted_block(type, 1, 0.0);
    const bool hex = mesh::is_hexahedron(type);
    // Tets: S1 of element 0 lies in a coordinate plane of the block; take its area from the geometry.
    const mesh::Face face{0, hex ? 1 : 0};
    const Eigen::VectorXd r = residual(m, face, 2.5, Eigen::VectorXd::Zero(3 * m.num_nodes()));
    Vec3 total = Vec3::Zero();
    for (std::size_t a = 0; a < m.num_nodes(); ++a) total += r.segment<3>(3 * a);
    const double area = mesh::face_area(m, face);
    EXPECT_NEAR(total.norm(), 2.5 * area, 1e-13 * 2.5 * area) << mesh::to_string(type);
    if (type == ElementType::hex20) {
      const std::vector<int> local = mesh::face_nodes(type, 1);
      for (std::size_t k = 0; k < local.size(); ++k)
        EXPECT_NEAR(r(3 * m.elements[0].nodes[local[k]] + 2), 2.5 * 4.0 * (k < 4 ? -1.0 / 12.0 : 1.0 / 3.0), 1e-13);
    }
    if (hex) EXPECT_GT(total.z(), 0.0);  // +p A n_out with n_out = +z
  }
}

TEST(Pressure, TangentMatchesFiniteDifferences) {
  // Distorted, curved elements and a random displacement; central differences h = 1e-6: 1e-7 relative.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> v(-0.2, 0.2);
  for (ElementType type : {ElementType::hex8, ElementType::hex20, ElementType::tet4, ElementType::tet10}) {
    const mesh::Mesh m = test::distorted_block(type, 1, 0.1, true);
    Eigen::VectorXd u(3 * m.num_nodes());
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) = v(rng);
    for (int face = 0; face < mesh::faces_per_element(type); ++face) {
      const mesh::Face f{0, face};
      SparseMatrix K(u.size(), u.size());
      residual(m, f, 1.7, u, &K);
      const Eigen::MatrixXd Kd(K);
      Eigen::MatrixXd fd(u.size(), u.size());
      const double h = 1e-6;
      for (Eigen::Index j = 0; j < u.size(); ++j) {
        Eigen::VectorXd up = u, um = u;
        up(j) += h, um(j) -= h;
        fd.col(j) = (residual(m, f, 1.7, up) - residual(m, f, 1.7, um)) / (2 * h);
      }
      EXPECT_LT((Kd - fd).cwiseAbs().maxCoeff(), 1e-7 * fd.cwiseAbs().maxCoeff()) << mesh::to_string(type) << " S" << face + 1;
    }
  }
}

}  // namespace
}  // namespace cushion::solver
