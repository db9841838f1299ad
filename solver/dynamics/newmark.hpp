#pragma once
/// Implicit dynamics: Newmark time stepping (default gamma = 1/2, beta = 1/4, the average-acceleration
/// rule: unconditionally stable, second order, no numerical damping) of the nonlinear solid,
///   f_int(u_{n+1}) + M a_{n+1} + C v_{n+1} = f_ext,
///   a_{n+1} = (u_{n+1} - u_n - dt v_n) / (beta dt^2) - (1/(2 beta) - 1) a_n,
///   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1})
/// on the free DOFs, solved by Newton (tangent K_T + M/(beta dt^2) + gamma C/(beta dt)); the
/// constrained DOFs follow their prescribed u, v, a exactly (a shaken base has the exact acceleration).
/// M: consistent mass on all DOFs [t]; C: damping on all DOFs [N s/mm], typically the Rayleigh
/// C = alpha M + beta_R K_R(0) with K_R(0) the long-term tangent at the start of the step (the same
/// matrices as the steady-state step, LinearisedSystem). Velocities are absolute: alpha M damps the
/// rigid motion too. The material integrates its full time-domain history (Prony terms included).
#include "solver/equilibrium.hpp"

namespace cushion::solver::dynamics {

/// Newmark parameters (gamma >= 1/2, beta >= (gamma + 1/2)^2 / 4 for unconditional stability) and
/// the Hilber-Hughes-Taylor alpha in [-1/3, 0] (ABAQUS *DYNAMIC, ALPHA): with alpha != 0 the
/// non-inertia forces G = f_int + contact - f_ext + C v are weighted between the ends of the step,
///   M a_n+1 + (1 + alpha) G_n+1 - alpha G_n = 0   (free DOFs),
/// with gamma = (1 - 2 alpha) / 2, beta = (1 - alpha)^2 / 4 for second-order accuracy and damping of
/// the high frequencies (spectral radius (1 + alpha) / (1 - alpha) as omega dt -> infinity).
struct NewmarkParameters {
  double gamma = 0.5;
  double beta = 0.25;
  double alpha = 0.0;  ///< HHT alpha [-]; 0: the plain Newmark rule
};

/// Displacement [mm], velocity [mm/s] and acceleration [mm/s^2] on all DOFs.
struct Kinematics {
  Eigen::VectorXd u, v, a;
};

/// Newmark kinematics of one step t -> t + dt from `start` (all DOFs at t) and `prescribed` (u, v, a
/// at t + dt, constrained entries used): for a trial full displacement u at t + dt,
///   a = c_a (u - u_n) - c_a dt v_n - (1/(2 beta) - 1) a_n,  v = v_n + dt ((1 - gamma) a_n + gamma a)
/// on the free DOFs, c_a = 1/(beta dt^2) [1/s^2]; the constrained DOFs take the prescribed values.
class NewmarkUpdate {
 public:
  /// `start_force`: with HHT (alpha != 0) the non-inertia force G_n [N] at the start (full vector, only
  /// the free entries are used); it must outlive the update. Ignored when alpha = 0.
  NewmarkUpdate(const DofMap& dofs, NewmarkParameters p, const Kinematics& start, const Kinematics& prescribed,
                double dt, const Eigen::VectorXd* start_force = nullptr);
  /// u [mm], v [mm/s], a [mm/s^2] at t + dt (full) for the full displacement u [mm].
  Kinematics at(const Eigen::VectorXd& u) const;
  /// Predictor [mm], full: free DOFs u_n + dt v_n + dt^2/2 a_n (constant acceleration), constrained prescribed.
  Eigen::VectorXd predictor() const;
  double c_a() const { return c_a_; }  ///< d a / d u on the free DOFs [1/s^2]
  double c_v() const { return c_v_; }  ///< d v / d u on the free DOFs = gamma / (beta dt) [1/s]
  const NewmarkParameters& parameters() const { return p_; }
  /// G_n [N] (full; HHT only), nullptr without.
  const Eigen::VectorXd* start_force() const { return start_force_; }

