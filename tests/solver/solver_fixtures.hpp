#pragma once
/// Shared helpers for the solver tests: small distorted meshes, the materials used in the checks,
/// a general homogeneous deformation and a central finite difference of an element's internal force.
#include <memory>
#include <random>

#include "material/hyperfoam.hpp"
#include "material/neo_hookean.hpp"
#include "material/viscoelastic.hpp"
#include "mesh/quadratic.hpp"
#include "mesh/structured_hex.hpp"
#include "solver/elements/solid_element.hpp"

namespace cushion::solver::test {

/// Block [0,2]^3 mm cut into n^3 hex8 / hex20 / hex20r (or 6 n^3 tet4 or tet10), every corner node
/// moved randomly by up to `distortion` times the element size. Quadratic elements stay
/// straight-sided (mid-edge nodes at the midpoints of the distorted edges) unless `curved`, which
/// moves the mid-edge nodes as well.
inline mesh::Mesh distorted_block(mesh::ElementType type, int n, double distortion, bool curved = false,
                                  unsigned seed = 7) {
  mesh::BlockSpec spec;
  spec.low = Vec3::Zero();
  spec.high = Vec3::Constant(2.0);
  spec.n = {n, n, n};
  spec.type = mesh::is_hexahedron(type) ? mesh::ElementType::hex8 : mesh::ElementType::tet4;
  mesh::Mesh m = mesh::structured_block(spec);
  const bool quadratic = type == mesh::ElementType::tet10 || type == mesh::ElementType::hex20 ||
                         type == mesh::ElementType::hex20r;
  auto make_quadratic = [&] { m = type == mesh::ElementType::tet10 ? mesh::to_tet10(m) : mesh::to_hex20(m, type); };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 2.0 / n;
  if (quadratic && curved) make_quadratic();
  for (auto& X : m.nodes) X += distortion * h * Vec3(u(rng), u(rng), u(rng));
  if (quadratic && !curved) make_quadratic();
  return m;
}

/// True if node X of the undistorted block [0,2]^3 lies on its boundary (tolerance 1e-9 mm).
inline bool on_block_boundary(const mesh::Mesh& undistorted, int node) {
  const Vec3& X = undistorted.nodes[node];
  for (int i = 0; i < 3; ++i)
    if (X(i) < 1e-9 || X(i) > 2.0 - 1e-9) return true;
  return false;
}

/// A general deformation gradient with det F = 0.8 (shear, stretch, no symmetry).
inline Mat3 general_F() {
  Mat3 F;
  F << 1.05, 0.12, -0.07, 0.09, 0.92, 0.11, -0.04, 0.08, 0.88;
  return F / std::cbrt(F.determinant() / 0.8);
}

inline std::shared_ptr<const material::NeoHookean> neo_hookean() {
  return std::make_shared<material::NeoHookean>(0.05, 0.12);  // mu, lambda [MPa]
}

/// Two-term hyperfoam (mu_i alpha_i > 0), foam-like moduli [MPa].
inline std::shared_ptr<const material::Hyperfoam> hyperfoam() {
  return std::make_shared<material::Hyperfoam>(
      std::vector<material::HyperfoamTerm>{{0.04, 6.0, 0.1}, {-0.004, -2.0, 0.0}});
}

/// Hyperfoam with two Prony terms (g = 0.3, tau = 0.5 s; g = 0.2, tau = 5 s).
inline std::shared_ptr<const material::Viscoelastic> visco_hyperfoam() {
  return std::make_shared<material::Viscoelastic>(
      hyperfoam(), std::vector<material::PronyTerm>{{0.3, 0.5}, {0.2, 5.0}});
}

/// Nodal coordinates of element e as a NodeMatrix [mm].
inline NodeMatrix element_nodes(const mesh::Mesh& m, int e) {
  const auto& el = m.elements[e];
  NodeMatrix X(3, mesh::nodes_per_element(el.type));
  for (int a = 0; a < X.cols(); ++a) X.col(a) = m.nodes[el.nodes[a]];
  return X;
}

/// Central difference of f_int with respect to u_new, step h [mm]: column j = d f_int / d u_j.
inline ElementMatrix fd_element_tangent(ElementInput in, double h) {
  const int ndof = static_cast<int>(in.u_new.size());
  std::vector<double> scratch(in.state_new.size());
  in.state_new = scratch;
  ElementMatrix K(ndof, ndof);
  const NodeMatrix u0 = in.u_new;
  for (int j = 0; j < ndof; ++j) {
    in.u_new = u0;
    in.u_new(j) += h;
    const ElementVector fp = integrate_element(in, false).f_int;
    in.u_new = u0;
    in.u_new(j) -= h;
    const ElementVector fm = integrate_element(in, false).f_int;
    K.col(j) = (fp - fm) / (2 * h);
  }
  return K;
}

}  // namespace cushion::solver::test
