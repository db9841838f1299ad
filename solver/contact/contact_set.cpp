// Node-to-rigid-surface contact: penalty + augmented Lagrangian normal force, regularised Coulomb
// friction with stick points, exact linearisation (see contact_set.hpp for the equations).
#include "solver/contact/contact_set.hpp"

#include <sstream>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/selectors.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* format, double x) { return io::format_with(format, x); }

/// The C1 ramp p(x) of width w [N] and its slope (contact_set.hpp).
std::pair<double, double> smooth_ramp(double x, double w) {
  if (x >= 0.5 * w) return {x, 1.0};
  if (x <= -0.5 * w) return {0.0, 0.0};
  const double y = x + 0.5 * w;
  return {y * y / (2.0 * w), y / w};
}

/// Corner nodes of the faces of the set, as indices into `nodes` (quads: 4 in cyclic order, triangles: 3).
std::vector<std::vector<int>> set_faces(const mesh::Mesh& mesh, const std::vector<int>& nodes) {
  std::vector<int> index(mesh.num_nodes(), -1);
  for (std::size_t k = 0; k < nodes.size(); ++k) index[nodes[k]] = static_cast<int>(k);
  std::vector<std::vector<int>> faces;
  for (const mesh::Face& f : mesh::surface_from_node_set(mesh, nodes)) {
    const mesh::Element& el = mesh.elements[f.element];
    const std::vector<int> local = mesh::face_nodes(el.type, f.face);
    const std::size_t corners = el.type == mesh::ElementType::hex8 ? 4 : 3;
    std::vector<int> face;
    for (std::size_t c = 0; c < corners; ++c) face.push_back(index[el.nodes[local[c]]]);
    faces.push_back(std::move(face));
  }
  return faces;
}

/// Integral [mm^2] of weight(x, n) over a face (corner positions y, indenter frame; n its unit normal at x)
/// from n x n sample points: midpoints of a bilinear quad's parameter cells, centroids of a triangle's n^2
/// sub-triangles.
template <class Weight>
double integrate_face(const std::vector<Vec3>& y, const Weight& weight) {
  constexpr int n = 8;
  double sum = 0.0;
  if (y.size() == 4) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double a = (i + 0.5) / n, b = (j + 0.5) / n;
        const Vec3 x = (1 - a) * (1 - b) * y[0] + a * (1 - b) * y[1] + a * b * y[2] + (1 - a) * b * y[3];
        const Vec3 da = (1 - b) * (y[1] - y[0]) + b * (y[2] - y[3]), db = (1 - a) * (y[3] - y[0]) + a * (y[2] - y[1]);
        const Vec3 normal = da.cross(db);
        const double dA = normal.norm() / (n * n);
        if (dA > 0.0) sum += dA * weight(x, Vec3(normal / (n * n * dA)));
      }
    return sum;
  }
  const Vec3 normal = 0.5 * (y[1] - y[0]).cross(y[2] - y[0]);
  const double dA = normal.norm() / (n * n);
  if (!(dA > 0.0)) return 0.0;
  const Vec3 unit = normal.normalized();
  auto sample = [&](double a, double b) { sum += dA * weight(y[0] + a / n * (y[1] - y[0]) + b / n * (y[2] - y[0]), unit); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      sample(i + 1.0 / 3.0, j + 1.0 / 3.0);                     // upward sub-triangle
      if (i + j < n - 1) sample(i + 2.0 / 3.0, j + 2.0 / 3.0);  // downward sub-triangle
    }
  return sum;
}

}  // namespace

