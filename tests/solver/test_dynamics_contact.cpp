// Contact frozen at the base state (solver/dynamics/contact_linearisation.hpp): a 10 mm cube on
// rollers pressed 2 mm by a flat rigid plane (penalty 1 MPa/mm, augmented to 1e-4 mm), then swept
// with the indenter as an appended DOF. With a massless foam the closed-node springs (eps_k
// proportional to the tributary areas, i.e. to the consistent nodal loads of the uniform stress) act
// in series with the cube: 1/K_contact = 1/K_prescribed + 1/(penalty x area), exactly (1e-8), so the
// dynamic modulus equals the prescribed-displacement sweep's up to the analytic penalty effect
// K_p / (K_p + K_pen) (~0.5 % here). The indenter reaction equals the summed spring forces (1e-10);
// a free indenter of mass m gives the transmissibility K / (K - w^2 m); tangentially a frictionless
// indenter slides freely (zero reaction), a frictional one sticks through eps_T P.
#include <gtest/gtest.h>

#include <cstdio>

#include "solver/dynamics/contact_linearisation.hpp"
#include "solver/dynamics/sweep.hpp"
#include "solver_fixtures.hpp"
#include "test_contact_support.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

constexpr double penalty = 1.0;  // [MPa/mm]
constexpr double area = 100.0;   // top face [mm^2]

/// The preloaded cube, its contact set and its linearisation (foam density 1e-20 t/mm^3: massless).
struct ContactCube {
  ContactModel m;
  std::vector<Section> sections;
  std::unique_ptr<ContactSet> set;
  std::unique_ptr<LinearisedSystem> sys;
  int w = 0;  ///< appended indenter DOF

  static mesh::BlockSpec block() {
    mesh::BlockSpec spec;
    spec.low = Vec3::Zero();
    spec.high = Vec3(10, 10, 10);
    spec.n = {2, 2, 2};
    return spec;
  }
  // Built in place (the assembler refers to m.mesh): rollers x = 0 in x, y = 0 in y, z = 0 in z.
  explicit ContactCube(double friction)
      : m(make_model(block(), visco_hyperfoam(), [](const Vec3& X, int i) { return X(i) == 0.0; },
                     friction > 0.0 ? LinearSolverKind::lu : LinearSolverKind::cholesky_or_lu)) {
    ContactParameters p;
    p.penalty = penalty;
    p.tolerance = 1e-4;
    p.friction = friction;
    p.max_augmentations = 40;
    set = std::make_unique<ContactSet>("plate", m.mesh, m.mesh.node_sets.at("zmax"),
                                       make_plane(Vec3(0, 0, 10), Vec3(0, 0, -1)), p);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.u.size());
    for (int i = 1; i <= 8; ++i)
      if (!contact_increment(m, *set, Vec3(0, 0, -0.25 * i), zero).converged())
        throw std::runtime_error("contact preload did not converge");
    sections = m.assembler->sections();
    sections[0].density = 1e-20;
    sys = std::make_unique<LinearisedSystem>(m.mesh, sections,
                                             base_point_states(*m.assembler, m.state, m.u, BaseStress::relaxed), m.u);
    w = static_cast<int>(3 * m.mesh.num_nodes());
  }
  std::vector<int> rollers(bool with_base_z) const {
    std::vector<int> d = set_dofs(m.mesh, "xmin", 0);
    for (int k : set_dofs(m.mesh, "ymin", 1)) d.push_back(k);
    if (with_base_z)
      for (int k : set_dofs(m.mesh, "zmin", 2)) d.push_back(k);
    return d;
  }
  HarmonicModel contact_model(const ContactLinearisation& lin) const {
    HarmonicModel model;
    model.system = sys.get();
    model.extra_dofs = 1;
    model.extra_stiffness.resize(w + 1, w + 1);
    model.extra_stiffness.setFromTriplets(lin.stiffness.begin(), lin.stiffness.end());
    return model;
  }
  /// Platen nodes prescribed (no contact): K_p = R_top / U [N/mm].
  cplx prescribed_stiffness(double f) const {
    HarmonicModel model;
    model.system = sys.get();
    SteadyStateSolver s(model, {}, {set_dofs(m.mesh, "zmax", 2), rollers(true), {}},
                        {{"top", set_dofs(m.mesh, "zmax", 2)}, {"base", set_dofs(m.mesh, "zmin", 2)}});
    return s.solve(f, 0.01).reaction[0] / 0.01;
  }
};

const Vec3 ez = Vec3::UnitZ();

