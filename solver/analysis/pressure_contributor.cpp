#include "solver/analysis/pressure_contributor.hpp"

#include "mesh/shape.hpp"
#include "solver/dof_map.hpp"

namespace cushion::solver {

namespace {

/// A quadrature point of a face: values and (s, t) derivatives of the ELEMENT's shape functions there
/// (those of nodes off the face vanish on it) and the weight [-].
struct FacePoint {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;  ///< n x 2: dN_a/ds, dN_a/dt
  double w = 0.0;
};

/// Points of face `face`: xi(s, t) is the affine map of the face's corners in natural coordinates (quad:
/// (-1,-1), (1,-1), (1,1), (-1,1) to corners 0..3; triangle: corners 0, 1, 2 at (0,0), (1,0), (0,1)),
/// so x_s x x_t follows the outward node order of mesh::face_nodes.
std::vector<FacePoint> face_rule(mesh::ElementType type, int face) {
  const std::vector<int> local = mesh::face_nodes(type, face);
  const std::vector<mesh::Vec3> xi_nodes = mesh::node_coordinates(type);
  const bool quad = mesh::faces_per_element(type) == 6;
  const mesh::Vec3 P0 = xi_nodes[local[0]], P1 = xi_nodes[local[1]], P2 = xi_nodes[local[2]];
  const mesh::Vec3 P3 = quad ? xi_nodes[local[3]] : P0;
  const bool quadratic = type == mesh::ElementType::hex20 || type == mesh::ElementType::hex20r;
  const auto gauss = mesh::gauss_legendre(quad && !quadratic ? 2 : 3);
  std::vector<FacePoint> out;
  for (const auto& [gi, wi] : gauss)
    for (const auto& [gj, wj] : gauss) {
      mesh::Vec3 xi, d_s, d_t;
      double w = wi * wj;
      if (quad) {
        xi = 0.25 * ((1 - gi) * (1 - gj) * P0 + (1 + gi) * (1 - gj) * P1 + (1 + gi) * (1 + gj) * P2 + (1 - gi) * (1 + gj) * P3);
        d_s = 0.25 * ((1 - gj) * (P1 - P0) + (1 + gj) * (P2 - P3));
        d_t = 0.25 * ((1 - gi) * (P3 - P0) + (1 + gi) * (P2 - P1));
      } else {  // collapsed (Duffy) Gauss on the triangle: s = u, t = (1 - u) v, ds dt = (1 - u) du dv
        const double u = 0.5 * (1 + gi), v = 0.5 * (1 + gj);
        xi = P0 + u * (P1 - P0) + (1 - u) * v * (P2 - P0);
        d_s = P1 - P0, d_t = P2 - P0;
        w *= 0.25 * (1 - u);
      }
      const Eigen::MatrixXd G = mesh::shape_gradients(type, xi);
      FacePoint p;
      p.N = mesh::shape_values(type, xi);
      p.dN.resize(G.rows(), 2);
      p.dN.col(0) = G * d_s;
      p.dN.col(1) = G * d_t;
      p.w = w;
      out.push_back(std::move(p));
    }
  return out;
}

Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

class PressureContributor final : public ResidualContributor {
 public:
  PressureContributor(const AnalysisContext& ctx, const StepSpec& step, const DofMap& dofs)
      : mesh_(ctx.mesh()), step_(step), amplitudes_(ctx.spec().amplitudes), dofs_(dofs), t_start_(ctx.model().time) {}

  void begin_increment(const IncrementInfo& increment, EquilibriumProblem& problem) override {
    const double t_step = increment.t_end - t_start_;
    std::vector<double> p;
    for (const PressureSpec& ps : step_.pressures)
      p.push_back(ramped_value(ps.value, ps.amplitude, amplitudes_, ps.start_value, t_step, step_.period, t_start_));
    problem.add_term([this, p](const Eigen::VectorXd& u, Eigen::VectorXd& r, SparseMatrix* K) {
      for (std::size_t k = 0; k < step_.pressures.size(); ++k)
        add_face_pressure(mesh_, step_.pressures[k].face, p[k], u, dofs_, r, K);
    });
  }

 private:
  const mesh::Mesh& mesh_;
  const StepSpec& step_;
  const std::map<std::string, Amplitude>& amplitudes_;
  const DofMap& dofs_;
  double t_start_;
};

}  // namespace

void add_face_pressure(const mesh::Mesh& mesh, const mesh::Face& f, double p, const Eigen::VectorXd& u,
                       const DofMap& dofs, Eigen::VectorXd& r, SparseMatrix* K) {
  if (p == 0.0) return;
  const mesh::Element& el = mesh.elements[f.element];
  const std::vector<int> local = mesh::face_nodes(el.type, f.face);
  for (const FacePoint& q : face_rule(el.type, f.face)) {
    Vec3 x_s = Vec3::Zero(), x_t = Vec3::Zero();
    for (int a : local) {
      const int node = el.nodes[a];
      const Vec3 x = mesh.nodes[node] + u.segment<3>(3 * node);
      x_s += q.dN(a, 0) * x, x_t += q.dN(a, 1) * x;
    }
    const Vec3 n = x_s.cross(x_t);
    for (int a : local) {
      const int A = el.nodes[a];
      r.segment<3>(3 * A) += p * q.w * q.N(a) * n;
      if (!K) continue;
      for (int b : local) {
        const Mat3 dn = q.dN(b, 1) * cross_matrix(x_s) - q.dN(b, 0) * cross_matrix(x_t);
        const Mat3 k_ab = p * q.w * q.N(a) * dn;
        const int B = el.nodes[b];
        for (int i = 0; i < 3; ++i) {
          const int ei = dofs.equation(3 * A + i);
          if (ei < 0) continue;
          for (int j = 0; j < 3; ++j) {
            const int ej = dofs.equation(3 * B + j);
            if (ej >= 0 && k_ab(i, j) != 0.0) K->coeffRef(ei, ej) += k_ab(i, j);
          }
        }
      }
    }
  }
}

std::shared_ptr<ResidualContributor> step_pressures(const AnalysisContext& ctx, const StepSpec& step, const DofMap& dofs) {
  if (step.pressures.empty()) return nullptr;
  return std::make_shared<PressureContributor>(ctx, step, dofs);
}

bool case_has_pressure(const CaseSpec& spec) {
  for (const StepSpec& s : spec.steps)
    if (!s.pressures.empty()) return true;
  return false;
}

}  // namespace cushion::solver
