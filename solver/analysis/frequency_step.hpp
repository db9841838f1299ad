#pragma once
/// Linear perturbation steps share the linearisation of the carried state; the "frequency" step
/// (FrequencySpec, decks: *FREQUENCY) computes the lowest natural frequencies of K_R(0) phi = w^2 M phi
/// (long-term base-state tangent, material + geometric; consistent mass) with the DOFs of the step's
/// boundary conditions held (solver/dynamics/modes.hpp: dense, up to 6000 free DOFs) and writes
/// <step>_frequencies.csv (mode, frequency_Hz, eigenvalue_rad2_s2). Contact is not included. The carried
/// state (u, material state, time) is left unchanged.
#include <memory>
#include <vector>

#include "solver/analysis/step.hpp"
#include "solver/dynamics/linearised_system.hpp"

namespace cushion::solver {

/// The model linearised about the carried (committed) state, with `stress` in the geometric stiffness;
/// AnalysisError naming `step` if a material point fails there.
std::unique_ptr<dynamics::LinearisedSystem> linearise_base_state(const AnalysisContext& ctx, const StepSpec& step,
                                                                 const Assembler& assembler, BaseStress stress);

/// Every natural frequency [Hz], ascending, of `system` (long-term tangent, mass) with the DOFs marked in
/// `held` (one flag per DOF of the system, at least) kept at zero; AnalysisError naming `step` past the dense
/// solver's 6000 free DOFs or for a mass that is not positive definite on the free DOFs.
std::vector<double> natural_frequencies_with_held(const dynamics::LinearisedSystem& system, const std::vector<bool>& held,
                                                  const StepSpec& step);

class FrequencyStep final : public CaseStep {
 public:
  using CaseStep::CaseStep;
  /// AnalysisError if the base state cannot be linearised, the model has more than 6000 free DOFs or its
  /// mass is not positive definite on them.
  void run(AnalysisContext& ctx) override;
};

/// The Step of a "frequency" step (called by make_step).
std::unique_ptr<Step> make_frequency_step(const StepSpec& spec);

}  // namespace cushion::solver
