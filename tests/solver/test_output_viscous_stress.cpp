// Requirement: the frame's viscous_stress_norm (viscous_stress_norm_kPa in the .vtu) comes from the
// material interface (Material::viscous_stress), so a Prony material wrapped in an effect reports it too.
// Checks, on a distorted 2x2x2 hex block of Hyperfoam + 2 Prony terms loaded from the virgin state by a
// smooth field over dt = 0.1 s (point outputs and trial state from one assembly):
//  - plain Viscoelastic: non-zero, equal to the former formula |F (S - S_inf(F)) F^T / J| (relative 1e-12);
//  - Mullins over the same Viscoelastic (first loading: eta = 1, the effect adds nothing): non-zero and
//    equal to the plain value (relative 1e-12);
//  - strain-dependent Prony (c = 2): each point's viscous PK2 stress is f(J) = J^-c times the plain one.
#include <gtest/gtest.h>

#include "material/effect_mullins.hpp"
#include "material/effect_strain_dependent_prony.hpp"
#include "solver/analysis/analysis_output.hpp"
#include "tests/solver/solver_fixtures.hpp"

namespace cushion::solver {
namespace {

/// A smooth compressive displacement field [mm] on the block [0,2]^3 (about 15 % at the top).
Eigen::VectorXd compression(const mesh::Mesh& m) {
  Eigen::VectorXd u(3 * m.num_nodes());
  for (std::size_t a = 0; a < m.num_nodes(); ++a) {
    const Vec3& X = m.nodes[a];
    u.segment<3>(3 * a) = Vec3(0.02 * X(0) * X(2), 0.03 * X(1), -0.15 * X(2) + 0.02 * X(0) * X(1));
  }
  return u;
}

/// One assembly of the block with `material` from its virgin state: point outputs, trial state, frame.
struct Evaluation {
  std::vector<PointOutput> points;
  StateStore state;
  FrameData frame;
};

Evaluation evaluate(const mesh::Mesh& m, std::shared_ptr<const material::Material> material) {
  Section section{"foam", {}, std::move(material), Formulation::full, 1e-10};
  for (std::size_t e = 0; e < m.num_elements(); ++e) section.elements.push_back(static_cast<int>(e));
  const Assembler assembler(m, {section}, DofMap(m.num_nodes(), std::vector<bool>(3 * m.num_nodes(), false)));
  Evaluation out;
  out.state = assembler.make_state_store();
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(3 * m.num_nodes()), u = compression(m);
  Eigen::VectorXd f;
  const AssemblyStatus status = assembler.assemble(u0, u, 0.1, out.state, f, nullptr, &out.points);
  EXPECT_FALSE(status.failed()) << status.message;
  out.frame = make_frame(0.1, assembler, out.points, out.state, u, f);
  return out;
}

TEST(OutputViscousStress, PronyWithAnEffectReportsTheViscousStress) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 2, 0.15);
  const auto visco = test::visco_hyperfoam();
  const Evaluation plain = evaluate(m, visco);
  const Evaluation mullins =
      evaluate(m, std::make_shared<material::MullinsEffect>(visco, test::hyperfoam(), material::MullinsParameters{}));

  // The former formula (S - S_inf(F) from the point outputs), element averages over the points.
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    double visc = 0.0, V = 0.0;
    for (int q = 0; q < 8; ++q) {
      const PointOutput& p = plain.points[8 * e + q];
      const Vec6 S_inf = visco->long_term_base().evaluate(p.F).S;
      visc += p.dV0 * cauchy_from_pk2(p.F, from_voigt_stress(p.S - S_inf)).norm();
      V += p.dV0;
    }
    const double expected = visc / V;
    EXPECT_GT(expected, 1e-4) << "element " << e;  // [MPa]: the Prony terms carry stress after dt = 0.1 s
    EXPECT_NEAR(plain.frame.viscous_stress_norm[e], expected, 1e-12 * expected) << "element " << e;
    EXPECT_NEAR(mullins.frame.viscous_stress_norm[e], expected, 1e-12 * expected) << "element " << e;
  }
}

TEST(OutputViscousStress, StrainDependentPronyScalesTheViscousStress) {
  const mesh::Mesh m = test::distorted_block(mesh::ElementType::hex8, 1, 0.15);
  const auto visco = test::visco_hyperfoam();
  const material::StrainDependentPronyEffect scaled(visco, 2.0);
  const Evaluation plain = evaluate(m, visco);
  const std::size_t n = visco->state_size();
  for (int q = 0; q < 8; ++q) {
    const PointOutput& p = plain.points[q];
    const std::span<const double> state = plain.state.new_state(0).subspan(q * n, n);
    const Vec6 S_visc = visco->viscous_stress(p.F, state);
    EXPECT_GT(S_visc.norm(), 1e-4) << "point " << q;
    const Vec6 expected = scaled.factor(p.F.determinant()) * S_visc;
    EXPECT_LE((scaled.viscous_stress(p.F, state) - expected).norm(), 1e-14 * expected.norm()) << "point " << q;
  }
}

}  // namespace
}  // namespace cushion::solver
