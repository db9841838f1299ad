#include "solver/analysis/contact_contributor.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "solver/contact/augmented_solve.hpp"
#include "solver/contact/indenter_factory.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* format, double x) { return io::format_with(format, x); }

const std::vector<int>& node_set(const AnalysisContext& ctx, const ContactSpec& spec) {
  const auto it = ctx.mesh().node_sets.find(spec.set);
  if (it == ctx.mesh().node_sets.end())
    throw InputError(ctx.spec().file.string() + ": " + spec.key + ".set: unknown node set \"" + spec.set + "\"");
  return it->second;
}

void warn(AnalysisContext& ctx, const std::string& note) {
  ctx.log() << "  warning: " << note << "\n";
  ctx.report_progress("warning: " + note);
}

// The plane x[axis] = c if every node of `nodes` lies on it (within `tolerance` [mm]).
std::optional<AxisPlane> common_plane(const mesh::Mesh& mesh, const std::vector<int>& nodes, int axis,
                                      double tolerance) {
  if (nodes.empty()) return std::nullopt;
  const double c = mesh.nodes[nodes.front()][axis];
  for (int n : nodes)
    if (std::abs(mesh.nodes[n][axis] - c) > tolerance) return std::nullopt;
  return AxisPlane{axis, c};
}

// Planes of the model where a boundary condition of any step holds the normal displacement of a set
// lying in it (symmetry conditions apart from fixed or zero-displacement ones). Tolerance: 1e-6 of
// the mesh's bounding-box diagonal.
HeldPlanes held_planes(const CaseSpec& spec, const mesh::Mesh& mesh) {
  HeldPlanes out;
  mesh::Vec3 lo = mesh.nodes.front(), hi = lo;
  for (const mesh::Vec3& x : mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  out.tolerance = 1e-6 * (hi - lo).norm();
  auto add = [&](std::vector<AxisPlane>& planes, const AxisPlane& p) {
    for (const AxisPlane& q : planes)
      if (q.axis == p.axis && std::abs(q.offset - p.offset) <= out.tolerance) return;
    planes.push_back(p);
  };
  for (const StepSpec& step : spec.steps)
    for (const BoundarySpec& bc : step.boundary) {
      const auto set = mesh.node_sets.find(bc.set);
      const bool zero = bc.kind != BoundarySpec::Kind::displacement || (bc.value == 0.0 && !bc.amplitude);
      if (set == mesh.node_sets.end() || !zero) continue;
      for (int axis = 0; axis < 3; ++axis)
        if (bc.dofs[axis])
          if (const auto plane = common_plane(mesh, set->second, axis, out.tolerance))
            add(bc.kind == BoundarySpec::Kind::symmetry ? out.symmetry : out.held, *plane);
    }
  return out;
}

ContactSet build_set(const ContactSpec& spec, AnalysisContext& ctx) {
  const std::string where = ctx.spec().file.string() + ": " + spec.key;
  try {
    std::vector<std::string> notes;
    auto surface = make_indenter(spec.indenter, where + ".indenter", held_planes(ctx.spec(), ctx.mesh()), &notes);
    for (const std::string& note : notes) warn(ctx, note);
    return ContactSet(spec.name, ctx.mesh(), node_set(ctx, spec), std::move(surface), spec.parameters);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind(where, 0) == 0 ? what : where + ": " + what);
  }
}

}  // namespace

std::vector<std::string> contact_history_columns(const std::string& n) {
  return {n + ".U1_mm", n + ".U2_mm", n + ".U3_mm", n + ".F1_N", n + ".F2_N", n + ".F3_N", n + ".normal_force_N",
          n + ".area_mm2", n + ".mean_pressure_kPa", n + ".max_penetration_mm", n + ".active_nodes",
          n + ".slipping_nodes", n + ".augmentations"};
}

ContactContributor::ContactContributor(const ContactSpec& spec, AnalysisContext& ctx)
    : ctx_(ctx), set_(build_set(spec, ctx)), force_factor_(spec.force_factor),
      history_(ctx.output().pvd_file().parent_path() / ("contact_" + spec.name + ".csv"),
               contact_history_columns(spec.name),
               {"contact '" + spec.name + "': " + set_.surface().describe(),
                "U = indenter translation; F = force of the indenter on the foam; forces and area x force_factor " +
                    fmt("%g", spec.force_factor)}) {
  const std::vector<double> zeros(contact_history_columns(spec.name).size(), 0.0);
  history_.write_row(ctx.model().time, zeros);
}

