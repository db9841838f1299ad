// Steady-state dynamics about a preloaded state: (1) a laterally free cube on rollers under a flat
// frictionless platen reproduces the material's frequency-domain modulus E*(w) = S33 + l3^2 C*_c(w)
// (C* condensed to uniaxial stress) to 1e-6, with the relaxed or the as-left base stress; (2) the
// undamped sweep peaks of a bar match the eigenvalues of (K, M) within 0.5 %.
#include <gtest/gtest.h>

#include "material/neo_hookean.hpp"
#include "solver/dynamics/modes.hpp"
#include "solver_fixtures.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

/// Nominal modulus of the material about F (diagonal): S33 + l3^2 (C33 - C3a Caa^-1 Ca3), a = 1, 2.
cplx material_modulus(const material::Material& mat, const Mat3& F, double S33, double omega) {
  const Mat6c C = mat.complex_tangent(F, omega);
  const Eigen::Matrix2cd Caa = C.block<2, 2>(0, 0);
  const Eigen::Vector2cd Ca3 = C.block<2, 1>(0, 2), C3a = C.block<1, 2>(2, 0).transpose();
  const cplx Cc = C(2, 2) - (C3a.transpose() * (Caa.inverse() * Ca3))(0);
  return S33 + F(2, 2) * F(2, 2) * Cc;
}

struct Cube {
  double H = 10.0;
  mesh::Mesh mesh = column(10.0, 10.0, 2, 2);
  std::shared_ptr<const material::Viscoelastic> mat = visco_hyperfoam();
  std::vector<Section> sections;
  std::unique_ptr<Assembler> A;
  StateStore st;
  Eigen::VectorXd u;
  Cube() {
    sections = {{"foam", {}, mat, Formulation::full, 1e-20}};
    for (std::size_t e = 0; e < mesh.num_elements(); ++e) sections[0].elements.push_back(static_cast<int>(e));
    A = std::make_unique<Assembler>(
        mesh, sections,
        DofMap(mesh.num_nodes(), constrained_mask(mesh, {set_dofs(mesh, "xmin", 0), set_dofs(mesh, "ymin", 1),
                                                          set_dofs(mesh, "zmin", 2), set_dofs(mesh, "zmax", 2)})),
        AssemblyOptions{1});
    st = A->make_state_store();
    u = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  }
  /// Platen driven, rollers held: nominal modulus E = (R/A0) / (U/H0) at f [Hz].
  cplx fe_modulus(const LinearisedSystem& sys, double f) const {
    Excitation x{set_dofs(mesh, "zmax", 2), set_dofs(mesh, "xmin", 0)};
    for (int d : set_dofs(mesh, "ymin", 1)) x.held.push_back(d);
    for (int d : set_dofs(mesh, "zmin", 2)) x.held.push_back(d);
    HarmonicModel model;
    model.system = &sys;
    SteadyStateSolver s(model, {}, x, {{"top", set_dofs(mesh, "zmax", 2)}, {"base", set_dofs(mesh, "zmin", 2)}});
    const auto r = s.solve(f, 0.01);
    return r.reaction[0] / 100.0 / (0.01 / H);
  }
};

TEST(DynamicsConsistency, CubeModulusEqualsMaterialModulusRelaxedBase) {
  Cube c;
  ramp(*c.A, c.st, c.u, set_dofs(c.mesh, "zmax", 2), -2.0, 8, 1e6);  // 20 % preload, relaxed
  const auto points = base_point_states(*c.A, c.st, c.u, BaseStress::relaxed);
  LinearisedSystem sys(c.mesh, c.sections, points, c.u);
  const Mat3 F = points[0].F;
  std::vector<double> scratch;
  const double S33 = c.mat->long_term_base().integrate(F, F, 0.0, {}, scratch).S(2);
  ASSERT_LT(S33, -1e-3);
  for (double f : {0.5, 1.0, 5.0, 20.0}) {
    const cplx E_fe = c.fe_modulus(sys, f), E_mat = material_modulus(*c.mat, F, S33, 2 * M_PI * f);
    EXPECT_LT(std::abs(E_fe / E_mat - 1.0), 1e-6) << f;
    EXPECT_GT(std::arg(E_fe), 1e-3) << f;  // the Prony terms give a real loss
  }
}

