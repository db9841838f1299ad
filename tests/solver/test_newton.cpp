// Requirement: the Newton driver converges quadratically with the consistent tangent, reaches the
// exact homogeneous solution, and reports (never hides) divergence, material failure and singular
// tangents. With tangent reuse (modified Newton) it reaches the same solution to the same tolerance
// at a linear rate with fewer factorizations, keeps the factor across increments while it contracts,
// refactorizes when it does not, and drops it on failure. The predictor factorizes nothing when its
// right-hand side is negligible.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/equilibrium.hpp"
#include "tests/solver/counting_linear_solver.hpp"
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

/// One increment of the uniaxial block from rest to the top displacement of `block`: predictor then
/// Newton with `options`, factor record `factor` (tangent reuse) and the counting solver `linear`.
NewtonResult compress(UniaxialBlock& block, StateStore& state, const Eigen::VectorXd& u_old,
                      const Eigen::VectorXd& u_new, test::CountingLinearSolver& linear, const NewtonOptions& options,
                      TangentFactor* factor, Eigen::VectorXd& u_out, bool predictor_reuses = true) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u_new.size());
  EquilibriumProblem problem(*block.assembler, state, u_old, u_new, zero, 0.0);
  Eigen::VectorXd x = block.assembler->dofs().gather_free(u_old);
  problem.predict(x, linear, options.tangent_reuse.enabled && predictor_reuses ? factor : nullptr);
  const NewtonResult result = solve_newton(problem, linear, x, options, {}, factor);
  u_out = problem.u();
  return result;
}

NewtonOptions tight_options() {
  NewtonOptions options;
  options.residual_tolerance = 1e-11;
  options.correction_tolerance = 1e-11;
  options.max_iterations = 60;
  return options;
}

