#pragma once
/// Direct steady-state dynamics (docs/physics.md 4): harmonic response u(t) = Re(u^ e^{+i w t}) of the
/// linearised model about its base state, with prescribed harmonic displacements at some DOFs.
///
///   D(w) = K*(w) + K_x + i s K_R(0) + i w (alpha M + beta K_R(0)) - w^2 M,
///   D_ff u^_f = -D_fc u^_c,   reactions R^_c = D_cf u^_f + D_cc u^_c   [N]
/// K*(w): complex material + geometric stiffness (LinearisedSystem); K_x: extra real stiffness (the
/// linearised contact), not Rayleigh damped; K_R(0): the real long-term base-state tangent (the
/// stiffness-proportional Rayleigh and structural terms use it [A]); M: consistent mass plus lumped
/// masses. All DOFs are ABSOLUTE displacements, so the mass-proportional term alpha M acts on absolute
/// velocities as in ABAQUS: the rigid motion of a shaken base is damped too (a force alpha m w U on a
/// body moving rigidly with amplitude U). Reactions include the inertia and damping of the mass
/// carried by the constrained DOFs themselves (consistent-mass share of the supported nodes).
/// Linear solve per frequency (SolveMethod): direct = one complex UMFPACK LU per frequency (symbolic
/// analysis reused); iterative = GMRES on the complex D_ff preconditioned by a REAL sparse Cholesky
/// (CHOLMOD) factor of P = Re D_ff(w_ref), factorised once at the first frequency the solver sees and
/// refreshed (w_ref = current w) when GMRES needs more than max_iterations; if P is not positive
/// definite or GMRES still fails, that frequency falls back to the direct LU. P^-1 D_ff = I + i P^-1
/// Im D_ff + P^-1 Re(D_ff(w) - D_ff(w_ref)) has its spectrum clustered near 1 + i (loss factor), so
/// GMRES converges in a few tens of iterations; each iteration costs one complex product and one pair
/// of real triangular solves, far less than a complex factorisation.
#include <complex>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "solver/dynamics/linearised_system.hpp"
#include "solver/linear_solver.hpp"

namespace cushion::solver::dynamics {

/// The model: the linearised solid on its 3 x nodes DOFs plus `extra_dofs` appended DOFs (e.g. the
/// vertical DOF of a rigid indenter, index 3 nodes + k), coupled by `extra_stiffness`.
struct HarmonicModel {
  const LinearisedSystem* system = nullptr;          ///< not owned, must outlive the solver
  int extra_dofs = 0;                                 ///< appended DOFs
  SparseMatrix extra_stiffness;                       ///< n x n [N/mm] (n = 3 nodes + extra), or empty
  std::vector<std::pair<int, double>> lumped_mass;    ///< (DOF, mass [t]) added to M
};

/// Prescribed DOFs: `driven` move with the excitation amplitude, `held` stay at zero; the rest are free.
/// `force`: harmonic forces (DOF, force [N] per unit amplitude) on free DOFs, added to the right-hand
/// side (D_ff u^_f = a F_f - D_fc u^_c); forces on prescribed DOFs move nothing and are ignored.
struct Excitation {
  std::vector<int> driven;
  std::vector<int> held;
  std::vector<std::pair<int, double>> force;
};

/// A named group of DOFs whose summed reaction and mean displacement are reported.
struct DofGroup {
  std::string name;
  std::vector<int> dofs;
};

/// Response at one frequency.
struct FrequencyResponse {
  double frequency = 0.0;                          ///< [Hz]
  std::complex<double> amplitude;                  ///< driven displacement u^_d [mm]
  Eigen::VectorXcd u;                              ///< all DOFs [mm]
  std::vector<std::complex<double>> reaction;      ///< per group: sum of reactions at its constrained DOFs [N]
  std::vector<std::complex<double>> displacement;  ///< per group: mean displacement [mm]
};

/// How D_ff u_f = b is solved at each frequency (see above).
struct SolveMethod {
  bool iterative = false;      ///< GMRES + real preconditioner P = Re D_ff (else complex LU)
  double tolerance = 1e-10;    ///< true relative residual |b - D x| / |b| [-]
  int max_iterations = 60;     ///< before the preconditioner is refreshed / the LU fallback
  /// The solver applying P^-1 (iterative only): e.g. PETSc CG + algebraic multigrid on one process
  /// (solver/petsc/). Empty: a CHOLMOD Cholesky factor of P. Its geometry is set when the model has
  /// no appended DOFs (nodes of `geometry`).
  std::function<std::unique_ptr<LinearSolver>()> preconditioner;
  const std::vector<Eigen::Vector3d>* geometry = nullptr;  ///< reference node coordinates [mm]
};

/// Cost counters of a solver (wall seconds, summed over its frequencies).
struct SolveStats {
  int complex_factorisations = 0, real_factorisations = 0, iterations = 0;
  double assembly_time = 0.0, factorisation_time = 0.0, solve_time = 0.0;
};

/// Frequency-by-frequency solver. Damping (solver/case/damping.hpp): C = alpha M + beta K_R(0)
/// (damping_matrix), plus i s K_R(0).
class SteadyStateSolver {
 public:
  /// Throws std::invalid_argument on DOFs out of range, driven and held overlapping, no driven DOF and no force,
  /// negative damping, or a missing mass (a section without density, message naming it).
  SteadyStateSolver(HarmonicModel model, Damping damping, Excitation excitation, std::vector<DofGroup> groups,
                    SolveMethod method = {});
  ~SteadyStateSolver();

  /// Solves at `frequency` [Hz] (> 0, else std::invalid_argument) for an amplitude a: driven DOFs at
  /// a [mm], forces a F [N].
  /// Throws SingularMatrixError at an undamped resonance.
  FrequencyResponse solve(double frequency, std::complex<double> amplitude);

  /// D(w) on all DOFs [N/mm] (for checks).
  ComplexMatrix dynamic_matrix(double omega) const;
  std::size_t num_dofs() const { return n_; }
  std::size_t num_free() const { return free_.size(); }
  int analyses() const { return lu_.analyses(); }
  const SolveStats& stats() const { return stats_; }
  const std::vector<DofGroup>& groups() const { return groups_; }

 private:
  HarmonicModel model_;
  Damping damping_;
  std::vector<DofGroup> groups_;
  std::size_t n_ = 0;
  std::vector<int> free_, constrained_;
  Eigen::VectorXcd unit_c_;  ///< constrained amplitudes per unit driven amplitude (1 driven, 0 held)
  Eigen::VectorXcd unit_f_;  ///< forces on the free DOFs per unit amplitude [N]
  SparseMatrix K0_, M_, Kx_;  ///< n x n
  SparseMatrix Pf_, Pc_;      ///< selection matrices (rows: free / constrained DOFs)
  ComplexLuSolver lu_;
  SolveMethod method_;
  SolveStats stats_;
  struct Preconditioner;
  std::unique_ptr<Preconditioner> precond_;
  /// x with D_ff x = b by GMRES; false if it did not converge (or P is not positive definite).
  bool solve_iterative(const ComplexMatrix& Dff, const Eigen::VectorXcd& b, Eigen::VectorXcd& x);
};

}  // namespace cushion::solver::dynamics
