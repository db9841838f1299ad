// Requirement: node-to-rigid-surface contact (penalty + augmented Lagrangian, Coulomb friction)
// has an exact tangent, reproduces homogeneous states exactly, converges quadratically, shows
// stick then slip at mu N, and rejects bad input with a clear message.
// Checks:
//  - tangent = central difference of the contact residual (step 1e-6 mm) to 1e-6 relative, for a
//    sphere and the SIT-BAR (curvature terms), frictionless and with friction (stick and slip);
//  - patch test: a frictionless flat platen pressing a graded quarter block (symmetry planes,
//    hyperfoam) gives the homogeneous solution: equal top displacement (1e-10 mm), uniform stress
//    (1e-8 relative) and the force of the prescribed-displacement solution (1e-8 relative);
//    penetration within the stated tolerance after augmentation;
//  - Newton with contact active: residual order >= 1.8 in the final iterations;
//  - friction: platen sliding on a pressed block: stick (|Ft| < mu N, all nodes stuck) at small
//    slide, then every node at |f_T| = mu f_N (1e-8) and the total within 2 % below mu N;
//  - bad input: contact set not on the surface, indenter starting inside, penalty too low.
#include <gtest/gtest.h>

#include <cmath>

#include "io/input_error.hpp"
#include "tests/solver/solver_fixtures.hpp"
#include "tests/solver/test_contact_support.hpp"

namespace cushion::solver {
namespace {

mesh::BlockSpec block(double L, int n, double grading = 1.0) {
  mesh::BlockSpec spec;
  spec.low = Vec3::Zero();
  spec.high = Vec3::Constant(L);
  spec.n = {n, n, n};
  if (grading != 1.0)
    for (int i = 0; i < 2; ++i) spec.grading[i] = {mesh::AxisGrading::Kind::geometric, grading, 0.0};
  return spec;
}

std::vector<int> top_nodes(const mesh::Mesh& m, double z) {
  std::vector<int> out;
  for (int a = 0; a < static_cast<int>(m.num_nodes()); ++a)
    if (std::abs(m.nodes[a].z() - z) < 1e-9) out.push_back(a);
  return out;
}

/// Central-difference check of the contact tangent on the free DOFs of a small model.
void check_tangent(ContactSet& set, const test::ContactModel& m, const Eigen::VectorXd& u) {
  const DofMap& dofs = m.assembler->dofs();
  SparseMatrix K = m.assembler->make_matrix();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(u.size());
  set.evaluate(u, dofs, r, &K);
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  const double h = 1e-6;
  double scale = Kd.cwiseAbs().maxCoeff(), worst = 0.0;
  ASSERT_GT(scale, 0.0);
  for (int eq = 0; eq < static_cast<int>(dofs.num_free()); ++eq) {
    const int d = dofs.free_dofs()[eq];
    Eigen::VectorXd up = u, um = u, rp = Eigen::VectorXd::Zero(u.size()), rm = rp;
    up(d) += h, um(d) -= h;
    set.evaluate(up, dofs, rp, nullptr);
    set.evaluate(um, dofs, rm, nullptr);
    const Eigen::VectorXd col = dofs.gather_free((rp - rm) / (2 * h));
    worst = std::max(worst, (col - Kd.col(eq)).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, 1e-6 * scale) << "tangent scale " << scale;
  set.evaluate(u, dofs, r, nullptr);  // restore the trial state of u
}

TEST(ContactSet, TangentMatchesFiniteDifferences) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(block(10, 2), test::neo_hookean(), fix_bottom);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.u.size());
  for (int a = 0; a < static_cast<int>(m.mesh.num_nodes()); ++a)
    if (m.mesh.nodes[a].z() > 1e-9) u.segment<3>(3 * a) = 0.2 * Vec3(U(rng), U(rng), U(rng));

