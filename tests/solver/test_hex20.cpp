// Requirement: the 20-node bricks C3D20 (hex20, 3x3x3 Gauss) and C3D20R (hex20r, 2x2x2) converge
// faster than hex8 in bending, have no spurious zero-energy mode in an assembled mesh, and run end to
// end from an .inp deck to ParaView output.
// Checks:
// - Zero-energy modes (eigenvalues of K at u = 0 below 1e-10 max, NeoHookean nu = 0.44) of free
//   boxes of 1 mm elements: C3D20 1x1x1 and 4x1x1: 6 (rigid body); C3D20R 1x1x1: 12 (6 spurious: rank
//   48 = 8 points x 6 strains); C3D20R 4x1x1: more than 6 (a column one element wide keeps spurious
//   modes); C3D20R 2x2x1, 2x2x2 and distorted 2x2x2: 6 (no spurious mode once two elements side by side
//   in two directions).
// - Cantilever 10 x 1 x 1 mm, x = 0 clamped, tip face z-displacement 1e-3 mm (small strain),
//   NeoHookean lambda = 0 (nu = 0, E = 2 mu, G = mu): tip stiffness vs Timoshenko
//   k = 1 / (L^3 / (3 E I) + L / (kappa G A)), kappa = 5/6, on 4x1x1, 8x2x2, 16x4x4 elements. hex20 and
//   hex20r within 1 % of the beam on 8x2x2; hex8 locks (error > 10 times hex20's) on the same meshes;
//   hex20r on 4x1x1 is singular (the column's spurious modes).
// - `cushion run` path (load_case + run_analysis) on an .inp of 2 x 2 x 2 C3D20R: a 10 mm cube on
//   rollers compressed 40 % (hyperfoam with nu = 0: lateral stretch 1): RF3 = A0 * P11, the closed form
//   P11 = (2 / l) sum mu_i / alpha_i (l^alpha_i - 1), to 1e-8; the .vtu cells are VTK_QUADRATIC_HEXAHEDRON
//   (25) whose VTK edges (end, end, mid) have the mid node at the middle of the ends.
#include <gtest/gtest.h>

#include <cstdio>

#include "mesh/inp_reader.hpp"
#include "mesh/selectors.hpp"
#include "solver/contact/contact_set.hpp"
#include "solver/equilibrium.hpp"
#include "solver/output/vtu_reader.hpp"
#include "tests/solver/solver_fixtures.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

/// Number of eigenvalues of the free-free stiffness at u = 0 below 1e-10 of the largest.
int zero_energy_modes(const mesh::Mesh& m) {
  Section s{"all", {}, std::make_shared<material::NeoHookean>(0.05, 0.4), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), {}), {.num_threads = 1});
  StateStore state = assembler.make_state_store();
  SparseMatrix K = assembler.make_matrix();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * m.num_nodes()), f;
  assembler.assemble(u, u, 0.0, state, f, &K);
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(K)).eigenvalues();
  return static_cast<int>((eig.array().abs() < 1e-10 * eig.cwiseAbs().maxCoeff()).count());
}

/// A free box of nx x ny x nz hex20 / hex20r elements of size 1 mm.
mesh::Mesh box(mesh::ElementType type, int nx, int ny, int nz) {
  mesh::BlockSpec spec;
  spec.high = Vec3(nx, ny, nz);
  spec.n = {nx, ny, nz};
  return mesh::to_hex20(mesh::structured_block(spec), type);
}

