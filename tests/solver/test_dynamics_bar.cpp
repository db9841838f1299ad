// Steady-state dynamics of a laterally confined hex8 column (1D bar) and of a single DOF, against
// closed-form transfer functions: the discrete chain (exact for the mesh) and the continuum wave
// solution with a complex modulus (Kelvin-Voigt via Rayleigh beta, Maxwell via Prony terms).
#include <gtest/gtest.h>

#include "material/neo_hookean.hpp"
#include "material/viscoelastic.hpp"
#include "solver/dynamics/sweep.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

constexpr double mu = 0.02, lambda = 0.01;  // [MPa]: confined modulus lambda + 2 mu = 0.05 MPa
constexpr double Mc = lambda + 2 * mu;

struct Bar {
  double w = 10.0, L = 80.0, rho = 1e-8;  // [mm, mm, t/mm^3]: first fixed-fixed mode ~14 Hz
  int n = 40;
  mesh::Mesh mesh;
  std::shared_ptr<const material::Material> mat;
  std::unique_ptr<Assembler> A;
  std::unique_ptr<LinearisedSystem> sys;

  Bar(std::shared_ptr<const material::Material> m, int nz, double density) : rho(density), n(nz), mat(std::move(m)) {
    mesh = column(w, L, n);
    std::vector<Section> sections{{"foam", {}, mat, Formulation::full, rho}};
    for (int e = 0; e < n; ++e) sections[0].elements.push_back(e);
    A = std::make_unique<Assembler>(mesh, sections, DofMap(mesh.num_nodes(), {}), AssemblyOptions{1});
    StateStore st = A->make_state_store();
    const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    sys = std::make_unique<LinearisedSystem>(mesh, sections, base_point_states(*A, st, u, BaseStress::relaxed), u,
                                             AssemblyOptions{1});
  }
  /// Base (zmin) driven in z, top (zmax) held in z, lateral DOFs held; groups {top, base}.
  SteadyStateSolver solver(Damping d, bool top_driven = false) const {
    Excitation x;
    x.driven = set_dofs(mesh, top_driven ? "zmax" : "zmin", 2);
    x.held = lateral_dofs(mesh);
    for (int dof : set_dofs(mesh, top_driven ? "zmin" : "zmax", 2)) x.held.push_back(dof);
    HarmonicModel model;
    model.system = sys.get();
    return SteadyStateSolver(model, d, x, {{"top", set_dofs(mesh, "zmax", 2)}, {"base", set_dofs(mesh, "zmin", 2)}});
  }
};

/// Discrete chain with consistent mass: reactions at the top (held) and base (driven, amplitude U).
/// E: complex modulus, rho_eff = rho (1 - i alpha / w) carries the mass-proportional damping.
std::pair<cplx, cplx> chain_reactions(cplx E, cplx rho_eff, double A, double h, int n, double w, cplx U) {
  const cplx q = w * w * rho_eff * h * h / E;
  const cplx theta = std::acos((6.0 - 2.0 * q) / (6.0 + q));
  auto u = [&](int j) { return U * std::sin(double(n - j) * theta) / std::sin(double(n) * theta); };
  const cplx k_off = -E * A / h - w * w * rho_eff * A * h / 6.0, k_diag = E * A / h - w * w * rho_eff * A * h / 3.0;
  return {k_off * u(n - 1), k_diag * U + k_off * u(1)};
}

/// Continuum bar: u = U sin(k (L - z)) / sin(k L); reactions at top and base.
std::pair<cplx, cplx> wave_reactions(cplx E, cplx rho_eff, double A, double L, double w, cplx U) {
  const cplx k = w * std::sqrt(rho_eff / E);
  return {-E * A * k * U / std::sin(k * L), E * A * k * U * std::cos(k * L) / std::sin(k * L)};
}

TEST(DynamicsBar, KelvinVoigtRayleighBetaMatchesChainAndWaveSolution) {
  Bar bar(std::make_shared<material::NeoHookean>(mu, lambda), 80, 1e-8);
  const Damping d{0.0, 2e-3, 0.0};
  auto solver = bar.solver(d);
  for (double f : {1.0, 5.0, 10.0, 20.0, 30.0}) {
    const double w = 2 * M_PI * f;
    const cplx U = 0.1;
    const auto r = solver.solve(f, U);
    const cplx E = Mc * cplx(1.0, w * d.rayleigh_beta);
    const auto [top_c, base_c] = chain_reactions(E, bar.rho, bar.w * bar.w, bar.L / bar.n, bar.n, w, U);
    EXPECT_LT(std::abs(r.reaction[0] / top_c - 1.0), 1e-8) << f;  // exact for the mesh
    EXPECT_LT(std::abs(r.reaction[1] / base_c - 1.0), 1e-8) << f;
    const auto [top_w, base_w] = wave_reactions(E, bar.rho, bar.w * bar.w, bar.L, w, U);
    EXPECT_LT(amplitude_error(r.reaction[0], top_w), 5e-3) << f;  // 0.5 %
    EXPECT_LT(phase_error_deg(r.reaction[0], top_w), 0.2) << f;
    EXPECT_LT(amplitude_error(r.reaction[1], base_w), 5e-3) << f;
    EXPECT_LT(phase_error_deg(r.reaction[1], base_w), 0.2) << f;
  }
  EXPECT_EQ(solver.analyses(), 1);  // symbolic analysis reused across frequencies
}

