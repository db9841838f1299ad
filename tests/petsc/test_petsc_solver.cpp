// Requirement: the PETSc solver (CG + GAMG with rigid-body modes, MUMPS LU) solves an elasticity tangent
// as CHOLMOD does (max |x - x_cholmod| <= 1e-8 max |x_cholmod|), keeps its preconditioner while the
// Krylov iterations stay low, reports a Krylov method that does not converge as LinearSolveError, and
// names bad options before a run.
#include <gtest/gtest.h>

#include "material/neo_hookean.hpp"
#include "mesh/structured_hex.hpp"
#include "solver/assembler.hpp"
#include "solver/petsc/petsc_solver.hpp"

namespace cushion::solver {
namespace {

/// Neo-Hookean block 20 x 20 x 10 mm of n x n x n/2 hex8, bottom fixed, top compressed by `squeeze` [mm]
/// (lateral faces free): the tangent at that state.
struct ElasticBlock {
  mesh::Mesh mesh;
  std::vector<bool> constrained;
  std::unique_ptr<Assembler> assembler;
  SparseMatrix K;

  explicit ElasticBlock(int n) {
    mesh::BlockSpec spec;
    spec.high = Eigen::Vector3d(20, 20, 10);
    spec.n = {n, n, std::max(1, n / 2)};
    mesh = mesh::structured_block(spec);
    constrained.assign(3 * mesh.num_nodes(), false);
    for (std::size_t a = 0; a < mesh.num_nodes(); ++a) {
      if (mesh.nodes[a](2) < 1e-9) constrained[3 * a] = constrained[3 * a + 1] = constrained[3 * a + 2] = true;
      if (mesh.nodes[a](2) > 10 - 1e-9) constrained[3 * a + 2] = true;
    }
    Section section{"rubber", {}, std::make_shared<material::NeoHookean>(0.4, 2.0), Formulation::full, 0.0};
    for (std::size_t e = 0; e < mesh.num_elements(); ++e) section.elements.push_back(static_cast<int>(e));
    assembler = std::make_unique<Assembler>(mesh, std::vector<Section>{section}, DofMap(mesh.num_nodes(), constrained));
    K = assembler->make_matrix();
  }
  /// The tangent [N/mm] with the top moved down by `squeeze` [mm] (linear in z).
  const SparseMatrix& tangent(double squeeze) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.num_nodes()));
    for (std::size_t a = 0; a < mesh.num_nodes(); ++a) u(3 * a + 2) = -squeeze * mesh.nodes[a](2) / 10.0;
    StateStore state = assembler->make_state_store();
    Eigen::VectorXd f;
    assembler->assemble(u, u, 0.0, state, f, &K);
    return K;
  }
  const DofMap& dofs() const { return assembler->dofs(); }
};

Eigen::VectorXd cholmod_solution(const SparseMatrix& K, const Eigen::VectorXd& b) {
  auto direct = make_linear_solver(LinearSolverKind::cholesky);
  direct->factorize(K);
  return direct->solve(b);
}