  ContactParameters p;
  p.penalty = 0.5;
  {  // sphere, frictionless: curvature term t_N H
    ContactSet set("sphere", m.mesh, top_nodes(m.mesh, 10), make_sphere(Vec3(5, 5, 19), 10), p);
    check_tangent(set, m, u);
    EXPECT_GT(set.totals().active, 0);
  }
  {  // SIT-BAR scaled down so that its lobes and blend zone touch the 10 mm block
    SitBarShape shape;
    shape.lowest_z = 9.0, shape.it_spacing = 4.0, shape.a = 5.0, shape.b = 6.0, shape.c = 3.0, shape.blend = 2.0;
    shape.plate_x = 30, shape.plate_y = 30, shape.plate_edge = 1, shape.centre_x = 5, shape.centre_y = 5;
    ContactSet set("sitbar", m.mesh, top_nodes(m.mesh, 10), make_sitbar(shape), p);
    check_tangent(set, m, u);
    EXPECT_GE(set.totals().active, 3);
  }
  {  // friction: commit a contact state, then move the indenter sideways: stick and slip nodes
    p.friction = 0.3;
    p.tangential_penalty = 0.5;
    ContactSet set("friction", m.mesh, top_nodes(m.mesh, 10), make_sphere(Vec3(5, 5, 19), 10), p);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(u.size());
    set.evaluate(u, m.assembler->dofs(), r, nullptr);
    set.commit();
    set.set_position(Vec3(0.6, 0.25, -0.05));
    check_tangent(set, m, u);
    const ContactTotals t = set.totals();
    EXPECT_GT(t.slipping, 0);
    EXPECT_LT(t.slipping, t.active);
  }
}

TEST(ContactSet, PatchTestFlatPlaten) {
  const double L = 10.0, d = 2.0;
  auto fix = [](const Vec3& X, int i) { return (i == 0 && X.x() < 1e-9) || (i == 1 && X.y() < 1e-9) || (i == 2 && X.z() < 1e-9); };
  test::ContactModel m = test::make_model(block(L, 3, 2.5), test::hyperfoam(), fix);
  ContactParameters p;
  p.penalty = 0.05;  // soft on purpose: augmentation has to do the work
  p.tolerance = 1e-6;
  p.max_augmentations = 30;
  ContactSet set("platen", m.mesh, top_nodes(m.mesh, L), make_plane(Vec3(0, 0, L), Vec3(0, 0, -1)), p);
  NewtonResult last;
  for (int n = 1; n <= 4; ++n) {
    const AugmentedResult r = test::contact_increment(m, set, Vec3(0, 0, -0.25 * n * d), m.u, 1e-10, &last);
    ASSERT_TRUE(r.converged()) << r.newton.message << r.message;
    if (n == 4) {
      EXPECT_GT(r.solves, 1);  // augmentations were needed
    }
  }
  const ContactTotals t = set.totals();
  EXPECT_LE(t.max_penetration, p.tolerance);
  EXPECT_EQ(t.active, static_cast<int>(set.nodes().size()));

  // Homogeneous state: equal top displacement and lateral u proportional to X.
  const std::vector<int> top = set.nodes();
  const double w = m.u(3 * top[0] + 2);
  EXPECT_NEAR(w, -d, 2e-6);
  for (int a : top) EXPECT_NEAR(m.u(3 * a + 2), w, 1e-10);
  const double lateral = m.u(3 * top.back()) / m.mesh.nodes[top.back()].x();
  for (int a = 0; a < static_cast<int>(m.mesh.num_nodes()); ++a)
    EXPECT_NEAR(m.u(3 * a), lateral * m.mesh.nodes[a].x(), 1e-10);

  // Same block with the top displacement prescribed to w (lateral free): force and stress.
  auto fix_top = [&](const Vec3& X, int i) { return fix(X, i) || (i == 2 && std::abs(X.z() - L) < 1e-9); };
  test::ContactModel ref = test::make_model(block(L, 3, 2.5), test::hyperfoam(), fix_top);
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(ref.u.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(ref.assembler->dofs().num_free());
  NewtonOptions options;
  options.residual_tolerance = options.correction_tolerance = 1e-12;
  for (int n = 1; n <= 4; ++n) {
    Eigen::VectorXd u_target = ref.u;
    for (int a : top) u_target(3 * a + 2) = 0.25 * n * w;
    EquilibriumProblem problem(*ref.assembler, ref.state, ref.u, u_target, f_ext, 0.0);
    ASSERT_TRUE(solve_newton(problem, *ref.linear, x, options).converged());
    ref.state.commit();
    ref.u = problem.u();
  }
  Eigen::VectorXd f_int;
  std::vector<PointOutput> points_ref, points;
  ref.assembler->assemble(ref.u, ref.u, 0.0, ref.state, f_int, nullptr, &points_ref);
  double force_ref = 0.0;
  for (int a : top) force_ref += f_int(3 * a + 2);  // reaction on the foam (negative: compression)
  EXPECT_NEAR(t.force.z(), force_ref, 1e-8 * std::abs(force_ref));
  m.assembler->assemble(m.u, m.u, 0.0, m.state, f_int, nullptr, &points);
  for (std::size_t q = 0; q < points.size(); ++q)
    EXPECT_LE((points[q].sigma - points_ref[0].sigma).cwiseAbs().maxCoeff(),
              1e-8 * points_ref[0].sigma.cwiseAbs().maxCoeff());
  // Newton with contact active: at least quadratic in the final iterations.
  const auto& h = last.history;
  ASSERT_GE(h.size(), 3u);
  bool quadratic = false;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {
    const double e0 = h[k - 1].residual_max / h[k].force_scale, e1 = h[k].residual_max / h[k].force_scale,
                 e2 = h[k + 1].residual_max / h[k].force_scale;
    if (e1 < 0.2 && e2 > 1e-13 && e1 < e0) quadratic = quadratic || std::log(e2 / e1) / std::log(e1 / e0) >= 1.8;
  }
  EXPECT_TRUE(quadratic);
}

TEST(ContactSet, FrictionStickThenSlip) {
  const double L = 10.0, mu = 0.3;
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(block(L, 3), test::neo_hookean(), fix_bottom, LinearSolverKind::lu);
  ContactParameters p;
  p.penalty = 1.0;
  p.tangential_penalty = 0.02;  // stick up to a relative slip of mu t_N / eps_T ~ 0.2 mm
  p.friction = mu;
  p.tolerance = 1e-3;
  ContactSet set("platen", m.mesh, top_nodes(m.mesh, L), make_plane(Vec3(0, 0, L), Vec3(0, 0, -1)), p);
  for (int n = 1; n <= 2; ++n)
    ASSERT_TRUE(test::contact_increment(m, set, Vec3(0, 0, -0.5 * n), m.u).converged());
  bool saw_stick = false, saw_slip = false;
  for (int n = 1; n <= 30; ++n) {
    const double s = 0.1 * n;
    NewtonResult first;
    const AugmentedResult r = test::contact_increment(m, set, Vec3(s, 0, -1.0), m.u, 1e-10, &first);
    ASSERT_TRUE(r.converged()) << "slide " << s << ": " << r.newton.message << r.message;
    const ContactTotals t = set.totals();
    const double N = -t.force.z(), Ft = t.force.x();
    ASSERT_GT(N, 0.0);
    if (t.slipping == 0) {
      saw_stick = true;
      EXPECT_LT(Ft, mu * N);
      EXPECT_GT(Ft, 0.0);
    }
    if (t.slipping == t.active) {  // gross slip: every node at the Coulomb limit
      saw_slip = true;
      FrameData frame;
      set.add_frame_fields(frame);
      const NamedField& f = frame.point_fields.back();  // "platen_force_N"
      ASSERT_EQ(f.name, "platen_force_N");
      for (int a : set.nodes())
        EXPECT_NEAR(std::hypot(f.values[3 * a], f.values[3 * a + 1]), -mu * f.values[3 * a + 2], 1e-8 * N);
      EXPECT_LE(Ft, mu * N * (1 + 1e-12));
      EXPECT_GE(Ft, 0.98 * mu * N);  // slip directions close to the sliding direction
      EXPECT_NEAR(t.force.y(), 0.0, 1e-8 * N);
    }
  }
  EXPECT_TRUE(saw_stick);
  EXPECT_TRUE(saw_slip);
}

TEST(ContactSet, RejectsNodesOffTheSurface) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(block(10, 2), test::neo_hookean(), fix_bottom);
  std::vector<int> nodes = top_nodes(m.mesh, 10);
  nodes.push_back(13);  // the centre node of the 3x3x3 node grid
  ASSERT_NEAR((m.mesh.nodes[13] - Vec3(5, 5, 5)).norm(), 0.0, 1e-12);
  try {
    ContactSet set("bad", m.mesh, nodes, make_plane(Vec3(0, 0, 10), Vec3(0, 0, -1)), {});
    FAIL() << "an interior node was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not on the outer surface"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node 14"), std::string::npos) << e.what();
  }
}

TEST(ContactSet, RejectsIndenterStartingInside) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(block(10, 2), test::neo_hookean(), fix_bottom);
  ContactSet set("ball", m.mesh, top_nodes(m.mesh, 10), make_sphere(Vec3(5, 5, 14), 5), {});
  try {
    check_no_initial_penetration(set, m.u, "at t = 0 s");
    FAIL() << "an indenter 1 mm inside the block was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("starts inside"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("by 1 mm"), std::string::npos) << e.what();
  }
  ContactSet clear("ball", m.mesh, top_nodes(m.mesh, 10), make_sphere(Vec3(5, 5, 15.05), 5), {});
  EXPECT_NO_THROW(check_no_initial_penetration(clear, m.u, "at t = 0 s"));
}

TEST(ContactSet, PenaltyTooLowIsReported) {
  auto fix_bottom = [](const Vec3& X, int) { return X.z() < 1e-9; };
  test::ContactModel m = test::make_model(block(10, 2), test::neo_hookean(), fix_bottom);
  ContactParameters p;
  p.penalty = 1e-5;
  p.tolerance = 1e-3;
  p.max_augmentations = 3;
  ContactSet set("platen", m.mesh, top_nodes(m.mesh, 10), make_plane(Vec3(0, 0, 10), Vec3(0, 0, -1)), p);
  const Eigen::VectorXd u0 = m.u;
  const AugmentedResult r = test::contact_increment(m, set, Vec3(0, 0, -1), m.u);
  EXPECT_TRUE(r.newton.converged());
  EXPECT_TRUE(r.penetration_failed);
  EXPECT_EQ(r.solves, 4);
  EXPECT_NE(r.message.find("penalty"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("too low"), std::string::npos) << r.message;
  EXPECT_EQ(m.u, u0);  // nothing committed
}

}  // namespace
}  // namespace cushion::solver
