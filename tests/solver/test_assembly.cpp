// Requirement: the assembled tangent is the derivative of the assembled residual, and assembly is
// bitwise deterministic for any number of threads.
// Checks: K_ff vs a central difference (step 1e-6 mm) of the free residual on a distorted 2x2x2 hex
// mesh with two sections (NeoHookean full integration, Hyperfoam + Prony with F-bar, dt = 0.1 s),
// max |K - K_fd| <= 1e-6 max |K|; f_int, K and point outputs identical bit for bit with 1, 2 and 3
// threads on a 4x4x4 hex and a tet10 mesh; failures name the first failed element.
#include <gtest/gtest.h>

#include <cstring>

#include "solver/equilibrium.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

/// A smooth non-homogeneous displacement field [mm] on the block.
Eigen::VectorXd smooth_field(const mesh::Mesh& m, double amplitude) {
  Eigen::VectorXd u(3 * m.num_nodes());
  for (std::size_t a = 0; a < m.num_nodes(); ++a) {
    const Vec3& X = m.nodes[a];
    u.segment<3>(3 * a) = amplitude * Vec3(0.3 * X(1) * X(2) - 0.2 * X(0), 0.15 * X(0) * X(0) + 0.1 * X(2),
                                           -0.25 * X(2) + 0.1 * X(0) * X(1));
  }
  return u;
}

std::vector<Section> two_sections(const mesh::Mesh& m) {
  Section a{"soft", {}, test::neo_hookean(), Formulation::full, 1e-10};
  Section b{"foam", {}, test::visco_hyperfoam(), Formulation::fbar, 1e-10};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) (m.nodes[m.elements[e].nodes[0]](2) < 0.5 ? a : b).elements.push_back(e);
  return {a, b};
}

TEST(Assembly, TangentMatchesFiniteDifferenceOfResidual) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 2, 0.12);
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  for (std::size_t a = 0; a < m.num_nodes(); ++a)
    if (m.nodes[a](2) < 0.3) constrained[3 * a] = constrained[3 * a + 1] = constrained[3 * a + 2] = true;
  const auto sections = two_sections(m);
  ASSERT_FALSE(sections[0].elements.empty());
  ASSERT_FALSE(sections[1].elements.empty());
  const Assembler assembler(m, sections, DofMap(m.num_nodes(), constrained), {2});
  StateStore state = assembler.make_state_store();
  const Eigen::VectorXd u_old = Eigen::VectorXd::Zero(3 * m.num_nodes());
  const Eigen::VectorXd u = smooth_field(m, 1.0), f_ext = u_old;
  EquilibriumProblem problem(assembler, state, u_old, u, f_ext, 0.1);

  Eigen::VectorXd x = assembler.dofs().gather_free(u), r, rp, rm;
  ASSERT_FALSE(problem.evaluate(x, r, true).status == material::Status::failed);
  const Eigen::MatrixXd K = Eigen::MatrixXd(problem.tangent());
  Eigen::MatrixXd K_fd(K.rows(), K.cols());
  const double h = 1e-6;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp(j) += h;
    xm(j) -= h;
    problem.evaluate(xp, rp, false);
    problem.evaluate(xm, rm, false);
    K_fd.col(j) = (rp - rm) / (2 * h);
  }
  EXPECT_LE((K - K_fd).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
}

struct Snapshot {
  Eigen::VectorXd f;
  std::vector<double> K;
  std::vector<PointOutput> points;
};

Snapshot assemble_with(const mesh::Mesh& m, unsigned threads) {
  std::vector<bool> constrained(3 * m.num_nodes(), false);
  for (std::size_t a = 0; a < m.num_nodes(); ++a)
    if (m.nodes[a](2) < 0.1) constrained[3 * a + 2] = true;
  Section s{"all", {}, test::visco_hyperfoam(), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), constrained), {threads});
  EXPECT_EQ(assembler.num_threads(), threads);
  StateStore state = assembler.make_state_store();
  SparseMatrix K = assembler.make_matrix();
  Snapshot snap;
  const Eigen::VectorXd u = smooth_field(m, 0.5);
  const auto status = assembler.assemble(0.5 * u, u, 0.05, state, snap.f, &K, &snap.points);
  EXPECT_EQ(status.status, material::Status::ok);
  snap.K.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
  return snap;
}

TEST(Assembly, BitwiseIdenticalForAnyThreadCount) {
  for (auto type : {mesh::ElementType::hex8, mesh::ElementType::tet10}) {
    SCOPED_TRACE(mesh::to_string(type));
    const mesh::Mesh m = test::distorted_block(type, type == mesh::ElementType::hex8 ? 4 : 2, 0.1);
    const Snapshot one = assemble_with(m, 1);
    for (unsigned threads : {2u, 3u}) {
      const Snapshot many = assemble_with(m, threads);
      ASSERT_EQ(one.f.size(), many.f.size());
      EXPECT_EQ(std::memcmp(one.f.data(), many.f.data(), sizeof(double) * one.f.size()), 0);
      ASSERT_EQ(one.K.size(), many.K.size());
      EXPECT_EQ(std::memcmp(one.K.data(), many.K.data(), sizeof(double) * one.K.size()), 0);
      ASSERT_EQ(one.points.size(), many.points.size());
      for (std::size_t p = 0; p < one.points.size(); ++p) EXPECT_EQ(one.points[p].S, many.points[p].S);
    }
  }
}

TEST(Assembly, ColoursSeparateElementsSharingNodes) {
  // Structured hex: 8 colours suffice and greedy colouring finds them.
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 4, 0.0);
  Section s{"all", {}, test::neo_hookean(), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  const Assembler assembler(m, {s}, DofMap(m.num_nodes(), {}), {2});
  EXPECT_EQ(assembler.num_colours(), 8u);
}

TEST(Assembly, ReportsFirstFailedElementAndRejectsForeignMatrix) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 2, 0.0);
  Section s{"all", {}, test::neo_hookean(), Formulation::full, 0.0};
  for (int e = 0; e < static_cast<int>(m.num_elements()); ++e) s.elements.push_back(e);
  for (unsigned threads : {1u, 2u}) {
    const Assembler assembler(m, {s}, DofMap(m.num_nodes(), {}), {threads});
    StateStore state = assembler.make_state_store();
    // Invert elements 3 and 6 by pushing one of their private corner nodes through the element.
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * m.num_nodes());
    for (int e : {6, 3}) {
      const int corner = m.elements[e].nodes[e == 3 ? 2 : 7];
      u.segment<3>(3 * corner) = -1.8 * (m.nodes[corner] - Vec3::Constant(1.0));
    }
    Eigen::VectorXd f;
    const AssemblyStatus status = assembler.assemble(u, u, 0.0, state, f, nullptr);
    EXPECT_TRUE(status.failed());
    EXPECT_EQ(status.element, 3);
    SparseMatrix wrong(3, 3);
    EXPECT_THROW(assembler.assemble(u, u, 0.0, state, f, &wrong), std::logic_error);
  }
}

TEST(Assembly, RejectsFbarOnTets) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::tet4, 1, 0.0);
  Section s{"all", {0}, test::neo_hookean(), Formulation::fbar, 0.0};
  EXPECT_THROW(Assembler(m, {s}, DofMap(m.num_nodes(), {}), {}), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::solver
