#pragma once
/// The "steady_state" step of a case (keys: solver/case/steady_state_spec.hpp): a frequency
/// sweep of the model linearised about the committed end state of the previous step (solver/dynamics/
/// steady_state.hpp for the equations). A linear perturbation: the carried state (u, material state,
/// time) is left unchanged, so a later step continues from the base state.
///
/// Base state: the previous step's committed displacements; the geometric stress is the relaxed
/// (long-term) stress at that deformation (default, ABAQUS convention) or the stress as left
/// ("base_stress": "as_left"); the Prony series gives the complex material tangent C*(w) about it.
/// Excitation: harmonic displacement of one component of a set, the "held" components at zero, all
/// else free; displacements are absolute (alpha M damps absolute velocities).
/// Contact: the contacts of the previous static/visco step are frozen at the base state
/// (solver/dynamics/contact_linearisation.hpp: closed nodes keep a normal penalty spring; tangentially
/// free sliding, or sticking with friction); each indenter gets one translation DOF along the
/// excitation's component, held (base shaken), driven (indenter shaken) or free with a mass
/// (transmissibility). An indenter named by the sweep without a closed node is an InputError.
/// Outputs in the run folder: <step>_sweep.csv (one row per frequency, written at the end of the
/// sweep in one piece) and, if output.vtk, <step>_sweep.pvd + <step>_sweep_NNNN.vtu (time = frequency
/// [Hz]; base displacement and stress plus the harmonic amplitudes: dynamics::write_frequency_frame);
/// one progress line per frequency. Frequencies are solved on up to 2 threads.
#include "solver/analysis/step.hpp"

namespace cushion::solver {

class SteadyStateStep final : public CaseStep {
 public:
  using CaseStep::CaseStep;
  /// Throws InputError for a named indenter without contact at the base state (before anything is
  /// written; input errors of the case, mesh and material are raised by load_case); AnalysisError if
  /// the base state cannot be linearised or a frequency hits an undamped resonance (no sweep file is
  /// then written).
  void run(AnalysisContext& ctx) override;
};

/// The Step of a "steady_state" case step (called by make_step).
std::unique_ptr<Step> make_steady_state_step(const StepSpec& spec);

}  // namespace cushion::solver