TEST(DynamicsConsistency, AsLeftBaseUsesCommittedStressRelaxedIgnoresIt) {
  Cube c;
  ramp(*c.A, c.st, c.u, set_dofs(c.mesh, "zmax", 2), -2.0, 8, 0.02);  // fast preload: not relaxed
  // Committed total PK2 S33 from the platen force: P33 = R / A0 = l3 S33.
  Eigen::VectorXd f_int;
  StateStore probe = c.st;
  c.A->assemble(c.u, c.u, 0.0, probe, f_int, nullptr);
  double R = 0.0;
  for (int d : set_dofs(c.mesh, "zmax", 2)) R += f_int(d);
  const auto as_left = base_point_states(*c.A, c.st, c.u, BaseStress::as_left);
  const auto relaxed = base_point_states(*c.A, c.st, c.u, BaseStress::relaxed);
  const Mat3 F = as_left[0].F;
  const double S33_total = R / 100.0 / F(2, 2);
  std::vector<double> scratch;
  const double S33_inf = c.mat->long_term_base().integrate(F, F, 0.0, {}, scratch).S(2);
  ASSERT_GT(std::abs(S33_total - S33_inf), 0.2 * std::abs(S33_inf));  // far from relaxed
  LinearisedSystem sys_left(c.mesh, c.sections, as_left, c.u), sys_relaxed(c.mesh, c.sections, relaxed, c.u);
  for (double f : {1.0, 20.0}) {
    const double w = 2 * M_PI * f;
    EXPECT_LT(std::abs(c.fe_modulus(sys_left, f) / material_modulus(*c.mat, F, S33_total, w) - 1.0), 1e-6);
    EXPECT_LT(std::abs(c.fe_modulus(sys_relaxed, f) / material_modulus(*c.mat, F, S33_inf, w) - 1.0), 1e-6);
  }
}

TEST(DynamicsModes, UndampedSweepPeaksMatchEigenvalues) {
  const mesh::Mesh mesh = column(10.0, 80.0, 20);
  std::vector<Section> sections{{"foam", {}, std::make_shared<material::NeoHookean>(0.02, 0.01), Formulation::full, 1e-8}};
  for (int e = 0; e < 20; ++e) sections[0].elements.push_back(e);
  Assembler A(mesh, sections, DofMap(mesh.num_nodes(), {}), AssemblyOptions{1});
  StateStore st = A.make_state_store();
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  LinearisedSystem sys(mesh, sections, base_point_states(A, st, u0, BaseStress::relaxed), u0);
  // Base shaken in z, top free, lateral DOFs held: fixed-free axial modes.
  Excitation x{set_dofs(mesh, "zmin", 2), lateral_dofs(mesh)};
  HarmonicModel model;
  model.system = &sys;
  SteadyStateSolver s(model, {}, x, {{"top", set_dofs(mesh, "zmax", 2)}, {"base", set_dofs(mesh, "zmin", 2)}});
  std::vector<bool> held(3 * mesh.num_nodes(), false);
  for (int d : x.driven) held[d] = true;
  for (int d : x.held) held[d] = true;
  std::vector<int> free;
  for (std::size_t d = 0; d < held.size(); ++d)
    if (!held[d]) free.push_back(static_cast<int>(d));
  const auto fn = natural_frequencies(sys.long_term_stiffness(), sys.mass(), free, 2);
  ASSERT_EQ(fn.size(), 2u);
  auto amp = [&](double f) { return std::abs(s.solve(f, 1.0).displacement[0]); };
  std::vector<double> peaks;
  const double df = 0.5;
  double a_prev = amp(df), a_cur = amp(2 * df);
  for (double f = 3 * df; f < 60.0 && peaks.size() < 2; f += df) {
    const double a_next = amp(f);
    if (a_cur > a_prev && a_cur > a_next) {  // golden-section refinement of the peak in [f - 2 df, f]
      double lo = f - 2 * df, hi = f;
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int i = 0; i < 40; ++i) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        (amp(x1) > amp(x2) ? hi : lo) = (amp(x1) > amp(x2) ? x2 : x1);
      }
      peaks.push_back(0.5 * (lo + hi));
    }
    a_prev = a_cur;
    a_cur = a_next;
  }
  ASSERT_EQ(peaks.size(), 2u);
  for (int i = 0; i < 2; ++i) EXPECT_LT(std::abs(peaks[i] / fn[i] - 1.0), 5e-3) << i;
  // Independent sanity: fixed-free bar c / (4 L), c = sqrt(0.05 / 1e-8) mm/s, within 1 % on 20 elements.
  EXPECT_NEAR(fn[0] / (std::sqrt(0.05 / 1e-8) / 320.0), 1.0, 1e-2);
}

}  // namespace
}  // namespace cushion::solver::test