double relative_difference(const Eigen::VectorXd& x, const Eigen::VectorXd& reference) {
  return (x - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

/// A load with every component present (not only the loaded direction).
Eigen::VectorXd load(Eigen::Index n) { return Eigen::VectorXd::LinSpaced(n, -1.0, 2.0); }

TEST(PetscSolver, GamgWithRigidBodyModesAgreesWithCholmod) {
  ElasticBlock block(8);
  const SparseMatrix& K = block.tangent(1.0);
  const Eigen::VectorXd b = load(K.rows());
  auto solver = petsc::make_solver(true, "-ksp_rtol 1e-12");
  solver->set_geometry(block.dofs(), block.mesh.nodes);
  solver->factorize(K);
  const Eigen::VectorXd x = solver->solve(b);
  EXPECT_LE(relative_difference(x, cholmod_solution(K, b)), 1e-8);
  EXPECT_EQ(solver->method(), "petsc cg + gamg");
  EXPECT_NE(solver->analysis_report().find("6 rigid-body modes"), std::string::npos) << solver->analysis_report();
  EXPECT_NE(solver->last_solve_report().find("CONVERGED"), std::string::npos) << solver->last_solve_report();
}

TEST(PetscSolver, WithoutGeometrySolvesTheFreeDofsOnly) {
  ElasticBlock block(6);
  const SparseMatrix& K = block.tangent(0.5);
  const Eigen::VectorXd b = load(K.rows());
  auto solver = petsc::make_solver(false, "-ksp_rtol 1e-12");  // GMRES
  solver->factorize(K);
  EXPECT_LE(relative_difference(solver->solve(b), cholmod_solution(K, b)), 1e-8);
  EXPECT_NE(solver->analysis_report().find("near-null space: none"), std::string::npos) << solver->analysis_report();
}

TEST(PetscSolver, MumpsLuAgreesWithCholmod) {
  ElasticBlock block(6);
  const SparseMatrix& K = block.tangent(1.0);
  const Eigen::VectorXd b = load(K.rows());
  auto solver = petsc::make_solver(true, "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps");
  solver->set_geometry(block.dofs(), block.mesh.nodes);
  solver->factorize(K);
  EXPECT_LE(relative_difference(solver->solve(b), cholmod_solution(K, b)), 1e-10);
  EXPECT_EQ(solver->method(), "petsc preonly + lu (mumps)");
  // A direct solve never keeps an old factorization: the second tangent is factorized again.
  const SparseMatrix& K2 = block.tangent(0.5);
  solver->factorize(K2);
  EXPECT_LE(relative_difference(solver->solve(b), cholmod_solution(K2, b)), 1e-10);
  EXPECT_NE(solver->analysis_report().find("2 preconditioner setups"), std::string::npos) << solver->analysis_report();
}

TEST(PetscSolver, KeepsThePreconditionerWhileIterationsStayLow) {
  ElasticBlock block(6);
  const Eigen::VectorXd b = load(block.tangent(0.0).rows());
  auto run = [&](const std::string& options) {
    auto solver = petsc::make_solver(true, "-ksp_rtol 1e-12 " + options);
    solver->set_geometry(block.dofs(), block.mesh.nodes);
    for (double squeeze : {0.0, 0.5, 1.0}) {
      const SparseMatrix& K = block.tangent(squeeze);
      solver->factorize(K);
      // A reused preconditioner still solves the current matrix to the tolerance.
      EXPECT_LE(relative_difference(solver->solve(b), cholmod_solution(K, b)), 1e-8) << options << " " << squeeze;
    }
    return solver->analysis_report();
  };
  EXPECT_NE(run("").find("1 preconditioner setups"), std::string::npos) << run("");
  EXPECT_NE(run("-cushion_pc_reuse_max_it 0").find("3 preconditioner setups"), std::string::npos);
}

TEST(PetscSolver, KrylovMethodThatDoesNotConvergeThrowsLinearSolveError) {
  ElasticBlock block(6);
  auto solver = petsc::make_solver(true, "-ksp_max_it 1");
  solver->set_geometry(block.dofs(), block.mesh.nodes);
  solver->factorize(block.tangent(1.0));
  try {
    solver->solve(load(block.K.rows()));
    ADD_FAILURE() << "no exception";
  } catch (const LinearSolveError& e) {
    EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("DIVERGED_ITS"), std::string::npos) << e.what();
  }
}

TEST(PetscOptions, NamesWhatIsWrong) {
  EXPECT_EQ(petsc::options_problem(true, ""), "");
  EXPECT_EQ(petsc::options_problem(true, "-ksp_type gmres -pc_type gamg -pc_gamg_threshold 0.01"), "");
  EXPECT_EQ(petsc::options_problem(true, "-ksp_max_it 1"), "");  // not converging is no input error
  EXPECT_EQ(petsc::options_problem(true, "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps"), "");
  EXPECT_NE(petsc::options_problem(true, "-ksp_tpye cg").find("unknown or unused PETSc option(s) -ksp_tpye"),
            std::string::npos);
  EXPECT_NE(petsc::options_problem(true, "-pc_type gamg -pc_gamg_bogus 3").find("-pc_gamg_bogus"), std::string::npos);
  EXPECT_NE(petsc::options_problem(true, "-ksp_type cgx").find("KSP type cgx"), std::string::npos);
  EXPECT_NE(petsc::options_problem(true, "-ksp_rtol abc").find("abc"), std::string::npos);
}

}  // namespace
}  // namespace cushion::solver