TEST(DynamicsBar, MaxwellPronyMatchesWaveSolutionBothDirections) {
  const std::vector<material::PronyTerm> prony{{0.3, 0.01}, {0.2, 0.1}};
  auto mat = std::make_shared<material::Viscoelastic>(std::make_shared<material::NeoHookean>(mu, lambda), prony);
  Bar bar(mat, 80, 1e-8);
  for (bool top_driven : {false, true}) {
    auto solver = bar.solver({}, top_driven);
    for (double f : {1.0, 5.0, 10.0, 20.0, 30.0}) {
      const double w = 2 * M_PI * f;
      // Independent Prony factor: 1 + sum a_i i w tau_i / (1 + i w tau_i), a_i = g_i / (1 - sum g).
      cplx factor = 1.0;
      for (const auto& t : prony) factor += t.g / (1.0 - 0.5) * cplx(0, w * t.tau) / cplx(1, w * t.tau);
      const cplx E = Mc * factor;
      const auto r = solver.solve(f, 0.1);
      // By symmetry the driven end's reaction is the base formula, the held end's the top formula.
      const auto [held_w, driven_w] = wave_reactions(E, bar.rho, bar.w * bar.w, bar.L, w, 0.1);
      const cplx held = r.reaction[top_driven ? 1 : 0], driven = r.reaction[top_driven ? 0 : 1];
      EXPECT_LT(amplitude_error(held, held_w), 5e-3) << f;
      EXPECT_LT(phase_error_deg(held, held_w), 0.2) << f;
      EXPECT_LT(amplitude_error(driven, driven_w), 5e-3) << f;
      EXPECT_LT(phase_error_deg(driven, driven_w), 0.2) << f;
    }
  }
}

// Single DOF: massless element (density ~0) carrying a lumped mass m on its top; the base is shaken.
// Mass-proportional damping acts on the ABSOLUTE velocity of the mass:
//   u/U = k* / (k* - w^2 m + i w alpha m),  k* = k (1 + i w beta + i s),  R_base = k* (U - u).
TEST(DynamicsSdof, TransmissibilityWithAbsoluteMassDamping) {
  const double h = 10.0, w0 = 10.0, m = 4e-4;  // [mm, mm, t]
  const mesh::Mesh mesh = column(w0, h, 1);
  std::vector<Section> sections{{"foam", {0}, std::make_shared<material::NeoHookean>(mu, lambda), Formulation::full, 1e-20}};
  Assembler A(mesh, sections, DofMap(mesh.num_nodes(), {}), AssemblyOptions{1});
  StateStore st = A.make_state_store();
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  LinearisedSystem sys(mesh, sections, base_point_states(A, st, u0, BaseStress::relaxed), u0);
  HarmonicModel model;
  model.system = &sys;
  for (int d : set_dofs(mesh, "zmax", 2)) model.lumped_mass.emplace_back(d, m / 4);
  Excitation x{set_dofs(mesh, "zmin", 2), lateral_dofs(mesh)};
  const Damping damp{180.0, 1e-4, 0.05};
  SteadyStateSolver solver(model, damp, x, {{"top", set_dofs(mesh, "zmax", 2)}, {"base", set_dofs(mesh, "zmin", 2)}});
  const double k = Mc * w0 * w0 / h;
  for (double f : {1.0, 5.0, 20.0, 80.0}) {
    const double w = 2 * M_PI * f;
    const auto r = solver.solve(f, 1.0);
    const cplx ks = k * cplx(1.0, w * damp.rayleigh_beta + damp.structural);
    const cplx iwam(0.0, w * damp.rayleigh_alpha * m);  // i w alpha m
    const cplx T = ks / (ks - w * w * m + iwam);
    EXPECT_LT(std::abs(r.displacement[0] / T - 1.0), 1e-9) << f;
    EXPECT_LT(std::abs(r.reaction[1] / (ks * (1.0 - T)) - 1.0), 1e-9) << f;
    // The relative-velocity alternative (alpha m (u - U)) is measurably different here.
    const cplx T_rel = (ks + iwam) / (ks - w * w * m + iwam);
    EXPECT_GT(std::abs(r.displacement[0] / T_rel - 1.0), 1e-3) << f;
  }
}

TEST(DynamicsSweep, AmplitudeFromAcceleration) {
  // 0.25 m/s^2 = 250 mm/s^2; peak-to-peak reading halves it.
  const double f = 5.0, w = 2 * M_PI * f;
  EXPECT_DOUBLE_EQ(displacement_amplitude(250.0, AccelerationReading::peak, f), 250.0 / (w * w));
  EXPECT_DOUBLE_EQ(displacement_amplitude(250.0, AccelerationReading::peak_to_peak, f), 125.0 / (w * w));
  EXPECT_THROW(displacement_amplitude(250.0, AccelerationReading::peak, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace cushion::solver::test
