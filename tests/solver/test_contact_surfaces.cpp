// Requirement: every rigid indenter surface returns a signed gap whose gradient and Hessian are the
// exact derivatives (the contact tangent relies on them), and the gap is the true signed distance
// where the shape has one.
// Checks: central differences of g (step 1e-5 mm) match grad g to 1e-7 and of grad g match the
// Hessian to 1e-5 (relative to the largest entry + 1e-6) at random points for plane, sphere,
// cylinder, flat punch (face, fillet, side), SIT-BAR (lobes, blend, plate) and an STL box; analytic
// distances to 1e-10 mm; the ellipsoid lobes' nearest points lie on the ellipsoid (1e-12); the STL
// box gives the box's signed distance inside and outside to 1e-12 mm, and the lobes' Hessian is symmetric bit for bit;
// an open STL is rejected.
#include <gtest/gtest.h>

#include <random>

#include "io/input_error.hpp"
#include "solver/contact/rigid_surface.hpp"

namespace cushion::solver {
namespace {

void check_derivatives(const RigidSurface& s, const Vec3& x) {
  SCOPED_TRACE(s.describe() + " at (" + std::to_string(x.x()) + ", " + std::to_string(x.y()) + ", " +
               std::to_string(x.z()) + ")");
  const GapPoint p = s.gap(x);
  const double h = 1e-5;
  Vec3 grad_fd;
  Mat3 hess_fd;
  for (int j = 0; j < 3; ++j) {
    Vec3 e = Vec3::Zero();
    e(j) = h;
    const GapPoint pp = s.gap(x + e), pm = s.gap(x - e);
    grad_fd(j) = (pp.g - pm.g) / (2 * h);
    hess_fd.col(j) = (pp.grad - pm.grad) / (2 * h);
  }
  EXPECT_LE((grad_fd - p.grad).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LE((hess_fd - p.hess).cwiseAbs().maxCoeff(), 1e-5 * (p.hess.cwiseAbs().maxCoeff() + 1e-6));
  EXPECT_LE((p.hess - p.hess.transpose()).cwiseAbs().maxCoeff(), 1e-12 * (p.hess.cwiseAbs().maxCoeff() + 1));
}

mesh::TriangleSurface box_stl(const Vec3& lo, const Vec3& hi) {
  mesh::TriangleSurface s;
  for (int k = 0; k < 8; ++k)
    s.vertices.push_back(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
  // Faces as quads (outward, counter-clockwise seen from outside), split into two triangles.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s.triangles.push_back({q[0], q[1], q[2]});
    s.triangles.push_back({q[0], q[2], q[3]});
  }
  return s;
}

double box_distance(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  const Vec3 q = (x - c).cwiseAbs() - h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TEST(ContactSurfaces, AnalyticDistances) {
  const auto plane = make_plane(Vec3(0, 0, 80), Vec3(0, 0, -2));
  EXPECT_NEAR(plane->gap(Vec3(3, 4, 70)).g, 10.0, 1e-12);
  const auto sphere = make_sphere(Vec3(1, 2, 3), 5.0);
  EXPECT_NEAR(sphere->gap(Vec3(1, 2, 10)).g, 2.0, 1e-12);
  EXPECT_NEAR(sphere->gap(Vec3(1, 2, 7)).g, -1.0, 1e-12);
  const auto cyl = make_cylinder(Vec3(0, 0, 10), Vec3(0, 1, 0), 4.0);
  EXPECT_NEAR(cyl->gap(Vec3(3, 77, 6)).g, 1.0, 1e-12);
  const auto punch = make_flat_punch(0, 0, 80, 100, 1);
  EXPECT_NEAR(punch->gap(Vec3(50, 0, 70)).g, 10.0, 1e-12);           // below the face
  EXPECT_NEAR(punch->gap(Vec3(50, 0, 80.5)).g, -0.5, 1e-12);         // penetrating the face
  EXPECT_NEAR(punch->gap(Vec3(105, 0, 120)).g, 5.0, 1e-12);          // beside the wall
  const double r = std::hypot(3.0, 4.0);                             // from the fillet centre (99, 81)
  EXPECT_NEAR(punch->gap(Vec3(99 + 3, 0, 81 - 4)).g, r - 1.0, 1e-12);
}

TEST(ContactSurfaces, Derivatives) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  auto jitter = [&](const Vec3& x, double s) { return Vec3(x + s * Vec3(U(rng), U(rng), U(rng))); };
  const auto plane = make_plane(Vec3(0, 0, 80), Vec3(0.2, 0.1, 1));
  const auto sphere = make_sphere(Vec3(0, 0, 130), 50);
  const auto cyl = make_cylinder(Vec3(0, 0, 100), Vec3(1, 0.3, 0), 20);
  const auto punch = make_flat_punch(0, 0, 80, 100, 2);
  for (int k = 0; k < 10; ++k) {
    check_derivatives(*plane, jitter(Vec3(10, 10, 70), 20));
    check_derivatives(*sphere, jitter(Vec3(10, 0, 75), 10));
    check_derivatives(*cyl, jitter(Vec3(0, 10, 70), 10));
    check_derivatives(*punch, jitter(Vec3(50, 20, 78), 1));    // face
    check_derivatives(*punch, jitter(Vec3(99.8, 0, 80.5), 0.5));  // fillet
    check_derivatives(*punch, jitter(Vec3(70, 72, 85), 1));    // side wall (rho ~ 101)
  }
  SitBarShape shape;
  const auto sitbar = make_sitbar(shape);
  for (int k = 0; k < 20; ++k) {
    check_derivatives(*sitbar, jitter(Vec3(60, 0, 78), 20));    // under a lobe
    check_derivatives(*sitbar, jitter(Vec3(0, 10, 95), 5));     // between the lobes (blend)
    check_derivatives(*sitbar, jitter(Vec3(150, 80, 135), 5));  // lobe-plate junction
    check_derivatives(*sitbar, jitter(Vec3(175, 120, 137), 3)); // plate edge
  }
  const Vec3 lo(-10, -20, 80), hi(30, 20, 120);
  const auto stl = make_stl_surface(box_stl(lo, hi), "box.stl");
  for (int k = 0; k < 20; ++k) {
    check_derivatives(*stl, jitter(Vec3(0, 0, 70), 5));     // face region
    check_derivatives(*stl, jitter(Vec3(35, 0, 75), 3));    // edge region
    check_derivatives(*stl, jitter(Vec3(35, 25, 75), 3));   // vertex region
  }
}

TEST(ContactSurfaces, SitBarLobesAreEllipsoids) {
  SitBarShape shape;
  shape.blend = 1.0;
  const auto sitbar = make_sitbar(shape);
  const Vec3 centre(60, 0, shape.lowest_z + shape.c), e(shape.a, shape.b, shape.c);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int k = 0; k < 50; ++k) {
    const Vec3 x = Vec3(90, 20, 70) + Vec3(30 * U(rng), 40 * U(rng), 8 * U(rng));
    const GapPoint p = sitbar->gap(x);
    EXPECT_NEAR(p.grad.norm(), 1.0, 1e-12);
    const Vec3 foot = x - p.g * p.grad - centre;  // nearest point on the lobe
    EXPECT_NEAR(foot.cwiseQuotient(e).squaredNorm(), 1.0, 1e-12);
    EXPECT_TRUE(p.hess == p.hess.transpose()) << "the Hessian symmetrised in place reads its own new entries";
  }
  EXPECT_NEAR(sitbar->gap(Vec3(60, 0, 70)).g, 10.0, 1e-10);   // straight below a lobe's lowest point
  EXPECT_NEAR(sitbar->gap(Vec3(-60, 0, 81)).g, -1.0, 1e-10);
}

TEST(ContactSurfaces, StlBoxIsSignedDistance) {
  const Vec3 lo(-10, -20, 80), hi(30, 20, 120);
  const auto stl = make_stl_surface(box_stl(lo, hi), "box.stl");
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int k = 0; k < 200; ++k) {
    const Vec3 x = Vec3(10, 0, 100) + 35 * Vec3(U(rng), U(rng), U(rng));
    EXPECT_NEAR(stl->gap(x).g, box_distance(x, lo, hi), 1e-12);
  }
}

TEST(ContactSurfaces, OpenStlRejected) {
  mesh::TriangleSurface open = box_stl(Vec3::Zero(), Vec3::Ones());
  open.triangles.pop_back();
  try {
    make_stl_surface(open, "indenter.stl");
    FAIL() << "an open STL was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("indenter.stl"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cushion::solver
