#pragma once
/// Step damping of "dynamic" and "steady_state" steps (ABAQUS *GLOBAL DAMPING, Rayleigh), one
/// "damping" object in both:
///   "damping"?: {"rayleigh_alpha_1_s"? = 0, "rayleigh_beta_s"? = 0, "structural"? = 0}   all >= 0
/// ("structural" in steady_state steps only). The damping matrix C = alpha M + beta K_R(0) is built by
/// dynamics::damping_matrix (solver/dynamics/linearised_system.hpp); the steady state adds i s K_R(0).
namespace cushion::solver {

/// Rayleigh and structural damping coefficients of a step.
struct Damping {
  double rayleigh_alpha = 0.0;  ///< mass-proportional alpha [1/s] (paper: 180)
  double rayleigh_beta = 0.0;   ///< stiffness-proportional beta [s] (paper: 1e-4)
  double structural = 0.0;      ///< structural (hysteretic) loss factor s [-] (steady state only)
};

}  // namespace cushion::solver