void ContactContributor::begin_step(const ContactSpec& spec, const StepSpec& step, const DofMap& dofs) {
  step_spec_ = spec;
  step_ = &step;
  dofs_ = &dofs;
  t_start_ = ctx_.model().time;
  start_position_ = committed_position_;
  contact_in_step_ = false;
  if (!checked_start_) {
    set_.set_position(committed_position_);
    char when[64];
    std::snprintf(when, sizeof when, "at t = %g s", ctx_.model().time);
    try {
      check_no_initial_penetration(set_, ctx_.model().u, when);
    } catch (const InputError& e) {
      throw InputError(ctx_.spec().file.string() + ": " + spec.key + ": " + e.what());
    }
    checked_start_ = true;
  }
}

Vec3 ContactContributor::motion_at(double t_total) const {
  const double t_step = t_total - t_start_, period = step_->period;
  if (step_spec_.amplitude) {
    const Amplitude& a = ctx_.spec().amplitudes.at(*step_spec_.amplitude);
    return step_spec_.motion * a.at(a.total_time ? t_total : t_step);
  }
  return start_position_ + (step_spec_.motion - start_position_) * std::min(1.0, t_step / period);
}

void ContactContributor::begin_increment(const IncrementInfo& increment, EquilibriumProblem& problem) {
  t_end_ = increment.t_end;
  set_.set_position(motion_at(increment.t_end));
  set_.begin_attempt();
  problem.add_term([this](const Eigen::VectorXd& u, Eigen::VectorXd& r, SparseMatrix* K) {
    if (predicting_)
      set_.evaluate_predictor(committed_position_, u, *dofs_, r, K);
    else
      set_.evaluate(u, *dofs_, r, K);
  });
}

bool ContactContributor::update_after_solve(std::string& failure) {
  const AugmentOutcome a = set_.augment();
  if (a.failed) failure = a.message;
  if (!a.converged)
    ctx_.log() << "    contact '" << set_.name() << "': augmentation " << set_.augmentations() << ", penetration "
             << a.max_penetration << " mm > " << set_.parameters().tolerance << " mm\n";
  return !a.converged && !a.failed;
}

void ContactContributor::commit() {
  const ContactTotals t = set_.totals();
  const Vec3 c = set_.position();
  const double f = force_factor_;
  const std::vector<double> row{c.x(), c.y(), c.z(), f * t.force.x(), f * t.force.y(), f * t.force.z(),
                                f * t.normal_force, f * t.area, 1e3 * t.mean_pressure, t.max_penetration,
                                double(t.active), double(t.slipping), double(set_.augmentations())};
  set_.commit();
  committed_position_ = c;
  history_.write_row(t_end_, row);
  std::string note;
  if (t.active > 0) {
    contact_in_step_ = had_contact_ = true;
  } else if (had_contact_) {
    note = "contact '" + set_.name() + "': the indenter lost contact at t = " + fmt("%g", t_end_) +
           " s (smallest gap " + fmt("%.4g", t.min_gap) + " mm)";
    had_contact_ = false;
  } else if (t_end_ >= t_start_ + step_->period * (1 - 1e-12) && !contact_in_step_) {
    note = "contact '" + set_.name() + "': no node of set '" + step_spec_.set + "' touched the indenter in step '" +
           step_->name + "' (smallest gap " + fmt("%.4g", t.min_gap) + " mm at the end); check its position and motion";
  }
  if (!note.empty()) warn(ctx_, note);
}

void ContactContributor::revert() { set_.revert(); }

void ContactContributor::add_frame_fields(FrameData& frame) const { set_.add_frame_fields(frame); }

std::vector<std::shared_ptr<ResidualContributor>> step_contacts(AnalysisContext& ctx, const StepSpec& step,
                                                                const DofMap& dofs) {
  std::vector<std::shared_ptr<ResidualContributor>> out;
  for (const ContactSpec& c : step.contact) {
    std::shared_ptr<ContactContributor> contact = ctx.contact(c);
    contact->begin_step(c, step, dofs);
    out.push_back(std::move(contact));
  }
  return out;
}

bool case_has_friction(const CaseSpec& spec) {
  for (const StepSpec& s : spec.steps)
    for (const ContactSpec& c : s.contact)
      if (c.parameters.friction > 0.0) return true;
  return false;
}

}  // namespace cushion::solver