TEST(Hex20Solver, ZeroEnergyModes) {
  const int full = zero_energy_modes(box(mesh::ElementType::hex20, 1, 1, 1));
  const int full_column = zero_energy_modes(box(mesh::ElementType::hex20, 4, 1, 1));
  const int reduced_one = zero_energy_modes(box(mesh::ElementType::hex20r, 1, 1, 1));
  const int reduced_column = zero_energy_modes(box(mesh::ElementType::hex20r, 4, 1, 1));
  const int reduced_slab = zero_energy_modes(box(mesh::ElementType::hex20r, 2, 2, 1));
  const int reduced_mesh = zero_energy_modes(box(mesh::ElementType::hex20r, 2, 2, 2));
  const int reduced_distorted = zero_energy_modes(test::distorted_block(mesh::ElementType::hex20r, 2, 0.15));
  std::printf("zero-energy modes (6 = rigid body only): C3D20 1x1x1 %d, 4x1x1 %d; C3D20R 1x1x1 %d, 4x1x1 %d, "
              "2x2x1 %d, 2x2x2 %d (distorted %d)\n",
              full, full_column, reduced_one, reduced_column, reduced_slab, reduced_mesh, reduced_distorted);
  EXPECT_EQ(full, 6);
  EXPECT_EQ(full_column, 6);
  EXPECT_EQ(reduced_one, 12);    // 60 dofs - rank 48 (8 points x 6 strains) = 6 rigid + 6 spurious
  EXPECT_GT(reduced_column, 6);  // a column one element wide keeps spurious modes (measured 5)
  EXPECT_EQ(reduced_slab, 6);
  EXPECT_EQ(reduced_mesh, 6);
  EXPECT_EQ(reduced_distorted, 6);
}

/// Tip stiffness [N/mm] of the cantilever [0,L] x [0,b] x [0,h] clamped at x = 0, tip face moved by
/// delta in z (x, y free), from one Newton solve; NaN if the solve fails.
double cantilever_stiffness(mesh::ElementType type, int nx, int ny, int nz, double mu) {
  const double L = 10.0, b = 1.0, h = 1.0, delta = 1e-3;
  mesh::BlockSpec spec;
  spec.high = Vec3(L, b, h);
  spec.n = {nx, ny, nz};
  mesh::Mesh m = mesh::structured_block(spec);
  if (type != mesh::ElementType::hex8) m = mesh::to_hex20(m, type);
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * m.num_nodes());
  std::vector<int> tip;
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a) {
    if (m.nodes[a].x() < 1e-9) constrained[3 * a] = constrained[3 * a + 1] = constrained[3 * a + 2] = true;
    if (m.nodes[a].x() > L - 1e-9) {
      constrained[3 * a + 2] = true;
      u(3 * a + 2) = delta;
      tip.push_back(a);
    }
  }
  Section s{"all", {}, std::make_shared<material::NeoHookean>(mu, 0.0), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), constrained), {.num_threads = 2});
  StateStore state = assembler.make_state_store();
  auto linear = make_linear_solver(LinearSolverKind::cholesky);
  NewtonOptions options;
  options.residual_tolerance = 1e-9;
  options.correction_tolerance = 1e-9;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u.size());
  EquilibriumProblem problem(assembler, state, zero, u, zero, 0.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(assembler.dofs().num_free());
  try {
    if (!solve_newton(problem, *linear, x, options).converged()) return NAN;
  } catch (const SingularMatrixError&) {
    return NAN;
  }
  double force = 0.0;
  for (int a : tip) force += problem.f_int()(3 * a + 2);
  return force / delta;
}

TEST(Hex20Solver, CantileverConvergesFasterThanHex8) {
  const double mu = 1000.0, E = 2.0 * mu, G = mu, L = 10.0, A = 1.0, I = 1.0 / 12.0, kappa = 5.0 / 6.0;
  const double k_beam = 1.0 / (L * L * L / (3.0 * E * I) + L / (kappa * G * A));
  const int meshes[3][3] = {{4, 1, 1}, {8, 2, 2}, {16, 4, 4}};
  double error[3][3];  // [type][mesh]
  const mesh::ElementType types[3] = {mesh::ElementType::hex8, mesh::ElementType::hex20, mesh::ElementType::hex20r};
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < 3; ++k) {
      const double stiffness = cantilever_stiffness(types[t], meshes[k][0], meshes[k][1], meshes[k][2], mu);
      error[t][k] = stiffness / k_beam - 1.0;
      std::printf("cantilever %-6s %2dx%dx%d: k = %.6e N/mm, error vs Timoshenko %+.4f %%\n",
                  mesh::to_string(types[t]).c_str(), meshes[k][0], meshes[k][1], meshes[k][2], stiffness,
                  100.0 * error[t][k]);
    }
  // C3D20R one element wide is singular (the spurious modes of a column survive the clamp).
  EXPECT_TRUE(std::isnan(error[2][0]));
  for (int t = 1; t < 3; ++t) {
    EXPECT_LT(std::abs(error[t][1]), 0.01) << mesh::to_string(types[t]);
    for (int k = t == 2 ? 1 : 0; k < 3; ++k) EXPECT_GT(std::abs(error[0][k]), 10.0 * std::abs(error[t][k])) << k;
  }
}

