#pragma once
/// Contact in the step driver: one ContactContributor per named contact of a case, kept in the
/// AnalysisContext across steps (its multipliers and stick points carry over). It moves the
/// indenter, adds the contact term to every increment, runs the Uzawa updates, writes
/// <out>/contact_<name>.csv (one row per converged increment) and the frame arrays, and logs
/// when the indenter has no contact or loses it.
#include <memory>
#include <vector>

#include "solver/analysis/step.hpp"
#include "solver/case/case_file.hpp"
#include "solver/case/contact_spec.hpp"
#include "solver/contact/contact_set.hpp"
#include "solver/output/history_csv.hpp"

namespace cushion::solver {

/// Columns of contact_<name>.csv after "time_s" (full-model forces and area: full_model_factors).
std::vector<std::string> contact_history_columns(const std::string& name);

/// Factors from the model's contact force components (x, y, z) to the full model's: force_factor, except
/// 0 for a component normal to a mirror plane of a reduced model (force_factor != 1 and a symmetry_x|y|z
/// condition of `step` on a node set that shares nodes with the contact set `contact_nodes`): the force on
/// the mirrored parts cancels it (a quarter model: F1 = F2 = 0). A symmetry condition away from the
/// contact surface (a base on rollers) is not a mirror plane. All factors are 1 when force_factor is 1.
Vec3 full_model_factors(double force_factor, const StepSpec& step, const mesh::Mesh& mesh,
                        const std::vector<int>& contact_nodes);

class ContactContributor final : public ResidualContributor {
 public:
  /// Builds the contact set on the node set spec.set (throws InputError naming spec.key for nodes
  /// off the surface, an open STL ...) and opens the history file in the output folder.
  ContactContributor(const ContactSpec& spec, AnalysisContext& ctx);

  /// Prepares a step: the motion of `spec` (this step's entry), the DOF numbering, the start time.
  /// Throws InputError if the indenter starts inside the block at the first step.
  void begin_step(const ContactSpec& spec, const StepSpec& step, const DofMap& dofs);

  void begin_increment(const IncrementInfo& increment, EquilibriumProblem& problem) override;
  bool update_after_solve(std::string& failure) override;
  void commit() override;
  void revert() override;
  void add_frame_fields(FrameData& frame) const override;
  /// While true, the contact term is the linear extrapolation from the last converged indenter
  /// position (ContactSet::evaluate_predictor).
  void set_predicting(bool on) override { predicting_ = on; }
  bool needs_unsymmetric_solver() const { return set_.parameters().friction > 0.0; }

  const ContactSet& set() const { return set_; }

 private:
  Vec3 motion_at(double t_total) const;

  AnalysisContext& ctx_;
  ContactSet set_;
  double force_factor_;
  Vec3 force_factors_;  ///< full_model_factors of the first step naming the contact
  HistoryWriter history_;
  // step data
  ContactSpec step_spec_;
  const StepSpec* step_ = nullptr;
  const DofMap* dofs_ = nullptr;
  double t_start_ = 0.0;
  Vec3 start_position_ = Vec3::Zero(), committed_position_ = Vec3::Zero();
  double t_end_ = 0.0;
  bool predicting_ = false;
  bool checked_start_ = false, had_contact_ = false, contact_in_step_ = false;
};

/// The contributors of a step's contacts (AnalysisContext::contact: created on first use, then
/// kept), each prepared for the step (begin_step).
std::vector<std::shared_ptr<ResidualContributor>> step_contacts(AnalysisContext& ctx, const StepSpec& step,
                                                                const DofMap& dofs);

/// The contact checks that need no solution, run before anything is written: every contact's set and
/// indenter are built (nodes off the surface, an open STL ... are InputErrors naming the case file and
/// the contact's key) and the contacts of the first step must not start inside the block (at t = 0 the
/// mesh is undeformed). A contact first used in a later step is checked for penetration when it starts.
void check_contacts_before_run(const LoadedCase& loaded);

/// True if any step of the case uses friction (the tangent is then unsymmetric: LU solver).
bool case_has_friction(const CaseSpec& spec);

}  // namespace cushion::solver
