#pragma once
/// Helpers for the contact tests: a block model with symmetry/fixed supports and a Newton +
/// Uzawa increment loop against one contact set.
#include <memory>

#include "mesh/structured_hex.hpp"
#include "solver/contact/augmented_solve.hpp"
#include "solver/equilibrium.hpp"

namespace cushion::solver::test {

/// A block model: mesh, assembler with one section, state, linear solver.
struct ContactModel {
  mesh::Mesh mesh;
  std::unique_ptr<Assembler> assembler;
  StateStore state;
  std::unique_ptr<LinearSolver> linear;
  Eigen::VectorXd u;  ///< committed full displacements [mm]
};

/// Box [0,L]^3-like block from `spec`; constrained[dof] from `fix(node, component)`.
template <class Fix>
ContactModel make_model(const mesh::BlockSpec& spec, std::shared_ptr<const material::Material> mat, Fix fix,
                        LinearSolverKind kind = LinearSolverKind::cholesky_or_lu) {
  ContactModel m;
  m.mesh = mesh::structured_block(spec);
  std::vector<bool> constrained(3 * m.mesh.num_nodes(), false);
  for (int a = 0; a < static_cast<int>(m.mesh.num_nodes()); ++a)
    for (int i = 0; i < 3; ++i) constrained[3 * a + i] = fix(m.mesh.nodes[a], i);
  Section s{"all", {}, std::move(mat), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.mesh.num_elements()); ++e) s.elements.push_back(e);
  m.assembler = std::make_unique<Assembler>(m.mesh, std::vector<Section>{s}, DofMap(m.mesh.num_nodes(), constrained),
                                            AssemblyOptions{.num_threads = 2, .distribution = nullptr});
  m.state = m.assembler->make_state_store();
  m.linear = make_linear_solver(kind);
  m.u = Eigen::VectorXd::Zero(3 * m.mesh.num_nodes());
  return m;
}

/// One increment: constrained DOFs to u_prescribed (full vector), indenter at `position`; Newton
/// (tolerances `tol`) inside the Uzawa loop; commits on success. Returns the result; `last`
/// receives the first Newton solve (the one that carries the increment).
inline AugmentedResult contact_increment(ContactModel& m, ContactSet& set, const Vec3& position,
                                         const Eigen::VectorXd& u_prescribed, double tol = 1e-10,
                                         NewtonResult* last = nullptr) {
  set.set_position(position);
  const DofMap& dofs = m.assembler->dofs();
  const Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(m.u.size());
  EquilibriumProblem problem(*m.assembler, m.state, m.u, u_prescribed, f_ext, 0.0);
  problem.add_term([&](const Eigen::VectorXd& u, Eigen::VectorXd& r, SparseMatrix* K) { set.evaluate(u, dofs, r, K); });
  NewtonOptions options;
  options.residual_tolerance = tol;
  options.correction_tolerance = tol;
  options.force_floor = 1e-6;
  options.max_iterations = 40;
  Eigen::VectorXd x = dofs.gather_free(m.u);
  int solves = 0;
  const AugmentedResult r = solve_augmented(
      [&] {
        NewtonResult n = solve_newton(problem, *m.linear, x, options);
        if (last && solves++ == 0) *last = n;  // the solve that carries the increment
        return n;
      },
      {&set});
  if (r.converged()) {
    m.state.commit();
    set.commit();
    m.u = problem.u();
  } else {
    m.state.revert();
    set.revert();
  }
  return r;
}

}  // namespace cushion::solver::test
