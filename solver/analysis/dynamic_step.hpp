#pragma once
/// The "dynamic" step of a case (keys: solver/case/case_spec.hpp): implicit time integration of
///   f_int(u) + M a + C v = f_contact   (free DOFs; all vectors full, reference frame axes, N)
/// by the Newmark rule (solver/dynamics/newmark.hpp; default gamma = 1/2, beta = 1/4, the
/// average-acceleration rule: unconditionally stable, no numerical damping, energy conserving), or
/// with "newmark": {"alpha": a} the Hilber-Hughes-Taylor rule (ABAQUS *DYNAMIC, ALPHA = a in
/// [-1/3, 0]): M a_n+1 + (1 + a) G_n+1 - a G_n = 0 with G = f_int - f_contact + C v, gamma = 1/2 - a,
/// beta = (1 - a)^2 / 4: second order, damps the high (mesh) frequencies, e.g. a = -0.05 as ABAQUS'
/// moderate-dissipation default.
///
/// Model: M the consistent mass from the section densities [t] (a material without density_kg_m3 is
/// an InputError naming the step and the material file); C = alpha M + beta K_R(0) [N s/mm] with
/// K_R(0) the long-term tangent (material + geometric, relaxed stress) at the start of the step, the
/// same damping as the steady_state step (LinearisedSystem), fixed for the step. Velocities are
/// absolute: alpha M damps rigid (base) motion too. Materials integrate their full history with the
/// increment's dt (Prony terms as in a visco step). Contact: the step's contacts as in static/visco
/// steps (the same contributors; the indenter moves quasi-statically along its motion, it has no mass).
///
/// Boundary conditions: as in static/visco steps. The constrained DOFs follow the prescribed
/// displacement history exactly, with velocity and acceleration from its time derivatives
/// (prescribed_motion): exact for "sine" amplitudes; for tabular amplitudes and the default linear
/// ramp the slope of the segment just completed and zero acceleration (the increments end on the
/// corners, so the velocity jumps there are not smeared; their inertia impulse is not applied).
/// A DOF released in this step (constrained before, free now) is released at once (its reaction is
/// not ramped down as in static steps): e.g. a plucked free vibration.
///
/// Start of the step: displacements and material state as left by the previous step; velocity zero
/// after a static, visco or no previous step; carried from a directly preceding dynamic step
/// (steady_state steps in between do not count: they leave the state unchanged). The starting
/// acceleration of the free DOFs is solved from equilibrium (M_ff a_f = -(f_int + f_contact-term +
/// M_fc a_c + C v)_f), so a preload out of balance or a released support starts consistently.
///
/// Increments: automatic as in static/visco steps (grow after easy increments up to max_s, cut back
/// after divergence or material failure; there is no accuracy control, so choose max_s to resolve the
/// motion, e.g. 1/20 of the shortest period of interest) or "fixed": every increment initial_s, no
/// cut-back. Outputs: frames and history as other steps, reactions RFi = f_int + M a + C v at the
/// constrained DOFs (support forces including inertia and damping); frames also hold
/// velocity_mm_s and acceleration_mm_s2 per node; <step>_energy.csv: per increment, kinetic energy
/// 1/2 v.M v, internal work sum 1/2 du.(f_int_n + f_int_n+1), damping work (same with C v) and the
/// work of external forces (same with f_int + M a + C v, i.e. supports and contact), all in mJ
/// (N mm) since the start of the step, and the balance KE + W_int + W_damp - W_ext - KE_start
/// (zero for the average-acceleration rule, negative with numerical dissipation).
#include "solver/analysis/step.hpp"

namespace cushion::solver {

class DynamicStep final : public CaseStep {
 public:
  using CaseStep::CaseStep;
  /// Throws InputError for a material without density (before any output of the step),
  /// AnalysisError when an increment cannot converge, Interrupted after Ctrl-C.
  void run(AnalysisContext& ctx) override;
};

/// The Step of a "dynamic" case step (called by make_step).
std::unique_ptr<Step> make_dynamic_step(const StepSpec& spec);

/// Columns of <step>_energy.csv after "time_s".
std::vector<std::string> energy_columns();

}  // namespace cushion::solver
