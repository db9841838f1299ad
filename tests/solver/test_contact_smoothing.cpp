// Requirement: the normal contact law is C1 across opening/closing (no active-set cycling) and exact
// for loaded nodes; the increment predictor extrapolates the contact force from the last converged
// indenter position to first order.
// Checks:
//  - nodes sitting in the smoothing zone |g| < delta/2 of a flat platen: force t_N = (eps delta/2 -
//    eps g)^2 / (2 eps delta) per node (1e-12 relative), 0 at g = delta/2 and eps delta/2 at
//    g = -delta/2 (continuous), exactly 0 beyond g = delta/2, and the tangent equals central differences (1e-6 relative);
//  - beyond the zone (g < -delta/2) the law is the exact penalty t_N = -eps g (1e-12 relative);
//  - ContactSet::evaluate_predictor(from) at indenter offset dc differs from evaluate() at the new
//    position by O(|dc|^2): halving dc divides the difference by 4 (within 3.6 ... 4.4) on a sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/solver/solver_fixtures.hpp"
#include "tests/solver/test_contact_support.hpp"

namespace cushion::solver {
namespace {

mesh::BlockSpec cube(double L, int n) {
  mesh::BlockSpec spec;
  spec.low = Vec3::Zero();
  spec.high = Vec3::Constant(L);
  spec.n = {n, n, n};
  return spec;
}

std::vector<int> top(const mesh::Mesh& m, double z) {
  std::vector<int> out;
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a)
    if (std::abs(m.nodes[a].z() - z) < 1e-9) out.push_back(a);
  return out;
}

TEST(ContactSmoothing, ForceIsC1AndExactBeyondTheZone) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(cube(10, 2), test::neo_hookean(), fix_bottom);
  ContactParameters p;
  p.penalty = 0.5, p.tolerance = 0.1, p.smoothing = 0.04;
  const std::vector<int> nodes = top(m.mesh, 10);
  const DofMap& dofs = m.assembler->dofs();
  // Platen underside at z = 10 + g (the body is above it): every top node has gap g [mm].
  auto force_at_gap = [&](double g, std::size_t k) {
    ContactSet set("platen", m.mesh, nodes, make_plane(Vec3(0, 0, 10 + g), Vec3(0, 0, -1)), p);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(m.u.size()), r = u;
    set.evaluate(u, dofs, r, nullptr);
    return set.normal_force_magnitudes()[k];
  };
  ContactSet probe("platen", m.mesh, nodes, make_plane(Vec3(0, 0, 10), Vec3(0, 0, -1)), p);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double eps = p.penalty * probe.areas()[k], d = p.smoothing;
    EXPECT_NEAR(force_at_gap(0.5 * d, k), 0.0, 1e-12 * eps * d);
    EXPECT_EQ(force_at_gap(0.6 * d, k), 0.0);
    EXPECT_NEAR(force_at_gap(-0.5 * d, k), 0.5 * eps * d, 1e-12 * eps * d);
    for (double g : {-0.015, -0.004, 0.0, 0.011}) {
      const double x = -eps * g + 0.5 * eps * d;
      EXPECT_NEAR(force_at_gap(g, k), x * x / (2 * eps * d), 1e-12 * eps * d) << "gap " << g;
    }
    EXPECT_NEAR(force_at_gap(-0.3, k), 0.3 * eps, 1e-12 * eps);  // 0.3 mm penetration: exact penalty
  }

  // Tangent in the zone: nodes perturbed around g = 0.
  ContactSet set("platen", m.mesh, nodes, make_plane(Vec3(0, 0, 10), Vec3(0, 0, -1)), p);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.u.size());
  for (std::size_t k = 0; k < nodes.size(); ++k)
    u.segment<3>(3 * nodes[k]) = Vec3(0.01 * std::sin(k), 0.02 * std::cos(3.0 * k), 0.015 * std::sin(2.0 * k + 1));
  SparseMatrix K = m.assembler->make_matrix();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(u.size());
  set.evaluate(u, dofs, r, &K);
  const Eigen::MatrixXd Kd(K);
  const double h = 1e-7, scale = Kd.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  double worst = 0.0;
  for (int eq = 0; eq < static_cast<int>(dofs.num_free()); ++eq) {
    const int dof = dofs.free_dofs()[eq];
    Eigen::VectorXd up = u, um = u, rp = Eigen::VectorXd::Zero(u.size()), rm = rp;
    up(dof) += h, um(dof) -= h;
    set.evaluate(up, dofs, rp, nullptr);
    set.evaluate(um, dofs, rm, nullptr);
    worst = std::max(worst, (dofs.gather_free((rp - rm) / (2 * h)) - Kd.col(eq)).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, 1e-6 * scale);
}

TEST(ContactSmoothing, PredictorIsFirstOrderInTheIndenterMotion) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(cube(10, 2), test::neo_hookean(), fix_bottom);
  const DofMap& dofs = m.assembler->dofs();
  ContactParameters p;
  p.penalty = 0.5;
  ContactSet set("ball", m.mesh, top(m.mesh, 10), make_sphere(Vec3(5, 5, 19.5), 10), p);  // 0.5 mm deep
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(m.u.size());
  const Vec3 from = Vec3::Zero();
  auto difference = [&](const Vec3& dc) {
    Eigen::VectorXd r_exact = Eigen::VectorXd::Zero(u.size()), r_pred = r_exact;
    set.set_position(from + dc);
    set.evaluate(u, dofs, r_exact, nullptr);
    set.evaluate_predictor(from, u, dofs, r_pred, nullptr);
    return (r_exact - r_pred).cwiseAbs().maxCoeff();
  };
  const Vec3 dc(0.05, -0.03, -0.1);
  const double e1 = difference(dc), e2 = difference(0.5 * dc);
  ASSERT_GT(e1, 0.0);
  EXPECT_GT(e1 / e2, 3.6);
  EXPECT_LT(e1 / e2, 4.4);
}

}  // namespace
}  // namespace cushion::solver
