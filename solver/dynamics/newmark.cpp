#include "solver/dynamics/newmark.hpp"

#include <stdexcept>

#include <Eigen/SparseCholesky>

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
  if (!(p_.alpha >= -1.0 / 3.0 - 1e-15 && p_.alpha <= 0.0))
    throw std::invalid_argument("Newmark: HHT alpha must be in [-1/3, 0]");
  Mff_ = free_block(M_, assembler.dofs());
  Cff_ = free_block(C_, assembler.dofs());
}

NewmarkUpdate::NewmarkUpdate(const DofMap& dofs, NewmarkParameters p, const Kinematics& start,
                             const Kinematics& prescribed, double dt, const Eigen::VectorXd* start_force)
    : dofs_(dofs), p_(p), start_(start), prescribed_(prescribed), start_force_(start_force), dt_(dt),
      c_a_(1.0 / (p.beta * dt * dt)),
      c_v_(p.gamma / (p.beta * dt)),
      a_pred_(-(dt * start.v) * c_a_ - (0.5 / p.beta - 1.0) * start.a) {}

Kinematics NewmarkUpdate::at(const Eigen::VectorXd& u) const {
  Kinematics k{u, prescribed_.v, prescribed_.a};
  for (int d : dofs_.free_dofs()) {
    k.a(d) = c_a_ * (u(d) - start_.u(d)) + a_pred_(d);
    k.v(d) = start_.v(d) + dt_ * ((1.0 - p_.gamma) * start_.a(d) + p_.gamma * k.a(d));
  }
  return k;
}

Eigen::VectorXd NewmarkUpdate::predictor() const {
  Eigen::VectorXd u = start_.u + dt_ * start_.v + 0.5 * dt_ * dt_ * start_.a;
  for (int d : dofs_.constrained_dofs()) u(d) = prescribed_.u(d);
  return u;
}

ExtraTerm NewmarkIntegrator::inertia_term(const NewmarkUpdate& update) const {
  const double alpha = update.parameters().alpha;
  if (alpha != 0.0 && !update.start_force())
    throw std::invalid_argument("Newmark: HHT (alpha != 0) needs the start force G_n in the update");
  return [this, &update, alpha](const Eigen::VectorXd& u, Eigen::VectorXd& r_full, SparseMatrix* K) {
    const Kinematics k = update.at(u);
    const double w = 1.0 + alpha;
    r_full += M_ * k.a / w + C_ * k.v;
    if (alpha != 0.0)
      for (int d : assembler_.dofs().free_dofs()) r_full(d) -= alpha / w * (*update.start_force())(d);
    if (K) *K += update.c_a() / w * Mff_ + update.c_v() * Cff_;
  };
}

Eigen::VectorXd NewmarkIntegrator::next_start_force(const Eigen::VectorXd& g_start, const Eigen::VectorXd& a) const {
  const Eigen::VectorXd Ma = M_ * a;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(a.size());
  for (int d : assembler_.dofs().free_dofs()) g(d) = (p_.alpha * g_start(d) - Ma(d)) / (1.0 + p_.alpha);
  return g;
}

Eigen::VectorXd NewmarkIntegrator::start_force(const Eigen::VectorXd& r_free, const Eigen::VectorXd& v) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(v.size());
  assembler_.dofs().scatter_free(r_free, g);
  const Eigen::VectorXd Cv = C_ * v;
  for (int d : assembler_.dofs().free_dofs()) g(d) += Cv(d);
  return g;
}

Eigen::VectorXd NewmarkIntegrator::initial_acceleration(const Eigen::VectorXd& r_free, const Eigen::VectorXd& v,
                                                        const Eigen::VectorXd& a_prescribed) const {
  const DofMap& dofs = assembler_.dofs();
  Eigen::VectorXd a_c = Eigen::VectorXd::Zero(a_prescribed.size());
  for (int d : dofs.constrained_dofs()) a_c(d) = a_prescribed(d);
  const Eigen::VectorXd rhs = -(r_free + dofs.gather_free(M_ * a_c + C_ * v));
  Eigen::VectorXd a = a_c;
  if (rhs.size() == 0) return a;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(Mff_);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw std::runtime_error("the mass matrix of the free DOFs is not positive definite");
  dofs.scatter_free(ldlt.solve(rhs), a);
  return a;
}

NewtonResult NewmarkIntegrator::step(StateStore& state, LinearSolver& linear, Kinematics& k, double dt,
                                     const Kinematics& prescribed, const Eigen::VectorXd& f_ext,
                                     const NewtonOptions& options, const std::vector<ExtraTerm>& extra) {
  if (!(dt > 0.0)) throw std::invalid_argument("Newmark: dt must be > 0");
  if (p_.alpha != 0.0) throw std::invalid_argument("Newmark: step() integrates the plain rule only (alpha = 0)");
  const DofMap& dofs = assembler_.dofs();
  const NewmarkUpdate update(dofs, p_, k, prescribed, dt);
  Eigen::VectorXd u_target = k.u;
  for (int d : dofs.constrained_dofs()) u_target(d) = prescribed.u(d);
  EquilibriumProblem problem(assembler_, state, k.u, u_target, f_ext, dt);
  for (const auto& term : extra) problem.add_term(term);
  problem.add_term(inertia_term(update));
  Eigen::VectorXd x = dofs.gather_free(update.predictor());
  NewtonResult r = solve_newton(problem, linear, x, options);
  if (!r.converged()) return r;
  Kinematics next = update.at(problem.u());
  force_ = problem.f_int() + M_ * next.a + C_ * next.v;
  k = std::move(next);
  return r;
}

}  // namespace cushion::solver::dynamics
