// Requirement: the consistent mass matrix carries the body's mass and inertia of rigid translation.
// Checks: for hex8, tet4, tet10, hex20, hex20r (interior nodes distorted, quadratic elements
// curved): element volumes sum to the cube's 8 mm^3 (1e-12); sum of the entries of each direction
// block = rho V to 1e-12 relative, with V from the element volumes; M times a unit rigid
// translation gives nodal forces summing to rho V in that direction and 0 in the others (1e-12);
// the tet4 element matrix equals the closed form rho V / 20 (1 + delta_ab) to 1e-14 relative;
// straight tet10 volume equals |det| / 6 of its corners (1e-14).
#include <gtest/gtest.h>

#include "solver/assembler.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

constexpr double rho = 1.2e-10;  // [t/mm^3] = 120 kg/m^3 foam

TEST(Mass, SumsToTotalMassAndTranslatesRigidly) {
  for (auto type : {mesh::ElementType::hex8, mesh::ElementType::tet4, mesh::ElementType::tet10,
                    mesh::ElementType::hex20, mesh::ElementType::hex20r}) {
    SCOPED_TRACE(mesh::to_string(type));
    // Interior nodes distorted, boundary nodes on the cube faces: the volume stays 8 mm^3.
    const mesh::Mesh regular = test::distorted_block(type, 2, 0.0, true);
    mesh::Mesh m = test::distorted_block(type, 2, 0.15, true);
    for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a)
      if (test::on_block_boundary(regular, a)) m.nodes[a] = regular.nodes[a];
    Section s{"all", {}, test::neo_hookean(), Formulation::full, rho};
    double V = 0.0;
    for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) {
      s.elements.push_back(e);
      V += element_volume(type, test::element_nodes(m, e));
    }
    EXPECT_NEAR(V, 8.0, 1e-12);
    const Assembler assembler(m, {s}, DofMap(m.num_nodes(), {}), {2});
    SparseMatrix M = assembler.make_matrix();
    assembler.assemble_mass(M);
    const double mass = rho * V;
    EXPECT_NEAR(assembler.total_mass(), mass, 1e-12 * mass);
    for (int i = 0; i < 3; ++i) {
      Eigen::VectorXd t = Eigen::VectorXd::Zero(M.rows());
      for (std::size_t a = 0; a < m.num_nodes(); ++a) t(3 * a + i) = 1.0;
      const Eigen::VectorXd f = M * t;  // inertia force of a unit rigid acceleration in direction i
      for (int j = 0; j < 3; ++j) {
        double sum = 0.0;
        for (std::size_t a = 0; a < m.num_nodes(); ++a) sum += f(3 * a + j);
        EXPECT_NEAR(sum, i == j ? mass : 0.0, 1e-12 * mass);
      }
    }
  }
}

TEST(Mass, Tet4MatchesClosedForm) {
  NodeMatrix X(3, 4);
  X << 0.1, 2.0, 0.3, 0.2, 0.0, 0.4, 1.7, 0.1, -0.2, 0.1, 0.3, 1.5;
  const double V = (X.col(1) - X.col(0)).cross(X.col(2) - X.col(0)).dot(X.col(3) - X.col(0)) / 6.0;
  ASSERT_GT(V, 0.0);
  const ElementMatrix M = consistent_mass(mesh::ElementType::tet4, X, rho);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double exact = i == j ? rho * V / 20.0 * (a == b ? 2.0 : 1.0) : 0.0;
          EXPECT_NEAR(M(3 * a + i, 3 * b + j), exact, 1e-14 * rho * V);
        }
}

TEST(Mass, StraightTet10VolumeEqualsCornerTet) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::tet10, 1, 0.15);
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) {
    const NodeMatrix X = test::element_nodes(m, e);
    const double V = (X.col(1) - X.col(0)).cross(X.col(2) - X.col(0)).dot(X.col(3) - X.col(0)) / 6.0;
    EXPECT_NEAR(element_volume(mesh::ElementType::tet10, X), V, 1e-14 * 8.0);
  }
}

}  // namespace
}  // namespace cushion::solver