TEST(Newton, TangentReuseReachesTheSameSolutionAtALinearRate) {
  // 30 % compression in one increment (predictor, then Newton to 1e-11): full Newton and modified
  // Newton end within 1e-9 mm of each other; modified Newton factorizes less, and its residual
  // ratios ||r_k+1|| / ||r_k|| on reused factors stay below max_contraction, above 1e-3 and tend to
  // a constant (linear rate; observed 0.152 here), while full Newton's fall quadratically (above).
  Eigen::VectorXd u_full, u_modified;
  int factorizations[2];
  NewtonResult results[2];
  for (int reuse : {0, 1}) {
    UniaxialBlock block(2, -0.6, test::neo_hookean(), Formulation::full);
    StateStore state = block.assembler->make_state_store();
    test::CountingLinearSolver linear(LinearSolverKind::cholesky_or_lu);
    NewtonOptions options = tight_options();
    options.tangent_reuse.enabled = reuse;
    TangentFactor factor;
    results[reuse] = compress(block, state, Eigen::VectorXd::Zero(block.u_new.size()), block.u_new, linear, options,
                              &factor, reuse ? u_modified : u_full);
    ASSERT_TRUE(results[reuse].converged()) << results[reuse].message;
    factorizations[reuse] = linear.factorizations;
  }
  EXPECT_LE((u_full - u_modified).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(factorizations[1], factorizations[0]);
  EXPECT_GT(results[1].iterations, results[0].iterations);

  const auto& h = results[1].history;
  const double r0 = h[0].residual_norm;
  std::string rates;
  int linear_steps = 0;
  std::vector<double> observed;
  for (std::size_t k = 1; k < h.size(); ++k) {
    if (h[k].new_tangent || h[k].residual_norm < 1e-12 * r0) continue;
    const double rate = h[k].residual_norm / h[k - 1].residual_norm;
    observed.push_back(rate);
    rates += " " + std::to_string(rate);
    EXPECT_LE(rate, NewtonOptions{}.tangent_reuse.max_contraction) << "iteration " << k;
    EXPECT_GE(rate, 1e-3) << "iteration " << k;
    ++linear_steps;
  }
  EXPECT_GE(linear_steps, 3);
  // Linear convergence: a constant ratio (the last two agree to 1 %).
  if (observed.size() >= 2) {
    EXPECT_NEAR(observed.back(), observed[observed.size() - 2], 1e-2 * observed.back());
  }
  std::printf("modified Newton: %d corrections, %d factorizations (full Newton: %d, %d); rates on reused factors:%s\n",
              results[1].iterations, factorizations[1], results[0].iterations, factorizations[0], rates.c_str());
}

TEST(Newton, TangentReuseKeepsTheFactorAcrossIncrementsAndDropsItOnFailure) {
  // Two increments of 5 % compression: the second reuses the factor of the first (no factorization)
  // and ends where full Newton ends (1e-9 mm).
  UniaxialBlock block(2, -0.1, test::neo_hookean(), Formulation::full);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  Eigen::VectorXd u_end[2];
  for (int reuse : {0, 1}) {
    StateStore state = block.assembler->make_state_store();
    test::CountingLinearSolver linear(LinearSolverKind::cholesky);
    NewtonOptions options = tight_options();
    options.tangent_reuse.enabled = reuse;
    TangentFactor factor;
    Eigen::VectorXd u1;
    ASSERT_TRUE(compress(block, state, zero, block.u_new, linear, options, &factor, u1).converged());
    state.commit();
    const int first = linear.factorizations;
    ASSERT_TRUE(compress(block, state, u1, 2.0 * block.u_new, linear, options, &factor, u_end[reuse]).converged());
    if (reuse) {
      EXPECT_TRUE(factor.current);
      EXPECT_EQ(linear.factorizations, first) << "second increment refactorized";
    } else {
      EXPECT_GT(linear.factorizations, first);
    }
  }
  EXPECT_LE((u_end[0] - u_end[1]).cwiseAbs().maxCoeff(), 1e-9);

  // An unconverged attempt (iteration limit) drops the factor: the retry starts with a new one.
  StateStore state = block.assembler->make_state_store();
  test::CountingLinearSolver linear(LinearSolverKind::cholesky);
  NewtonOptions options = tight_options();
  options.tangent_reuse.enabled = true;
  options.max_iterations = 1;
  TangentFactor factor;
  Eigen::VectorXd u;
  EXPECT_EQ(compress(block, state, zero, 4.0 * block.u_new, linear, options, &factor, u).outcome,
            NewtonOutcome::diverged);
  EXPECT_FALSE(factor.current);
}

TEST(Newton, SlowContractionRefactorizesLikeFullNewton) {
  // max_contraction below any achievable rate: every correction gets a new factorization, so the
  // iterates equal full Newton's (residual history to 1e-9 relative) with the same count (the
  // predictor's factor is not handed to Newton here, as in full Newton).
  NewtonResult results[2];
  int factorizations[2];
  for (int reuse : {0, 1}) {
    UniaxialBlock block(2, -0.6, test::neo_hookean(), Formulation::full);
    StateStore state = block.assembler->make_state_store();
    test::CountingLinearSolver linear(LinearSolverKind::cholesky_or_lu);
    NewtonOptions options = tight_options();
    options.tangent_reuse = {reuse == 1, 1e-30};
    TangentFactor factor;
    Eigen::VectorXd u;
    results[reuse] = compress(block, state, Eigen::VectorXd::Zero(block.u_new.size()), block.u_new, linear, options,
                              &factor, u, false);
    ASSERT_TRUE(results[reuse].converged());
    factorizations[reuse] = linear.factorizations;
  }
  EXPECT_EQ(factorizations[0], factorizations[1]);
  ASSERT_EQ(results[0].history.size(), results[1].history.size());
  for (std::size_t k = 0; k < results[0].history.size(); ++k) {
    const double a = results[0].history[k].residual_norm, b = results[1].history[k].residual_norm;
    if (a > 1e-12 * results[0].history[0].residual_norm) {
      EXPECT_NEAR(b, a, 1e-9 * a) << "iteration " << k;
    }
  }
}

TEST(Newton, PredictorFactorizesNothingWhenItsRightHandSideIsNegligible) {
  // At rest with nothing prescribed the predictor's right-hand side is exactly zero: no
  // factorization, no solve. With a prescribed increment it factorizes once and solves once.
  UniaxialBlock block(2, -0.2, test::neo_hookean(), Formulation::full);
  StateStore state = block.assembler->make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(block.u_new.size());
  for (int loaded : {0, 1}) {
    EquilibriumProblem problem(*block.assembler, state, zero, loaded ? block.u_new : zero, zero, 0.0);
    test::CountingLinearSolver linear(LinearSolverKind::cholesky);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(block.assembler->dofs().num_free());
    problem.predict(x, linear);
    EXPECT_EQ(problem.predictor_solved(), loaded == 1);
    EXPECT_EQ(linear.factorizations, loaded);
    EXPECT_EQ(linear.solves, loaded);
    if (!loaded) {
      EXPECT_EQ(solve_newton(problem, linear, x).iterations, 0);
    }
    EXPECT_EQ(linear.factorizations, loaded);
  }
}

}  // namespace
}  // namespace cushion::solver
