#pragma once
// The benchmarks' model: the quarter cube of the cube_compression case (40 x 40 x 80 mm, n^3 hex8,
// symmetry planes x = 0, y = 0, z = 0, top prescribed in z) and its tangent at 20 % compression.
#include <chrono>
#include <memory>
#include <thread>

#include "material/hyperfoam.hpp"
#include "mesh/structured_hex.hpp"
#include "solver/assembler.hpp"

namespace cushion::bench {

/// Quarter cube with symmetry planes x = 0, y = 0, z = 0 and the top prescribed in z (to top_mm).
struct CubeModel {
  mesh::Mesh m;
  std::vector<bool> constrained;
  Eigen::VectorXd u_end;
};

inline CubeModel quarter_cube(int n, double top_mm) {
  mesh::BlockSpec spec;
  spec.high = Eigen::Vector3d(40, 40, 80);  // [mm]
  spec.n = {n, n, n};
  CubeModel c{mesh::structured_block(spec), {}, {}};
  c.constrained.assign(3 * c.m.num_nodes(), false);
  c.u_end = Eigen::VectorXd::Zero(3 * c.m.num_nodes());
  for (std::size_t a = 0; a < c.m.num_nodes(); ++a) {
    const Eigen::Vector3d& X = c.m.nodes[a];
    for (int i = 0; i < 3; ++i)
      if (X(i) < 1e-9) c.constrained[3 * a + i] = true;
    if (X(2) > 80 - 1e-9) c.constrained[3 * a + 2] = true, c.u_end(3 * a + 2) = top_mm;
  }
  return c;
}

/// The quarter cube's tangent [N/mm] at homogeneous 20 % compression of a one-term hyperfoam (nu = 0:
/// no lateral motion): a representative SPD tangent; `assembly_s` the wall time of its assembly.
struct CubeTangent {
  CubeModel c;
  std::unique_ptr<solver::Assembler> assembler;
  solver::SparseMatrix K;
  double assembly_s = 0.0;
};

inline CubeTangent compressed_cube_tangent(int n) {
  CubeTangent t{quarter_cube(n, -16.0), nullptr, {}, 0.0};
  auto foam = std::make_shared<material::Hyperfoam>(std::vector<material::HyperfoamTerm>{{0.01, 10.0, 0.0}});
  solver::Section section{"foam", {}, foam, solver::Formulation::full, 0.0};
  for (std::size_t e = 0; e < t.c.m.num_elements(); ++e) section.elements.push_back(static_cast<int>(e));
  t.assembler = std::make_unique<solver::Assembler>(t.c.m, std::vector<solver::Section>{section},
                                                    solver::DofMap(t.c.m.num_nodes(), t.c.constrained),
                                                    solver::AssemblyOptions{std::max(1u, std::thread::hardware_concurrency()), nullptr});
  solver::StateStore state = t.assembler->make_state_store();
  t.K = t.assembler->make_matrix();
  Eigen::VectorXd f;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(t.c.u_end.size());
  for (std::size_t a = 0; a < t.c.m.num_nodes(); ++a) u(3 * a + 2) = -0.2 * t.c.m.nodes[a](2);
  const auto t0 = std::chrono::steady_clock::now();
  t.assembler->assemble(u, u, 0.0, state, f, &t.K);
  t.assembly_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

}  // namespace cushion::bench
