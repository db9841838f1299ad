#include "solver/analysis/boundary.hpp"

#include <algorithm>

#include "solver/dof_map.hpp"

namespace cushion::solver {

namespace {

std::vector<int> condition_dofs(const mesh::Mesh& mesh, const BoundarySpec& bc) {
  std::vector<int> dofs;
  for (int node : mesh.node_sets.at(bc.set))
    for (int c = 0; c < 3; ++c)
      if (bc.dofs[c]) dofs.push_back(DofMap::dof(node, c));
  return dofs;
}

}  // namespace

std::vector<bool> constrained_mask(const mesh::Mesh& mesh, const StepSpec& step) {
  std::vector<bool> mask(3 * mesh.num_nodes(), false);
  for (const BoundarySpec& bc : step.boundary)
    for (int d : condition_dofs(mesh, bc)) mask[d] = true;
  return mask;
}

StepBoundary::StepBoundary(const mesh::Mesh& mesh, const StepSpec& step,
                           const std::map<std::string, Amplitude>& amplitudes, double t_start,
                           const Eigen::VectorXd& u_start, Eigen::VectorXd f_start)
    : step_(step), amplitudes_(amplitudes), t_start_(t_start), u_start_(u_start), f_start_(std::move(f_start)) {
  for (const BoundarySpec& bc : step.boundary) entries_.push_back({&bc, condition_dofs(mesh, bc)});
  if (f_start_.size() == 0) f_start_ = Eigen::VectorXd::Zero(u_start.size());
  for (const LoadSpec& load : step.loads) {
    std::vector<int> dofs;
    for (int node : mesh.node_sets.at(load.set)) dofs.push_back(DofMap::dof(node, load.component));
    loads_.push_back({&load, std::move(dofs)});
  }
}

Eigen::VectorXd StepBoundary::loads(double t_step) const {
  Eigen::VectorXd f = f_start_ * (1.0 - std::clamp(t_step / step_.period, 0.0, 1.0));
  for (const LoadEntry& e : loads_)
    for (int d : e.dofs)
      f(d) = ramped_value(e.load->value, e.load->amplitude, amplitudes_, f_start_(d), t_step, step_.period, t_start_);
  return f;
}

void StepBoundary::apply(double t_step, Eigen::VectorXd& u) const {
  for (const Entry& e : entries_)
    for (int d : e.dofs)
      u(d) = prescribed_value(*e.bc, amplitudes_, u_start_(d), t_step, step_.period, t_start_);
}

void StepBoundary::apply_motion(double t_step, Eigen::VectorXd& u, Eigen::VectorXd& v, Eigen::VectorXd& a) const {
  for (const Entry& e : entries_)
    for (int d : e.dofs) {
      const PrescribedMotion m = prescribed_motion(*e.bc, amplitudes_, u_start_(d), t_step, step_.period, t_start_);
      u(d) = m.u, v(d) = m.v, a(d) = m.a;
    }
}

std::vector<double> StepBoundary::corner_times() const {
  std::vector<double> times;
  std::vector<const std::optional<std::string>*> names;
  for (const Entry& e : entries_) names.push_back(&e.bc->amplitude);
  for (const LoadEntry& e : loads_) names.push_back(&e.load->amplitude);
  for (const auto* name : names) {
    if (!*name) continue;
    const Amplitude& a = amplitudes_.at(**name);
    for (double t : a.time) {
      const double t_step = a.total_time ? t - t_start_ : t;
      if (t_step > 0.0 && t_step < step_.period) times.push_back(t_step);
    }
  }
  return times;
}

}  // namespace cushion::solver
