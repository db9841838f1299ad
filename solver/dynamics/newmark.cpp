#include "solver/dynamics/newmark.hpp"

#include <stdexcept>

namespace cushion::solver::dynamics {
namespace {

/// Free-free block of an all-DOF matrix.
SparseMatrix free_block(const SparseMatrix& A, const DofMap& dofs) {
  const auto& free = dofs.free_dofs();
  SparseMatrix P(static_cast<Eigen::Index>(free.size()), A.rows());
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < free.size(); ++i) t.emplace_back(static_cast<int>(i), free[i], 1.0);
  P.setFromTriplets(t.begin(), t.end());
  SparseMatrix B = P * A * SparseMatrix(P.transpose());
  B.makeCompressed();
  return B;
}

}  // namespace

NewmarkIntegrator::NewmarkIntegrator(const Assembler& assembler, SparseMatrix M_all, SparseMatrix C_all,
                                     NewmarkParameters p)
    : assembler_(assembler), M_(std::move(M_all)), C_(std::move(C_all)), p_(p) {
  const auto n = static_cast<Eigen::Index>(assembler.dofs().num_dofs());
  if (M_.rows() != n || M_.cols() != n || C_.rows() != n || C_.cols() != n)
    throw std::invalid_argument("Newmark: M and C must be square on all DOFs");
  if (!(p_.gamma >= 0.5) || !(p_.beta >= 0.25 * (p_.gamma + 0.5) * (p_.gamma + 0.5) - 1e-15))
    throw std::invalid_argument("Newmark: parameters outside the unconditionally stable range");
  Mff_ = free_block(M_, assembler.dofs());
  Cff_ = free_block(C_, assembler.dofs());
}

NewtonResult NewmarkIntegrator::step(StateStore& state, LinearSolver& linear, Kinematics& k, double dt,
                                     const Kinematics& prescribed, const Eigen::VectorXd& f_ext,
                                     const NewtonOptions& options, const std::vector<ExtraTerm>& extra) {
  if (!(dt > 0.0)) throw std::invalid_argument("Newmark: dt must be > 0");
  const DofMap& dofs = assembler_.dofs();
  const double b = p_.beta, g = p_.gamma;
  const double c_a = 1.0 / (b * dt * dt), c_v = g / (b * dt);

  // Full vectors at t + dt for a given u: free entries by Newmark, constrained ones prescribed.
  Eigen::VectorXd a_new = prescribed.a, v_new = prescribed.v;
  const Eigen::VectorXd a_pred = -(dt * k.v) * c_a - (0.5 / b - 1.0) * k.a;  // a_{n+1} - c_a (u - u_n)
  auto kinematics_at = [&](const Eigen::VectorXd& u) {
    for (int d : dofs.free_dofs()) {
      a_new(d) = c_a * (u(d) - k.u(d)) + a_pred(d);
      v_new(d) = k.v(d) + dt * ((1.0 - g) * k.a(d) + g * a_new(d));
    }
  };
  const SparseMatrix K_dyn = c_a * Mff_ + c_v * Cff_;

  Eigen::VectorXd u_target = k.u;
  for (int d : dofs.constrained_dofs()) u_target(d) = prescribed.u(d);
  EquilibriumProblem problem(assembler_, state, k.u, u_target, f_ext, dt);
  for (const auto& term : extra) problem.add_term(term);
  problem.add_term([&](const Eigen::VectorXd& u, Eigen::VectorXd& r_full, SparseMatrix* K) {
    kinematics_at(u);
    r_full += M_ * a_new + C_ * v_new;
    if (K) *K += K_dyn;
  });
  // Predictor: constant-acceleration extrapolation of the free DOFs.
  Eigen::VectorXd u0 = k.u + dt * k.v + 0.5 * dt * dt * k.a;
  Eigen::VectorXd x = dofs.gather_free(u0);
  NewtonResult r = solve_newton(problem, linear, x, options);
  if (!r.converged()) return r;
  const Eigen::VectorXd& u = problem.u();
  kinematics_at(u);
  force_ = problem.f_int() + M_ * a_new + C_ * v_new;
  k.u = u;
  k.v = v_new;
  k.a = a_new;
  return r;
}

}  // namespace cushion::solver::dynamics
