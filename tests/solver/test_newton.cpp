// Requirement: the Newton driver converges quadratically with the consistent tangent, reaches the
// exact homogeneous solution, and reports (never hides) divergence, material failure and singular
// tangents.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/equilibrium.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

/// Uniaxial compression of the block [0,2]^3 (n^3 hex8): symmetry planes x = 0, y = 0, z = 0, top
/// z = 2 moved by w [mm], lateral faces free. The exact solution is homogeneous.
struct UniaxialBlock {
  mesh::Mesh m;
  std::unique_ptr<Assembler> assembler;
  Eigen::VectorXd u_new;

  UniaxialBlock(int n, double w, std::shared_ptr<const material::Material> mat, Formulation formulation,
                unsigned threads = 1) {
    m = test::distorted_block(mesh::ElementType::hex8, n, 0.0);
    std::vector<bool> constrained(3 * m.num_nodes(), false);
    u_new = Eigen::VectorXd::Zero(3 * m.num_nodes());
    for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a) {
      const Vec3& X = m.nodes[a];
      for (int i = 0; i < 3; ++i)
        if (X(i) < 1e-9) constrained[3 * a + i] = true;
      if (X(2) > 2.0 - 1e-9) {
        constrained[3 * a + 2] = true;
        u_new(3 * a + 2) = w;
      }
    }
    Section s{"all", {}, std::move(mat), formulation, 0.0};
    for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
    assembler = std::make_unique<Assembler>(m, std::vector<Section>{s}, DofMap(m.num_nodes(), constrained),
                                            AssemblyOptions{threads});
  }
};

/// Lateral stretch of uniaxial stress at axial stretch l3 (S11 = 0), by bisection on the material.
double lateral_stretch(const material::Material& mat, double l3) {
  double lo = 0.5, hi = 2.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    const auto r = mat.integrate(Mat3::Identity(), Vec3(mid, mid, l3).asDiagonal().toDenseMatrix(), 0.0, {}, {});
    (r.S(0) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(Newton, QuadraticConvergenceOnHomogeneousCompression) {
  // 30 % compression in one increment. Check before round-off (r_k / r_0 > 1e-13):
  // r_{k+1} / r_0 <= 10 (r_k / r_0)^2 once r_k / r_0 < 1e-2, and the last such pair has
  // log(r_{k+1}/r_0) / log(r_k/r_0) >= 1.8.
  const auto mat = test::neo_hookean();
  UniaxialBlock block(2, -0.6, mat, Formulation::full);
  StateStore state = block.assembler->make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  EquilibriumProblem problem(*block.assembler, state, zero, block.u_new, zero, 0.0);
  // The first trial (interior at rest, top layer 60 % compressed) has an indefinite tangent.
  auto linear = make_linear_solver(LinearSolverKind::cholesky_or_lu);
  NewtonOptions options;
  options.residual_tolerance = 1e-14;
  options.correction_tolerance = 1e-14;
  options.line_search = false;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
  std::vector<std::string> log;
  const NewtonResult result =
      solve_newton(problem, *linear, x, options, [&](const NewtonIterate& it) { log.push_back(format_iterate(it)); });
  ASSERT_TRUE(result.converged()) << result.message;
  ASSERT_EQ(log.size(), result.history.size());

  const double r0 = result.history[0].residual_max;
  int quadratic_pairs = 0;
  double last_order = 0.0;
  for (std::size_t k = 0; k + 1 < result.history.size(); ++k) {
    const double ek = result.history[k].residual_max / r0, ek1 = result.history[k + 1].residual_max / r0;
    if (ek1 < 1e-13 || ek > 1e-2) continue;
    EXPECT_LE(ek1, 10.0 * ek * ek) << log[k + 1];
    last_order = std::log(ek1) / std::log(ek);
    ++quadratic_pairs;
  }
  EXPECT_GE(quadratic_pairs, 1);
  EXPECT_GE(last_order, 1.8);

  // Reaction on the top face equals P33 A0 of the material point in uniaxial stress (1e-8 relative).
  const double l = lateral_stretch(*mat, 0.7);
  const Mat3 F = Vec3(l, l, 0.7).asDiagonal();
  const auto point = mat->integrate(Mat3::Identity(), F, 0.0, {}, {});
  const double P33 = (F * from_voigt_stress(point.S))(2, 2);
  double reaction = 0.0;
  for (int a = 0; a < static_cast<int>(block.m.num_nodes()); ++a)
    if (block.m.nodes[a](2) > 2.0 - 1e-9) reaction += problem.f_int()(3 * a + 2);
  EXPECT_NEAR(reaction, P33 * 4.0, 1e-8 * std::abs(P33 * 4.0));
  // Lateral displacement of the free corner (2, 2, 2): (l - 1) 2 mm.
  for (int a = 0; a < static_cast<int>(block.m.num_nodes()); ++a)
    if ((block.m.nodes[a] - Vec3::Constant(2.0)).norm() < 1e-9) {
      EXPECT_NEAR(problem.u()(3 * a), 2.0 * (l - 1.0), 1e-9);
    }
}

TEST(Newton, PredictorReproducesTheLinearPatchAndSavesIterations) {
  // Linearised about the undeformed state, the predictor is a linear-elastic patch test: interior
  // nodes land on (F - I) X to 1e-10 mm on a distorted mesh.
  const mesh::Mesh regular = test::distorted_block(mesh::ElementType::hex8, 2, 0.0);
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 2, 0.15);
  const Mat3 G = test::general_F() - Mat3::Identity();
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  Eigen::VectorXd u_new = Eigen::VectorXd::Zero(3 * m.num_nodes());
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a)
    if (test::on_block_boundary(regular, a)) {
      u_new.segment<3>(3 * a) = G * m.nodes[a];
      for (int i = 0; i < 3; ++i) constrained[3 * a + i] = true;
    }
  Section s{"all", {}, test::neo_hookean(), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), constrained), {1});
  StateStore state = assembler.make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u_new.size());
  EquilibriumProblem problem(assembler, state, zero, u_new, zero, 0.0);
  auto linear = make_linear_solver(LinearSolverKind::cholesky);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(assembler.dofs().num_free());
  problem.predict(x, *linear);
  Eigen::VectorXd u = u_new;
  assembler.dofs().scatter_free(x, u);
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a)
    EXPECT_LE((u.segment<3>(3 * a) - G * m.nodes[a]).cwiseAbs().maxCoeff(), 1e-10);

  // Uniaxial compression: with the predictor Newton needs fewer corrections than without.
  int iterations[2];
  for (int with_predictor : {0, 1}) {
    UniaxialBlock block(2, -0.6, test::neo_hookean(), Formulation::full);
    StateStore st = block.assembler->make_state_store();
    EquilibriumProblem p(*block.assembler, st, zero.head(block.u_new.size()), block.u_new,
                         zero.head(block.u_new.size()), 0.0);
    auto solver = make_linear_solver(LinearSolverKind::cholesky_or_lu);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
    if (with_predictor) p.predict(y, *solver);
    const NewtonResult r = solve_newton(p, *solver, y);
    ASSERT_TRUE(r.converged()) << r.message;
    iterations[with_predictor] = r.iterations;
  }
  EXPECT_LT(iterations[1], iterations[0]);
}

