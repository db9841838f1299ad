#include "solver/equilibrium.hpp"

#include <cmath>

namespace cushion::solver {

EquilibriumProblem::EquilibriumProblem(const Assembler& assembler, StateStore& state, const Eigen::VectorXd& u_old,
                                       const Eigen::VectorXd& u_new, const Eigen::VectorXd& f_ext, double dt)
    : assembler_(assembler), state_(state), u_old_(u_old), f_ext_(f_ext), dt_(dt), u_(u_new),
      K_(assembler.make_matrix()) {}

ProblemEvaluation EquilibriumProblem::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& r, bool want_tangent) {
  const DofMap& dofs = assembler_.dofs();
  dofs.scatter_free(x, u_);
  status_ = assembler_.assemble(u_old_, u_, dt_, state_, f_int_, want_tangent ? &K_ : nullptr);
  r_full_ = f_int_ - f_ext_;
  for (const auto& term : terms_) term(u_, r_full_, want_tangent ? &K_ : nullptr);
  r = dofs.gather_free(r_full_);
  return summarize();
}

ProblemEvaluation EquilibriumProblem::summarize() const {
  const DofMap& dofs = assembler_.dofs();
  ProblemEvaluation ev;
  ev.status = status_.status;
  ev.dt_factor = status_.dt_factor;
  ev.message = status_.message;
  if (status_.element >= 0)
    ev.message = "element " + std::to_string(assembler_.mesh().elements[status_.element].label) + ": " + ev.message;
  // Force scale q: mean magnitude of the non-zero external loads and reactions.
  double sum = 0.0;
  int count = 0;
  for (Eigen::Index d = 0; d < r_full_.size(); ++d) {
    const double f = dofs.is_constrained(static_cast<int>(d)) ? r_full_(d) : f_ext_(d);
    if (f != 0.0) sum += std::abs(f), ++count;
  }
  ev.force_scale = count ? sum / count : 0.0;
  return ev;
}

ProblemEvaluation EquilibriumProblem::predict(Eigen::VectorXd& x, LinearSolver& linear, TangentFactor* reuse) {
  const DofMap& dofs = assembler_.dofs();
  const Eigen::VectorXd u_end = u_;  // constrained entries hold the prescribed end values
  Eigen::VectorXd u_start = u_old_;
  dofs.scatter_free(x, u_start);
  if (K_fc_.size() == 0) K_fc_ = assembler_.make_coupling_matrix();
  status_ = assembler_.assemble(u_old_, u_start, dt_, state_, f_int_, &K_, nullptr, &K_fc_);
  r_full_ = f_int_ - f_ext_;
  for (const auto& term : terms_) term(u_start, r_full_, &K_);
  const ProblemEvaluation ev = summarize();
  predictor_solved_ = false;
  if (ev.status == material::Status::failed) return ev;

  const auto& fixed = dofs.constrained_dofs();
  Eigen::VectorXd du_c(static_cast<Eigen::Index>(fixed.size()));
  for (std::size_t k = 0; k < fixed.size(); ++k) du_c(k) = u_end(fixed[k]) - u_old_(fixed[k]);
  // K_fc is exact in the owned rows only (distributed runs): its products are completed.
  Eigen::VectorXd coupling = K_fc_ * du_c;
  assembler_.complete_free(coupling);
  const Eigen::VectorXd rhs = -(dofs.gather_free(r_full_) + coupling);

  // Force scale of the boundary increment: what each free DOF is pushed with before cancellation.
  Eigen::VectorXd pushed = K_fc_.cwiseAbs() * du_c.cwiseAbs();
  assembler_.complete_free(pushed);
  const Eigen::Index loaded = (pushed.array() > 0.0).count();
  const double q_p = std::max(ev.force_scale, loaded ? pushed.sum() / static_cast<double>(loaded) : 0.0);
  if (rhs.size() == 0 || rhs.cwiseAbs().maxCoeff() <= negligible_predictor_residual * q_p) return ev;

  if (!reuse || !reuse->current) {
    linear.factorize(K_);
    if (reuse) *reuse = TangentFactor{true, 0};
  }
  x += linear.solve(rhs);
  if (reuse) ++reuse->uses;
  predictor_solved_ = true;
  return ev;
}

}  // namespace cushion::solver