// Contact areas on 8-node faces: the top face nodes of a 2 x 2 x 2 C3D20R block of [0,2]^3 (21 nodes)
// share the 4 mm^2 exactly, every node a positive part (1e-14).
TEST(Hex20Solver, ContactAreasOfQuadraticFaces) {
  const mesh::Mesh m = box(mesh::ElementType::hex20r, 2, 2, 2);
  const std::vector<int> top = mesh::select_nodes(m, mesh::parse_selector("z == 2", "test"));
  ASSERT_EQ(top.size(), 21u);
  const std::vector<double> areas = tributary_areas(m, top);
  double sum = 0.0;
  for (double a : areas) {
    EXPECT_GT(a, 0.0);
    sum += a;
  }
  EXPECT_NEAR(sum, 4.0, 1e-14);
}

TEST(Hex20Solver, RunFromC3D20RDeckToVtk) {
  const auto dir = test::scratch_dir();
  mesh::BlockSpec spec;
  spec.high = Vec3::Constant(10.0);
  spec.n = {2, 2, 2};
  mesh::write_inp(mesh::to_hex20(mesh::structured_block(spec), mesh::ElementType::hex20r), (dir / "block.inp").string());
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  const auto file = test::write_text(dir / "case.json", R"({
    "mesh": {"inp": "block.inp"},
    "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.25},
               "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                            {"set": "bottom", "type": "symmetry_z"}, {"set": "top", "dof": "z", "value_mm": -4}],
               "output": {"frames_every_s": 0.5, "history": [{"set": "top", "quantities": ["RF3"]}]}}]})");
  test::run_case(file, dir / "out");

  // foam_json: hyperfoam terms (mu_kPa, alpha) = (10, 10), (0.1, -2), (0.5, 3), nu = 0.
  const double l = 0.6, mu[3] = {10e-3, 0.1e-3, 0.5e-3}, alpha[3] = {10.0, -2.0, 3.0};
  double P11 = 0.0;
  for (int i = 0; i < 3; ++i) P11 += 2.0 / l * mu[i] / alpha[i] * (std::pow(l, alpha[i]) - 1.0);
  const CsvTable h = test::read_history(dir / "out");
  const double rf3 = h.col("top.RF3_N").back();
  std::printf("C3D20R cube at 40 %%: RF3 = %.10g N, closed form %.10g N\n", rf3, 100.0 * P11);
  EXPECT_NEAR(rf3, 100.0 * P11, 1e-8 * std::abs(100.0 * P11));

  const auto entries = read_pvd(dir / "out" / "results.pvd");
  ASSERT_EQ(entries.size(), 3u);
  const VtuContents vtu = read_vtu(dir / "out" / entries.back().file);
  ASSERT_EQ(vtu.points.size(), 81u);
  ASSERT_EQ(vtu.cell_types.size(), 8u);
  for (std::size_t c = 0; c < 8; ++c) {
    EXPECT_EQ(vtu.cell_types[c], 25);  // VTK_QUADRATIC_HEXAHEDRON
    ASSERT_EQ(vtu.vtk_edges[c].size(), 12u);
    for (const auto& e : vtu.vtk_edges[c]) {
      ASSERT_EQ(e.size(), 3u);
      EXPECT_LT((vtu.points[e[2]] - 0.5 * (vtu.points[e[0]] + vtu.points[e[1]])).norm(), 1e-12);
    }
  }
  EXPECT_EQ(vtu.cell_data.at("J").values.size(), 8u);
}

}  // namespace
}  // namespace cushion::solver
