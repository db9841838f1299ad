// Requirement: every element kernel's tangent equals the derivative of its internal force.
// Check: K from integrate_element vs a central finite difference of f_int (step 1e-6 mm on 2 mm
// elements), max |K - K_fd| <= 1e-6 max |K|, for hex8, hex8 F-bar, tet4, tet10, hex20 (C3D20) and
// hex20r (C3D20R) on distorted (quadratic: curved) elements under a general non-homogeneous
// deformation (det F ~ 0.8, finite strain), with NeoHookean, Hyperfoam and Hyperfoam + Prony (dt > 0
// from a non-trivial history).
#include <gtest/gtest.h>

#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

struct Case {
  mesh::ElementType type;
  Formulation formulation;
  const char* name;
};

const Case cases[] = {{mesh::ElementType::hex8, Formulation::full, "hex8"},
                      {mesh::ElementType::hex8, Formulation::fbar, "hex8 F-bar"},
                      {mesh::ElementType::tet4, Formulation::full, "tet4"},
                      {mesh::ElementType::tet10, Formulation::full, "tet10"},
                      {mesh::ElementType::hex20, Formulation::full, "hex20"},
                      {mesh::ElementType::hex20r, Formulation::full, "hex20r"}};

/// u = (F - I) X + noise [mm] at the element nodes.
NodeMatrix deformation(const NodeMatrix& X, const Mat3& F, double noise, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-noise, noise);
  NodeMatrix d = (F - Mat3::Identity()) * X;
  for (int i = 0; i < d.size(); ++i) d(i) += u(rng);
  return d;
}

void check_tangent(const material::Material& mat, bool with_history) {
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.name) + " / " + mat.describe());
    const mesh::Mesh m = test::distorted_block(c.type, 1, 0.12, true);
    std::mt19937 rng(11);
    const int nq = num_points(c.type);
    const std::size_t ns = mat.state_size();
    std::vector<double> state0(nq * ns), state1(nq * ns), state2(nq * ns);
    for (int q = 0; q < nq; ++q) mat.initial_state(std::span<double>(state0.data() + q * ns, ns));

    ElementInput in;
    in.type = c.type;
    in.formulation = c.formulation;
    in.X = test::element_nodes(m, 0);
    in.material = &mat;
    Mat3 F = test::general_F();
    in.u_old = NodeMatrix::Zero(3, in.X.cols());
    in.state_old = state0;
    if (with_history) {
      // First increment to 60 % of the deformation over 0.3 s builds a non-trivial history.
      in.u_new = deformation(in.X, Mat3::Identity() + 0.6 * (F - Mat3::Identity()), 0.03, rng);
      in.state_new = state1;
      in.dt = 0.3;
      ASSERT_NE(integrate_element(in, false).status, material::Status::failed);
      in.u_old = in.u_new;
      in.state_old = state1;
      in.dt = 0.2;
    }
    in.u_new = deformation(in.X, F, 0.05, rng);
    in.state_new = state2;
    const ElementOutput out = integrate_element(in, true);
    ASSERT_EQ(out.status, material::Status::ok) << out.message;
    const ElementMatrix K_fd = test::fd_element_tangent(in, 1e-6);
    const double scale = out.K.cwiseAbs().maxCoeff();
    EXPECT_LE((out.K - K_fd).cwiseAbs().maxCoeff(), 1e-6 * scale);
    if (c.formulation == Formulation::full && ns == 0) {  // a potential: K is symmetric
      EXPECT_LE((out.K - out.K.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
    }
  }
}

TEST(ElementTangent, NeoHookeanMatchesFiniteDifference) { check_tangent(*test::neo_hookean(), false); }

TEST(ElementTangent, HyperfoamMatchesFiniteDifference) { check_tangent(*test::hyperfoam(), false); }

TEST(ElementTangent, ViscoelasticHyperfoamWithHistoryMatchesFiniteDifference) {
  check_tangent(*test::visco_hyperfoam(), true);
}

TEST(ElementTangent, FbarTangentIsUnsymmetricUnderNonUniformDilatation) {
  // Guards against a symmetrised F-bar tangent: the consistent one is unsymmetric.
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 1, 0.12);
  const auto mat = test::neo_hookean();
  std::mt19937 rng(3);
  ElementInput in;
  in.formulation = Formulation::fbar;
  in.X = test::element_nodes(m, 0);
  in.material = mat.get();
  in.u_old = NodeMatrix::Zero(3, 8);
  in.u_new = deformation(in.X, test::general_F(), 0.1, rng);
  const ElementOutput out = integrate_element(in, true);
  const double scale = out.K.cwiseAbs().maxCoeff();
  EXPECT_GT((out.K - out.K.transpose()).cwiseAbs().maxCoeff(), 1e-4 * scale);
}

TEST(ElementTangent, InvertedElementReportsFailure) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 1, 0.0);
  const auto mat = test::neo_hookean();
  ElementInput in;
  in.X = test::element_nodes(m, 0);
  in.material = mat.get();
  in.u_old = NodeMatrix::Zero(3, 8);
  in.u_new = (Mat3(Vec3(1, 1, -0.5).asDiagonal()) - Mat3::Identity()) * in.X;  // det F < 0
  const ElementOutput out = integrate_element(in, true);
  EXPECT_EQ(out.status, material::Status::failed);
  EXPECT_EQ(out.failed_point, 0);
}

}  // namespace
}  // namespace cushion::solver
