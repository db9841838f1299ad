// Benchmark (not a test, not run by ctest).
//   bench_solver [elements_per_axis=20] [max_threads=2]
//       assembly throughput for 1..max_threads threads and one Newton solve of a compressed block;
//   bench_solver factor [n=20] [orderings=default,amd,metis,nesdis]
//       CHOLMOD setup on the tangent of the quarter cube case (40 x 40 x 80 mm, n^3 hex8, symmetry
//       planes, top compressed 20 %): for each ordering the analysis and factorization times, the
//       ordering CHOLMOD selected, nnz(L) and flops, with 1 and 2 OpenBLAS threads; then the
//       project's own solver (make_linear_solver) and its analysis_report().
#include <dlfcn.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>

#include <Eigen/CholmodSupport>

#include "material/hyperfoam.hpp"
#include "mesh/structured_hex.hpp"
#include "quarter_cube.hpp"
#include "solver/equilibrium.hpp"

using namespace cushion;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
/// CPU seconds of the process (all threads) since c0: less sensitive to a loaded machine than wall time.
double cpu_since(std::clock_t c0) { return double(std::clock() - c0) / CLOCKS_PER_SEC; }

/// OpenBLAS thread control through the dynamic symbols (absent with another BLAS).
int blas_threads(int set = 0) {
  using Set = void (*)(int);
  using Get = int (*)();
  if (set > 0)
    if (auto f = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(set);
  auto g = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return g ? g() : -1;
}

const char* ordering_name(int o) {
  switch (o) {
    case CHOLMOD_AMD: return "amd";
    case CHOLMOD_METIS: return "metis";
    case CHOLMOD_NESDIS: return "nesdis";
    case CHOLMOD_NATURAL: return "natural";
  }
  return "other";
}

int bench_factor(int n, const std::string& orderings) {
  const bench::CubeTangent tangent = bench::compressed_cube_tangent(n);
  const solver::SparseMatrix& K = tangent.K;
  std::printf("quarter cube %d^3 hex8: %ld free dofs, %ld nonzeros (full), assembly %.3f s; BLAS threads %d\n", n,
              static_cast<long>(K.rows()), static_cast<long>(K.nonZeros()), tangent.assembly_s, blas_threads());
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
  auto t0 = Clock::now();

  std::printf("%-8s %-7s %-8s %10s %10s %10s %12s %12s %10s\n", "ordering", "threads", "selected", "analyse_s",
              "factor_s", "factor_cpu", "nnz(L)", "flop", "residual");
  std::stringstream list(orderings);
  for (std::string name; std::getline(list, name, ',');) {
    for (int threads : {1, 2}) {
      blas_threads(threads);
      Eigen::CholmodSupernodalLLT<solver::SparseMatrix, Eigen::Lower> llt;
      cholmod_common& cm = llt.cholmod();
      if (name != "default") {
        cm.nmethods = 1;
        cm.method[0].ordering = name == "amd" ? CHOLMOD_AMD : name == "metis" ? CHOLMOD_METIS : CHOLMOD_NESDIS;
        cm.postorder = 1;
      }
      t0 = Clock::now();
      llt.analyzePattern(K);
      const double analyse = seconds_since(t0);
      t0 = Clock::now();
      const std::clock_t c0 = std::clock();
      llt.factorize(K);
      const double factor = seconds_since(t0), factor_cpu = cpu_since(c0);
      const Eigen::VectorXd x = llt.solve(b);
      std::printf("%-8s %-7d %-8s %10.3f %10.3f %10.3f %12.4g %12.4g %10.2e\n", name.c_str(), blas_threads(),
                  ordering_name(cm.method[cm.selected].ordering), analyse, factor, factor_cpu, cm.lnz, cm.fl,
                  (K.selfadjointView<Eigen::Lower>() * x - b).norm() / b.norm());
      std::fflush(stdout);
    }
  }
  blas_threads(2);
  auto linear = solver::make_linear_solver(solver::LinearSolverKind::cholesky_or_lu);
  t0 = Clock::now();
  linear->factorize(K);
  std::printf("make_linear_solver(cholesky_or_lu): analysis + factorization %.3f s, %s; %s\n", seconds_since(t0),
              linear->method().c_str(), linear->analysis_report().c_str());
  t0 = Clock::now();
  const std::clock_t c0 = std::clock();
  linear->factorize(K);
  std::printf("  second factorization (analysis reused, %d analyses): %.3f s wall, %.3f s CPU\n", linear->analyses(),
              seconds_since(t0), cpu_since(c0));
  return 0;
}

int bench_assembly(int n, unsigned max_threads) {
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
    const solver::Assembler assembler(m, {section}, solver::DofMap(m.num_nodes(), constrained), {threads, nullptr});
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

  const solver::Assembler assembler(m, {section}, solver::DofMap(m.num_nodes(), constrained), {max_threads, nullptr});
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
  std::printf("  %s\n", linear->analysis_report().c_str());
  return result.converged() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "factor") == 0)
    return bench_factor(argc > 2 ? std::atoi(argv[2]) : 20, argc > 3 ? argv[3] : "default,amd,metis,nesdis");
  const int n = argc > 1 ? std::atoi(argv[1]) : 20;
  const unsigned max_threads = argc > 2 ? std::atoi(argv[2]) : std::max(1u, std::thread::hardware_concurrency());
  return bench_assembly(n, max_threads);
}