std::vector<double> tributary_areas(const mesh::Mesh& mesh, const std::vector<int>& nodes) {
  std::vector<double> per_node(mesh.num_nodes(), 0.0);
  for (const mesh::Face& f : mesh::surface_from_node_set(mesh, nodes)) {
    // The face area is shared equally by all its nodes (corners and, on quadratic faces, mid-edge
    // nodes): a positive lumping, unlike the consistent loads of a quadratic face (zero at tet10
    // corners, negative at hex20 corners), which would pull corner nodes into the indenter.
    const mesh::Element& el = mesh.elements[f.element];
    const std::vector<int> local = mesh::face_nodes(el.type, f.face);
    const double area = mesh::face_area(mesh, f);
    for (int k : local) per_node[el.nodes[k]] += area / static_cast<double>(local.size());
  }
  std::vector<double> out;
  out.reserve(nodes.size());
  for (int a : nodes) out.push_back(per_node.at(a));
  return out;
}

ContactSet::ContactSet(std::string name, const mesh::Mesh& mesh, std::vector<int> nodes,
                       std::shared_ptr<const RigidSurface> surface, ContactParameters parameters)
    : name_(std::move(name)), mesh_(mesh), nodes_(std::move(nodes)), surface_(std::move(surface)), p_(parameters) {
  const std::string where = "contact '" + name_ + "'";
  if (nodes_.empty()) throw InputError(where + ": the contact node set is empty");
  if (!(p_.penalty > 0.0)) throw InputError(where + ": penalty must be > 0 MPa/mm");
  if (p_.tangential_penalty <= 0.0) p_.tangential_penalty = 0.1 * p_.penalty;
  if (p_.friction < 0.0) throw InputError(where + ": friction coefficient must be >= 0");
  if (!(p_.tolerance > 0.0)) throw InputError(where + ": penetration tolerance must be > 0 mm");
  if (p_.smoothing < 0.0) p_.smoothing = 0.5 * p_.tolerance;
  area_ = tributary_areas(mesh_, nodes_);
  faces_ = set_faces(mesh_, nodes_);
  int off_surface = 0, first = -1;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    if (!(area_[k] > 0.0)) ++off_surface, first = first < 0 ? nodes_[k] : first;
  if (off_surface) {
    double z_top = -INFINITY;  // the hint names this mesh's top face
    for (const Vec3& X : mesh_.nodes) z_top = std::max(z_top, X.z());
    std::ostringstream top;
    top << z_top;
    throw InputError(where + ": " + std::to_string(off_surface) + " of " + std::to_string(nodes_.size()) +
                     " contact nodes are not on the outer surface of the mesh, or on no exterior face whose nodes all "
                     "belong to the set (first: node " +
                     std::to_string(mesh_.node_labels.empty() ? first + 1 : mesh_.node_labels[first]) +
                     "); select surface nodes only, e.g. the top face \"z == " + top.str() + "\"");
  }
  const std::size_t n = nodes_.size();
  lambda_.assign(n, 0.0), lambda_trial_ = lambda_;
  xi_.assign(n, Vec3::Zero()), xi_trial_ = xi_;
  touching_.assign(n, 0), touching_trial_ = touching_;
  gap_.assign(n, INFINITY), t_N_.assign(n, 0.0), grad_norm_.assign(n, 1.0);
  force_.assign(n, Vec3::Zero());
  y_.assign(n, Vec3::Zero());
  status_.assign(n, ContactStatus::open);
}

void ContactSet::evaluate(const Eigen::VectorXd& u, const DofMap& dofs, Eigen::VectorXd& r_full, SparseMatrix* K) {
  evaluate_at(position_, Vec3::Zero(), u, dofs, r_full, K);
}

void ContactSet::evaluate_predictor(const Vec3& from, const Eigen::VectorXd& u, const DofMap& dofs,
                                    Eigen::VectorXd& r_full, SparseMatrix* K) {
  evaluate_at(from, position_ - from, u, dofs, r_full, K);
}

