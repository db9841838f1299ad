#include "solver/analysis/contact_contributor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "solver/contact/augmented_solve.hpp"
#include "solver/contact/indenter_factory.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* format, double x) { return io::format_with(format, x); }

const std::vector<int>& node_set(const mesh::Mesh& mesh, const CaseSpec& spec, const ContactSpec& c) {
  const auto it = mesh.node_sets.find(c.set);
  if (it == mesh.node_sets.end())
    throw InputError(spec.file.string() + ": " + c.key + ".set: unknown node set \"" + c.set + "\"");
  return it->second;
}

/// The first step of the case naming the contact `name`.
const StepSpec& first_step_with(const CaseSpec& spec, const std::string& name) {
  for (const StepSpec& step : spec.steps)
    for (const ContactSpec& c : step.contact)
      if (c.name == name) return step;
  throw std::logic_error("contact '" + name + "' is in no step");
}

/// The comment lines of contact_<name>.csv: the indenter, what U and F are, which values are full-model ones.
std::vector<std::string> history_comments(const ContactSet& set, double force_factor, const Vec3& factors) {
  std::vector<std::string> out{"contact '" + set.name() + "': " + set.surface().describe(),
                               "U = indenter translation [mm]; F = force of the indenter on the foam [N]"};
  if (force_factor == 1.0) {
    out.push_back("forces and area are the model's (force_factor 1)");
  } else {
    std::string zero;
    for (int i = 0; i < 3; ++i)
      if (factors(i) == 0.0) zero += std::string(zero.empty() ? "" : ", ") + "F" + std::to_string(i + 1);
    out.push_back("full-model values: forces, normal_force and area = model x force_factor " + fmt("%g", force_factor) +
                  (zero.empty() ? std::string()
                                : "; " + zero + " = 0 (normal to a symmetry plane through the contact surface: "
                                              "they cancel in the full model)") +
                  "; mean_pressure, penetration and node counts are the model's");
  }
  out.push_back("area = deformed foam surface within tolerance_mm of the indenter (faces sampled 8 x 8); "
                "slipping_nodes: closed nodes at the Coulomb limit, or every closed node without friction");
  return out;
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

/// The contact set of `c` on `mesh` (InputErrors prefixed by "<case file>: <c.key>"); the indenter's notes
/// (e.g. STL triangles dropped in a symmetry plane) go to `notes` when given.
ContactSet build_set(const ContactSpec& c, const mesh::Mesh& mesh, const CaseSpec& spec,
                     std::vector<std::string>* notes = nullptr) {
  const std::string where = spec.file.string() + ": " + c.key;
  try {
    std::vector<std::string> dropped;
    auto surface = make_indenter(c.indenter, where + ".indenter", held_planes(spec, mesh), &dropped);
    if (notes) notes->insert(notes->end(), dropped.begin(), dropped.end());
    return ContactSet(c.name, mesh, node_set(mesh, spec, c), std::move(surface), c.parameters);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind(where, 0) == 0 ? what : where + ": " + what);
  }
}

/// build_set for a run: the indenter's notes become warnings in the log and the progress.
ContactSet build_set_warning(const ContactSpec& c, AnalysisContext& ctx) {
  std::vector<std::string> notes;
  ContactSet set = build_set(c, ctx.mesh(), ctx.spec(), &notes);
  for (const std::string& note : notes) warn(ctx, note);
  return set;
}

/// check_no_initial_penetration at displacements u, as an InputError naming the case file and c.key.
void check_start(const ContactSet& set, const Eigen::VectorXd& u, double time, const ContactSpec& c, const CaseSpec& spec) {
  try {
    check_no_initial_penetration(set, u, "at t = " + fmt("%g", time) + " s");
  } catch (const InputError& e) {
    throw InputError(spec.file.string() + ": " + c.key + ": " + e.what());
  }
}

}  // namespace

Vec3 full_model_factors(double force_factor, const StepSpec& step, const mesh::Mesh& mesh,
                        const std::vector<int>& contact_nodes) {
  Vec3 factors = Vec3::Constant(force_factor);
  if (force_factor == 1.0) return factors;
  const std::set<int> contact(contact_nodes.begin(), contact_nodes.end());
  for (const BoundarySpec& bc : step.boundary) {
    if (bc.kind != BoundarySpec::Kind::symmetry) continue;
    const auto set = mesh.node_sets.find(bc.set);
    if (set == mesh.node_sets.end()) continue;
    const bool cuts = std::any_of(set->second.begin(), set->second.end(), [&](int a) { return contact.count(a) > 0; });
    for (int i = 0; i < 3; ++i)
      if (cuts && bc.dofs[i]) factors(i) = 0.0;
  }
  return factors;
}

std::vector<std::string> contact_history_columns(const std::string& n) {
  return {n + ".U1_mm", n + ".U2_mm", n + ".U3_mm", n + ".F1_N", n + ".F2_N", n + ".F3_N", n + ".normal_force_N",
          n + ".area_mm2", n + ".mean_pressure_kPa", n + ".max_penetration_mm", n + ".active_nodes",
          n + ".slipping_nodes", n + ".augmentations"};
}

ContactContributor::ContactContributor(const ContactSpec& spec, AnalysisContext& ctx)
    : ctx_(ctx), set_(build_set_warning(spec, ctx)), force_factor_(spec.force_factor),
      force_factors_(full_model_factors(spec.force_factor, first_step_with(ctx.spec(), spec.name), ctx.mesh(),
                                        set_.nodes())),
      history_(ctx.output().table("contact_" + spec.name + ".csv", contact_history_columns(spec.name),
                                  history_comments(set_, spec.force_factor, force_factors_))) {
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
    check_start(set_, ctx_.model().u, ctx_.model().time, spec, ctx_.spec());
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
  const Vec3 F = force_factors_.cwiseProduct(t.force);
  const std::vector<double> row{c.x(), c.y(), c.z(), F.x(), F.y(), F.z(),
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

void check_contacts_before_run(const LoadedCase& loaded) {
  const CaseSpec& spec = loaded.spec;
  const Eigen::VectorXd undeformed = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(loaded.mesh.num_nodes()));
  std::set<std::string> built;
  for (std::size_t s = 0; s < spec.steps.size(); ++s)
    for (const ContactSpec& c : spec.steps[s].contact) {
      if (!built.insert(c.name).second) continue;
      const ContactSet set = build_set(c, loaded.mesh, spec);
      if (s == 0) check_start(set, undeformed, 0.0, c, spec);  // later steps start from a deformed state
    }
}

bool case_has_friction(const CaseSpec& spec) {
  for (const StepSpec& s : spec.steps)
    for (const ContactSpec& c : s.contact)
      if (c.parameters.friction > 0.0) return true;
  return false;
}

}  // namespace cushion::solver