TEST(DynamicsContact, IndenterSweepEqualsPrescribedSweepInSeriesWithThePenalty) {
  ContactCube c(0.0);
  const ContactLinearisation lin = linearise_contact(c.m.mesh, *c.set, c.m.u, c.w, ez);
  ASSERT_EQ(lin.closed.size(), 9u);
  EXPECT_NEAR(lin.closed_area, area, 1e-9);
  const double K_pen = penalty * area;
  SteadyStateSolver driven(c.contact_model(lin), {}, {{c.w}, c.rollers(true), {}},
                           {{"indenter", {c.w}}, {"base", set_dofs(c.m.mesh, "zmin", 2)}});
  std::vector<int> held = c.rollers(false);
  held.push_back(c.w);
  SteadyStateSolver shaken(c.contact_model(lin), {}, {set_dofs(c.m.mesh, "zmin", 2), held, {}},
                           {{"indenter", {c.w}}, {"base", set_dofs(c.m.mesh, "zmin", 2)}});
  for (double f : {1.0, 5.0, 20.0}) {
    const cplx Kp = c.prescribed_stiffness(f);
    const cplx K_series = Kp * K_pen / (Kp + K_pen);
    // Indenter shaken, base held.
    const FrequencyResponse rd = driven.solve(f, 0.01);
    const cplx Kd = make_row(rd, Measure::indenter_driven, {area, 10.0}).stiffness;
    EXPECT_LT(std::abs(Kd / K_series - 1.0), 1e-8) << f;
    // Base shaken, indenter held: same stiffness (reciprocity, massless foam).
    const FrequencyResponse rs = shaken.solve(f, 0.01);
    const cplx Ks = make_row(rs, Measure::indenter_held, {area, 10.0}).stiffness;
    EXPECT_LT(std::abs(Ks / K_series - 1.0), 1e-8) << f;
    // The penalty effect on the modulus, against the analytic estimate K_p / (K_p + K_pen).
    const double effect = std::abs(Kd / Kp - 1.0), estimate = std::abs(Kp / (Kp + K_pen));
    EXPECT_NEAR(effect, estimate, 1e-8);
    EXPECT_LT(effect, 1e-2);
    // Indenter reaction = summed spring forces on the foam (z component).
    for (const FrequencyResponse* r : {&rd, &rs}) {
      const cplx F = contact_spring_force(*c.set, lin, r->u, r->u(c.w), ez)(2);
      EXPECT_LT(std::abs(r->reaction[0] - F), 1e-10 * std::abs(F)) << f;
    }
    std::printf("  %4.1f Hz: E_prescribed = %.6g kPa, E_contact = %.6g kPa, penalty effect %.3e (analytic %.3e)\n",
                f, 1e3 * std::abs(Kp) * 10 / area, 1e3 * std::abs(Kd) * 10 / area, effect, estimate);
  }
}

TEST(DynamicsContact, FreeIndenterWithMassGivesTheTransmissibility) {
  ContactCube c(0.0);
  const ContactLinearisation lin = linearise_contact(c.m.mesh, *c.set, c.m.u, c.w, ez);
  HarmonicModel model = c.contact_model(lin);
  const double mass = 1e-3;  // 1 kg [t]
  model.lumped_mass = {{c.w, mass}};
  SteadyStateSolver s(model, {}, {set_dofs(c.m.mesh, "zmin", 2), c.rollers(false), {}},
                      {{"indenter", {c.w}}, {"base", set_dofs(c.m.mesh, "zmin", 2)}});
  for (double f : {1.0, 3.5, 10.0}) {
    const double w2 = std::pow(2 * M_PI * f, 2);
    const cplx Kp = c.prescribed_stiffness(f), K = Kp * penalty * area / (Kp + penalty * area);
    const FrequencyResponse r = s.solve(f, 0.01);
    const cplx T = r.displacement[0] / r.amplitude, T_exact = K / (K - w2 * mass);
    EXPECT_LT(std::abs(T / T_exact - 1.0), 1e-8) << f;
    // Driving-point stiffness at the base: K (1 - T) (force through the foam per base amplitude).
    const cplx Kb = make_row(r, Measure::indenter_free, {area, 10.0}).stiffness;
    EXPECT_LT(std::abs(Kb / (K * (1.0 - T_exact)) - 1.0), 1e-7) << f;
    std::printf("  %4.1f Hz: |T| = %.6f (exact %.6f)\n", f, std::abs(T), std::abs(T_exact));
  }
}

TEST(DynamicsContact, TangentiallyFrictionlessSlidesFrictionalSticks) {
  const Vec3 ex = Vec3::UnitX();
  for (double mu : {0.0, 0.3}) {
    ContactCube c(mu);
    const ContactLinearisation lin = linearise_contact(c.m.mesh, *c.set, c.m.u, c.w, ex);
    ASSERT_EQ(lin.closed.size(), 9u) << mu;
    const double eps_T = mu > 0.0 ? c.set->parameters().tangential_penalty : 0.0;
    for (std::size_t i = 0; i < lin.closed.size(); ++i) {  // flat plane: eps n n^T + eps_T (I - n n^T)
      const double A = c.set->areas()[lin.closed[i]];
      const Mat3 expected = Vec3(eps_T * A, eps_T * A, penalty * A).asDiagonal();
      EXPECT_LT((lin.node_stiffness[i] - expected).norm(), 1e-12 * penalty * A) << mu;
    }
    auto held = c.rollers(true);
    SteadyStateSolver s(c.contact_model(lin), {}, {{c.w}, held, {}},
                        {{"indenter", {c.w}}, {"base", set_dofs(c.m.mesh, "zmin", 0)}});
    const FrequencyResponse r = s.solve(5.0, 0.01);
    const cplx F = contact_spring_force(*c.set, lin, r.u, r.u(c.w), ex)(0);
    if (mu == 0.0) {
      EXPECT_EQ(std::abs(r.reaction[0]), 0.0);  // free sliding: no tangential coupling at all
      EXPECT_EQ(r.u.head(c.w).cwiseAbs().maxCoeff(), 0.0);
    } else {
      EXPECT_LT(std::abs(r.reaction[0] - F), 1e-10 * std::abs(F));
      EXPECT_GT(r.reaction[0].real(), 0.0);  // sticking springs drag the top along
      EXPECT_LT(std::abs(r.reaction[0]) / 0.01, eps_T * area);  // in series with the foam's shear
    }
  }
}

}  // namespace
}  // namespace cushion::solver::test