void ContactSet::evaluate_at(const Vec3& c, const Vec3& dc, const Eigen::VectorXd& u, const DofMap& dofs,
                             Eigen::VectorXd& r_full, SparseMatrix* K) {
  switches_ = 0;
  const double mu = p_.friction;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int a = nodes_[k];
    const Vec3 y = mesh_.nodes[a] + u.segment<3>(3 * a) - c;  // indenter frame [mm]
    const GapPoint gp = surface_->gap(y);
    const double eps = p_.penalty * area_[k];
    const auto [t_N, dt_N] = smooth_ramp(lambda_trial_[k] - eps * gp.g, eps * p_.smoothing);
    const ContactStatus old_status = status_[k];
    Vec3 F = Vec3::Zero();        // force on the node [N]
    Mat3 dF = Mat3::Zero();       // dF/dx [N/mm]
    gap_[k] = gp.g;
    y_[k] = y;
    grad_norm_[k] = gp.grad.norm();
    if (t_N > 0.0) {
      t_N_[k] = t_N;
      F = t_N * gp.grad;
      dF = -eps * dt_N * gp.grad * gp.grad.transpose() + t_N * gp.hess;
      status_[k] = mu > 0.0 ? ContactStatus::stick : ContactStatus::slip;  // frictionless: slides freely
      touching_trial_[k] = 1;
      xi_trial_[k] = y;
      if (mu > 0.0 && touching_[k]) {
        const double nn = grad_norm_[k];
        const Vec3 n = gp.grad / nn;
        const Mat3 P = Mat3::Identity() - n * n.transpose();
        const Mat3 N = P * gp.hess / nn;  // dn/dx
        const Vec3 w = y - xi_[k];
        const Vec3 s = P * w;
        const Mat3 ds = P - (n * w.transpose() + n.dot(w) * Mat3::Identity()) * N;
        const double eps_T = p_.tangential_penalty * area_[k];
        const double s_norm = s.norm();
        if (eps_T * s_norm <= mu * t_N) {  // stick
          F += -eps_T * s;
          dF += -eps_T * ds;
          xi_trial_[k] = xi_[k];
        } else {  // slip: return to the Coulomb cone, stick point follows
          const Vec3 e = s / s_norm;
          const Vec3 F_T = -mu * t_N * e;
          F += F_T;
          dF += mu * eps * dt_N * e * gp.grad.transpose() - mu * t_N * (Mat3::Identity() - e * e.transpose()) * ds / s_norm;
          xi_trial_[k] = y + F_T / eps_T;
          status_[k] = ContactStatus::slip;
        }
      }
    } else {
      t_N_[k] = 0.0;
      status_[k] = ContactStatus::open;
      touching_trial_[k] = 0;
    }
    if ((old_status == ContactStatus::open) != (status_[k] == ContactStatus::open)) ++switches_;
    F -= dF * dc;  // F(x, c + dc) to first order: dF/dc = -dF/dx (F depends on x - c only)
    force_[k] = F;
    for (int i = 0; i < 3; ++i) r_full(3 * a + i) -= F(i);
    if (!K) continue;
    for (int i = 0; i < 3; ++i) {
      const int ei = dofs.equation(3 * a + i);
      if (ei < 0) continue;
      for (int j = 0; j < 3; ++j) {
        const int ej = dofs.equation(3 * a + j);
        if (ej >= 0 && dF(i, j) != 0.0) K->coeffRef(ei, ej) -= dF(i, j);
      }
    }
  }
}

AugmentOutcome ContactSet::augment() {
  AugmentOutcome out;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    if (t_N_[k] > 0.0) out.max_penetration = std::max(out.max_penetration, std::abs(gap_[k]));
  if (!p_.augmented) return out;  // linear pressure-overclosure law: the penalty force is the answer
  const bool within = out.max_penetration <= p_.tolerance;
  lambda_trial_ = t_N_;  // Uzawa update (also the warm start of the next increment)
  if (within) return out;
  out.converged = false;
  if (++augmentations_ > p_.max_augmentations) {
    out.failed = true;
    out.message = "contact '" + name_ + "': penetration " + fmt("%.4g", out.max_penetration) +
                  " mm still exceeds the tolerance " + fmt("%.4g", p_.tolerance) + " mm after " +
                  std::to_string(p_.max_augmentations) + " augmentations: the penalty " + fmt("%.4g", p_.penalty) +
                  " MPa/mm is too low; raise penalty_MPa_per_mm (e.g. to " +
                  fmt("%.3g", p_.penalty * std::max(10.0, out.max_penetration / p_.tolerance)) +
                  ") or max_augmentations, or relax tolerance_mm";
  }
  return out;
}

