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

/// Newmark parameters (gamma >= 1/2, beta >= (gamma + 1/2)^2 / 4 for unconditional stability).
struct NewmarkParameters {
  double gamma = 0.5;
  double beta = 0.25;
};

/// Displacement [mm], velocity [mm/s] and acceleration [mm/s^2] on all DOFs.
struct Kinematics {
  Eigen::VectorXd u, v, a;
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
  NewtonResult step(StateStore& state, LinearSolver& linear, Kinematics& k, double dt, const Kinematics& prescribed,
                    const Eigen::VectorXd& f_ext, const NewtonOptions& options = {},
                    const std::vector<ExtraTerm>& extra = {});

  /// f_int + M a + C v of the last converged step [N], full: reactions at the constrained DOFs.
  const Eigen::VectorXd& support_force() const { return force_; }

 private:
  const Assembler& assembler_;
  SparseMatrix M_, C_, Mff_, Cff_;
  NewmarkParameters p_;
  Eigen::VectorXd force_;
};

}  // namespace cushion::solver::dynamics