TEST(Newton, ZeroLoadConvergesWithoutIterations) {
  UniaxialBlock block(1, 0.0, test::neo_hookean(), Formulation::full);
  StateStore state = block.assembler->make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  EquilibriumProblem problem(*block.assembler, state, zero, block.u_new, zero, 0.0);
  auto linear = make_linear_solver(LinearSolverKind::cholesky);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
  const NewtonResult result = solve_newton(problem, *linear, x);
  EXPECT_TRUE(result.converged());
  EXPECT_EQ(result.iterations, 0);
}

TEST(Newton, MaterialFailureIsReportedNotConverged) {
  // Compressing the block to 5 % of its height in one increment inverts the elements: J <= 0.
  UniaxialBlock block(1, -1.98, test::neo_hookean(), Formulation::full);
  StateStore state = block.assembler->make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  Eigen::VectorXd u_bad = block.u_new;
  u_bad *= 1.2;  // top below the bottom: every point has det F < 0
  EquilibriumProblem problem(*block.assembler, state, zero, u_bad, zero, 0.0);
  auto linear = make_linear_solver(LinearSolverKind::cholesky);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
  const NewtonResult result = solve_newton(problem, *linear, x);
  EXPECT_EQ(result.outcome, NewtonOutcome::failed);
  EXPECT_NE(result.message.find("element 1"), std::string::npos) << result.message;
}

TEST(Newton, IterationLimitGivesDivergedNotConverged) {
  UniaxialBlock block(2, -0.6, test::neo_hookean(), Formulation::full);
  StateStore state = block.assembler->make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  EquilibriumProblem problem(*block.assembler, state, zero, block.u_new, zero, 0.0);
  auto linear = make_linear_solver(LinearSolverKind::cholesky_or_lu);
  NewtonOptions options;
  options.max_iterations = 1;  // quadratic convergence needs more than one correction here
  Eigen::VectorXd x = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
  const NewtonResult result = solve_newton(problem, *linear, x, options);
  EXPECT_EQ(result.outcome, NewtonOutcome::diverged);
  EXPECT_EQ(result.iterations, 1);
}

TEST(Newton, UnconstrainedRigidBodyModeIsSingular) {
  // Only the top face is loaded (z) and nothing holds x, y: the tangent is singular.
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 1, 0.0);
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  Section s{"all", {0}, test::neo_hookean(), Formulation::full, 0.0};
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), constrained), {1});
  StateStore state = assembler.make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * m.num_nodes());
  Eigen::VectorXd f_ext = zero;
  for (int a = 4; a < 8; ++a) f_ext(3 * a + 2) = 1e-3;  // unbalanced load [N]
  EquilibriumProblem problem(assembler, state, zero, zero, f_ext, 0.0);
  auto linear = make_linear_solver(LinearSolverKind::cholesky_or_lu);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(assembler.dofs().num_free());
  const NewtonResult result = solve_newton(problem, *linear, x);
  EXPECT_EQ(result.outcome, NewtonOutcome::singular);
  EXPECT_EQ(result.message, singular_stiffness_message);
}

}  // namespace
}  // namespace cushion::solver