 private:
  const DofMap& dofs_;
  NewmarkParameters p_;
  const Kinematics& start_;
  const Kinematics& prescribed_;
  const Eigen::VectorXd* start_force_;
  double dt_, c_a_, c_v_;
  Eigen::VectorXd a_pred_;  ///< a - c_a (u - u_n) on the free DOFs [mm/s^2]
};

/// Steps a nonlinear model through time with one assembler (the static analysis' DOF map).
class NewmarkIntegrator {
 public:
  /// M_all, C_all: n x n matrices on ALL DOFs (n = assembler DOFs). Throws std::invalid_argument on sizes.
  NewmarkIntegrator(const Assembler& assembler, SparseMatrix M_all, SparseMatrix C_all, NewmarkParameters p = {});

  /// One step from the committed material state and `k` (time t) to t + dt [s]. `prescribed` holds
  /// u, v, a at t + dt for the constrained DOFs (other entries ignored); f_ext [N] at t + dt (full).
  /// On convergence updates k, leaves the trial state in `state` (caller commits) and stores the
  /// support forces; otherwise k is unchanged (caller reverts). Extra terms (contact) are added.
  /// Plain Newmark only (alpha = 0; the dynamic step of a case supports HHT): invalid_argument otherwise.
  NewtonResult step(StateStore& state, LinearSolver& linear, Kinematics& k, double dt, const Kinematics& prescribed,
                    const Eigen::VectorXd& f_ext, const NewtonOptions& options = {},
                    const std::vector<ExtraTerm>& extra = {});

  /// f_int + M a + C v of the last converged step [N], full: reactions at the constrained DOFs.
  const Eigen::VectorXd& support_force() const { return force_; }

  /// The inertia and damping term M a + C v [N] of `update` (tangent c_a M_ff + c_v C_ff [N/mm]) for
  /// EquilibriumProblem::add_term; `update` must outlive the term. With HHT the equation is divided
  /// by 1 + alpha: the term is M a / (1 + alpha) + C v - alpha / (1 + alpha) G_n (free entries of G_n),
  /// tangent c_a M_ff / (1 + alpha) + c_v C_ff, so f_int and contact keep their unit weight.
  ExtraTerm inertia_term(const NewmarkUpdate& update) const;
  /// M a [N] and C v [N] on all DOFs.
  Eigen::VectorXd inertia_force(const Eigen::VectorXd& a) const { return M_ * a; }
  Eigen::VectorXd damping_force(const Eigen::VectorXd& v) const { return C_ * v; }
  /// Full accelerations in equilibrium at the start of a step [mm/s^2]: on the free DOFs
  /// M_ff a_f = -(r_f + [M a_c + C v]_f) with r_f = f_int + extra - f_ext at the free DOFs [N],
  /// a_c the constrained entries of `a_prescribed` (full) and v the full velocities [mm/s].
  /// Throws std::runtime_error if M_ff is not positive definite (a density missing).
  Eigen::VectorXd initial_acceleration(const Eigen::VectorXd& r_free, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& a_prescribed) const;
  const NewmarkParameters& parameters() const { return p_; }
  /// HHT: G_n+1 on the free DOFs from the converged equation, (alpha G_n - M a_n+1) / (1 + alpha)
  /// (full vector, constrained entries 0) [N]; `g_start` = G_n, `a` = a_n+1 (full).
  Eigen::VectorXd next_start_force(const Eigen::VectorXd& g_start, const Eigen::VectorXd& a) const;
  /// G at a state in equilibrium with residual r_free = f_int + contact - f_ext on the free DOFs:
  /// r_free + (C v)_free, scattered to a full vector (constrained entries 0) [N].
  Eigen::VectorXd start_force(const Eigen::VectorXd& r_free, const Eigen::VectorXd& v) const;

 private:
  const Assembler& assembler_;
  SparseMatrix M_, C_, Mff_, Cff_;
  NewmarkParameters p_;
  Eigen::VectorXd force_;
};

}  // namespace cushion::solver::dynamics
