#pragma once
/// Helpers for the dynamics tests: a hex8 column [0,w]^2 x [0,L], its DOF sets, a static preload.
#include <complex>
#include <memory>

#include "mesh/structured_hex.hpp"
#include "solver/dynamics/linearised_system.hpp"
#include "solver/dynamics/steady_state.hpp"
#include "solver/equilibrium.hpp"
#include "solver/linear_solver.hpp"

namespace cushion::solver::test {

using cplx = std::complex<double>;

/// Column of nz hex8 elements (nx = ny = 1 unless given), width w, height L [mm].
inline mesh::Mesh column(double w, double L, int nz, int nxy = 1) {
  mesh::BlockSpec spec;
  spec.low = Vec3::Zero();
  spec.high = Vec3(w, w, L);
  spec.n = {nxy, nxy, nz};
  return mesh::structured_block(spec);
}

/// DOFs of component c of the nodes of a set.
inline std::vector<int> set_dofs(const mesh::Mesh& m, const std::string& set, int c) {
  std::vector<int> d;
  for (int n : m.node_sets.at(set)) d.push_back(DofMap::dof(n, c));
  return d;
}

/// All x and y DOFs (lateral confinement).
inline std::vector<int> lateral_dofs(const mesh::Mesh& m) {
  std::vector<int> d;
  for (std::size_t n = 0; n < m.num_nodes(); ++n) d.push_back(3 * n), d.push_back(3 * n + 1);
  return d;
}

inline std::vector<bool> constrained_mask(const mesh::Mesh& m, const std::vector<std::vector<int>>& groups) {
  std::vector<bool> c(3 * m.num_nodes(), false);
  for (const auto& g : groups)
    for (int d : g) c[d] = true;
  return c;
}

/// Quasi-static ramp of the DOFs `driven` to `value` [mm] in `steps` increments of dt [s] each
/// (dt huge: relaxed). Updates u and commits the state; fails the test on non-convergence.
inline void ramp(const Assembler& A, StateStore& st, Eigen::VectorXd& u, const std::vector<int>& driven, double value,
                 int steps, double dt) {
  auto lin = make_linear_solver(LinearSolverKind::lu);
  const double start = driven.empty() ? 0.0 : u(driven.front());
  for (int i = 1; i <= steps; ++i) {
    Eigen::VectorXd target = u;
    for (int d : driven) target(d) = start + (value - start) * i / steps;
    EquilibriumProblem P(A, st, u, target, Eigen::VectorXd::Zero(u.size()), dt);
    Eigen::VectorXd x = A.dofs().gather_free(u);
    P.predict(x, *lin);
    NewtonOptions o;
    o.residual_tolerance = 1e-9;
    o.correction_tolerance = 1e-9;
    o.prescribed_increment = std::abs(value - start) / steps;
    const NewtonResult r = solve_newton(P, *lin, x, o);
    if (!r.converged()) throw std::runtime_error("ramp did not converge: " + r.message);
    u = P.u();
    st.commit();
  }
}

/// Relative error of a complex amplitude and its phase difference [deg].
inline double amplitude_error(cplx a, cplx b) { return std::abs(std::abs(a) / std::abs(b) - 1.0); }
inline double phase_error_deg(cplx a, cplx b) { return std::abs(std::arg(a / b)) * 180.0 / M_PI; }

}  // namespace cushion::solver::test
