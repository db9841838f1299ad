// Benchmark (not a test, not run by ctest): assembly throughput for 1..N threads and one Newton
// solve of a compressed foam block. Usage: bench_solver [elements_per_axis=20] [max_threads=2]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "material/hyperfoam.hpp"
#include "mesh/structured_hex.hpp"
#include "solver/equilibrium.hpp"

using namespace cushion;
using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 20;
  const unsigned max_threads = argc > 2 ? std::atoi(argv[2]) : std::max(1u, std::thread::hardware_concurrency());
  mesh::BlockSpec spec;
  spec.high = Eigen::Vector3d(100, 100, 50);  // [mm]
  spec.n = {n, n, std::max(1, n / 2)};
  const mesh::Mesh m = mesh::structured_block(spec);
  auto foam = std::make_shared<material::Hyperfoam>(std::vector<material::HyperfoamTerm>{{0.02, 8.0, 0.1}});

  // Bottom fixed, top pushed down by 10 % of the height.
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  Eigen::VectorXd u_end = Eigen::VectorXd::Zero(3 * m.num_nodes());
  for (std::size_t a = 0; a < m.num_nodes(); ++a) {
    const double z = m.nodes[a](2);
    if (z < 1e-9) constrained[3 * a] = constrained[3 * a + 1] = constrained[3 * a + 2] = true;
    if (z > 50 - 1e-9) constrained[3 * a + 2] = true, u_end(3 * a + 2) = -5.0;
  }
  solver::Section section{"foam", {}, foam, solver::Formulation::full, 0.0};
  for (std::size_t e = 0; e < m.num_elements(); ++e) section.elements.push_back(static_cast<int>(e));
  std::printf("mesh: %zu hex8, %zu nodes\n", m.num_elements(), m.num_nodes());

  for (unsigned threads = 1; threads <= max_threads; ++threads) {
    auto t0 = Clock::now();
    const solver::Assembler assembler(m, {section}, solver::DofMap(m.num_nodes(), constrained), {threads});
    const double setup = seconds_since(t0);
    solver::StateStore state = assembler.make_state_store();
    solver::SparseMatrix K = assembler.make_matrix();
    Eigen::VectorXd f;
    const int repeats = 5;
    t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) assembler.assemble(u_end * 0.0, u_end * 0.5, 0.0, state, f, &K);
    std::printf("threads %u: setup (colouring + pattern) %.3f s, assembly %.4f s each, %zu colours, nnz %ld\n",
                threads, setup, seconds_since(t0) / repeats, assembler.num_colours(), static_cast<long>(K.nonZeros()));
  }

  const solver::Assembler assembler(m, {section}, solver::DofMap(m.num_nodes(), constrained), {max_threads});
  solver::StateStore state = assembler.make_state_store();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u_end.size());
  solver::EquilibriumProblem problem(assembler, state, zero, u_end, zero, 0.0);
  auto linear = solver::make_linear_solver(solver::LinearSolverKind::cholesky_or_lu);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(assembler.dofs().num_free());
  auto t0 = Clock::now();
  problem.predict(x, *linear);
  const solver::NewtonResult result = solve_newton(problem, *linear, x, {}, [](const solver::NewtonIterate& it) {
    std::printf("  %s\n", solver::format_iterate(it).c_str());
  });
  std::printf("Newton: %s in %d iterations, %.3f s (linear solver %s, %d analyses)\n",
              solver::to_string(result.outcome).c_str(), result.iterations, seconds_since(t0),
              linear->method().c_str(), linear->analyses());
  return result.converged() ? 0 : 1;
}