void ContactSet::commit() {
  lambda_ = lambda_trial_;
  xi_ = xi_trial_;
  touching_ = touching_trial_;
  augmentations_ = 0;
}

void ContactSet::revert() {
  lambda_trial_ = lambda_;
  xi_trial_ = xi_;
  touching_trial_ = touching_;
  augmentations_ = 0;
}

ContactTotals ContactSet::totals() const {
  ContactTotals t;
  t.min_gap = INFINITY;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    t.min_gap = std::min(t.min_gap, gap_[k]);
    t.force += force_[k];
    if (t_N_[k] <= 0.0) continue;
    ++t.active;
    if (status_[k] == ContactStatus::slip) ++t.slipping;
    t.normal_force += t_N_[k] * grad_norm_[k];
    t.max_penetration = std::max(t.max_penetration, -gap_[k]);
  }
  if (t.active > 0) t.area = contact_area();
  if (t.area > 0.0) t.mean_pressure = t.normal_force / t.area;
  return t;
}

double ContactSet::contact_area() const {
  // In contact: gap within the penetration tolerance [mm] (a node carrying force may sit at g > 0 once its
  // multiplier exceeds its force, e.g. while the foam relaxes under a held indenter).
  const double touching = p_.tolerance;
  double area = 0.0;
  std::vector<Vec3> y;
  for (const std::vector<int>& face : faces_) {
    if (std::none_of(face.begin(), face.end(), [&](int k) { return t_N_[k] > 0.0; })) continue;
    y.clear();
    for (int k : face) y.push_back(y_[k]);
    // Projected on the indenter's surface: |n_foam . n_indenter| dA where the foam touches (gap <= touching).
    area += integrate_face(y, [&](const Vec3& x, const Vec3& n) {
      const GapPoint gp = surface_->gap(x);
      const double grad = gp.grad.norm();
      return gp.g <= touching && grad > 0.0 ? std::abs(n.dot(gp.grad)) / grad : 0.0;
    });
  }
  return area;
}

std::pair<double, int> ContactSet::penetration_at(const Eigen::VectorXd& u) const {
  double worst = 0.0;
  int label = -1;
  for (int a : nodes_) {
    const double g = surface_->gap(mesh_.nodes[a] + u.segment<3>(3 * a) - position_).g;
    if (-g > worst) worst = -g, label = mesh_.node_labels.empty() ? a + 1 : mesh_.node_labels[a];
  }
  return {worst, label};
}

void ContactSet::add_frame_fields(FrameData& frame) const {
  const std::size_t n = mesh_.num_nodes();
  NamedField pressure{name_ + "_pressure_kPa", 1, std::vector<double>(n, 0.0)};
  NamedField gap{name_ + "_gap_mm", 1, std::vector<double>(n, NAN)};
  NamedField status{name_ + "_status", 1, std::vector<double>(n, -1.0)};
  NamedField force{name_ + "_force_N", 3, std::vector<double>(3 * n, 0.0)};
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int a = nodes_[k];
    pressure.values[a] = 1e3 * t_N_[k] * grad_norm_[k] / area_[k];
    gap.values[a] = gap_[k];
    status.values[a] = static_cast<double>(status_[k]);
    for (int i = 0; i < 3; ++i) force.values[3 * a + i] = force_[k](i);
  }
  frame.point_fields.push_back(std::move(pressure));
  frame.point_fields.push_back(std::move(gap));
  frame.point_fields.push_back(std::move(status));
  frame.point_fields.push_back(std::move(force));
}

}  // namespace cushion::solver
