// Requirement: every element reproduces a homogeneous finite deformation exactly on a distorted mesh.
// Check (patch test): boundary nodes of a distorted block get u = (F - I) X for a general F with
// det F = 0.8; interior nodes are free and solved by Newton. Interior displacements equal (F - I) X
// to 1e-10 mm, and the stress at every quadrature point equals the material-point stress at F to
// 1e-10 relative. hex8, hex8 F-bar, tet4, tet10 (straight-sided: its 4-point rule is exact for
// the patch only then), hex20 (C3D20, 3x3x3) and hex20r (C3D20R, 2x2x2), straight-sided with
// distorted corners; NeoHookean and Hyperfoam.
#include <gtest/gtest.h>

#include "solver/equilibrium.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

void patch_test(mesh::ElementType type, Formulation formulation, std::shared_ptr<const material::Material> mat) {
  SCOPED_TRACE(mesh::to_string(type) + (formulation == Formulation::fbar ? " F-bar / " : " / ") + mat->describe());
  const mesh::Mesh regular = test::distorted_block(type, 2, 0.0);
  const mesh::Mesh m = test::distorted_block(type, 2, 0.15);
  const Mat3 F = test::general_F();

  std::vector<bool> constrained(3 * m.num_nodes(), false);
  Eigen::VectorXd u_new = Eigen::VectorXd::Zero(3 * m.num_nodes());
  int interior = 0;
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a) {
    if (!test::on_block_boundary(regular, a)) {
      ++interior;
      continue;
    }
    u_new.segment<3>(3 * a) = (F - Mat3::Identity()) * m.nodes[a];
    for (int i = 0; i < 3; ++i) constrained[3 * a + i] = true;
  }
  ASSERT_GT(interior, 0);

  Section section{"all", {}, mat, formulation, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) section.elements.push_back(e);
  const Assembler assembler(m, {section}, DofMap(m.num_nodes(), constrained), {.num_threads = 2});
  StateStore state = assembler.make_state_store();
  auto linear = make_linear_solver(formulation == Formulation::fbar ? LinearSolverKind::lu : LinearSolverKind::cholesky);
  NewtonOptions options;
  options.residual_tolerance = 1e-12;
  options.correction_tolerance = 1e-12;

  // Four increments of the boundary displacement; each starts from the previous solution.
  const Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(u_new.size());
  Eigen::VectorXd u_old = f_ext, u = f_ext;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(assembler.dofs().num_free());
  for (int n = 1; n <= 4; ++n) {
    Eigen::VectorXd u_target = 0.25 * n * u_new;
    EquilibriumProblem problem(assembler, state, u_old, u_target, f_ext, 0.0);
    const NewtonResult result = solve_newton(problem, *linear, x, options);
    ASSERT_TRUE(result.converged()) << "increment " << n << ": " << result.message;
    state.commit();
    u = problem.u();
    u_old = u;
  }

  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a) {
    const Vec3 exact = (F - Mat3::Identity()) * m.nodes[a];
    EXPECT_LE((u.segment<3>(3 * a) - exact).cwiseAbs().maxCoeff(), 1e-10) << "node " << a;
  }

  std::vector<PointOutput> points;
  Eigen::VectorXd f_int;
  assembler.assemble(u_old, u, 0.0, state, f_int, nullptr, &points);
  std::vector<double> s_old(mat->state_size()), s_new(mat->state_size());
  const material::PointResponse exact = mat->integrate(Mat3::Identity(), F, 0.0, s_old, s_new);
  const Vec6 sigma = to_voigt_stress(cauchy_from_pk2(F, from_voigt_stress(exact.S)));
  const double scale = exact.S.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  for (const PointOutput& p : points) {
    EXPECT_LE((p.F - F).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LE((p.S - exact.S).cwiseAbs().maxCoeff(), 1e-10 * scale);
    EXPECT_LE((p.sigma - sigma).cwiseAbs().maxCoeff(), 1e-10 * scale);
  }
}

TEST(PatchTest, Hex8) {
  patch_test(mesh::ElementType::hex8, Formulation::full, test::neo_hookean());
  patch_test(mesh::ElementType::hex8, Formulation::full, test::hyperfoam());
}

TEST(PatchTest, Hex8Fbar) {
  patch_test(mesh::ElementType::hex8, Formulation::fbar, test::neo_hookean());
  patch_test(mesh::ElementType::hex8, Formulation::fbar, test::hyperfoam());
}

TEST(PatchTest, Tet4) {
  patch_test(mesh::ElementType::tet4, Formulation::full, test::neo_hookean());
  patch_test(mesh::ElementType::tet4, Formulation::full, test::hyperfoam());
}

TEST(PatchTest, Tet10) {
  patch_test(mesh::ElementType::tet10, Formulation::full, test::neo_hookean());
  patch_test(mesh::ElementType::tet10, Formulation::full, test::hyperfoam());
}

TEST(PatchTest, Hex20) {
  patch_test(mesh::ElementType::hex20, Formulation::full, test::neo_hookean());
  patch_test(mesh::ElementType::hex20, Formulation::full, test::hyperfoam());
}

TEST(PatchTest, Hex20Reduced) {
  patch_test(mesh::ElementType::hex20r, Formulation::full, test::neo_hookean());
  patch_test(mesh::ElementType::hex20r, Formulation::full, test::hyperfoam());
}

}  // namespace
}  // namespace cushion::solver
