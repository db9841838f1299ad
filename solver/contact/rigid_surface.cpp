// Analytic rigid bodies as signed distance functions with exact gradients and Hessians.
// Hessian of a distance function to a point, line or curved surface: with u the unit direction
// from the nearest point and d the distance, H = (P - u u^T) / d for a point (P = I), a straight
// line (P = I - e e^T), and H = W (I + d W)^-1 for a smooth surface with shape operator W.
#include "solver/contact/rigid_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/input_error.hpp"

namespace cushion::solver {

namespace {

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char s[200];
  std::snprintf(s, sizeof s, f, a, b, c, d);
  return s;
}

class Plane final : public RigidSurface {
 public:
  Plane(const Vec3& p, const Vec3& n) : p_(p), n_(n.normalized()) {}
  GapPoint gap(const Vec3& x) const override { return {n_.dot(x - p_), n_, Mat3::Zero()}; }
  std::string describe() const override {
    return fmt("plane through (%g, %g, %g) mm", p_.x(), p_.y(), p_.z()) + fmt(", normal (%g, %g, %g)", n_.x(), n_.y(), n_.z());
  }

 private:
  Vec3 p_, n_;
};

class Sphere final : public RigidSurface {
 public:
  Sphere(const Vec3& c, double R) : c_(c), R_(R) {}
  GapPoint gap(const Vec3& x) const override {
    const Vec3 y = x - c_;
    const double r = std::max(y.norm(), 1e-12 * R_);
    const Vec3 u = y / r;
    return {r - R_, u, (Mat3::Identity() - u * u.transpose()) / r};
  }
  std::string describe() const override { return fmt("sphere R = %g mm at (%g, %g, %g) mm", R_, c_.x(), c_.y(), c_.z()); }

 private:
  Vec3 c_;
  double R_;
};

class Cylinder final : public RigidSurface {
 public:
  Cylinder(const Vec3& p, const Vec3& a, double R) : p_(p), a_(a.normalized()), R_(R) {}
  GapPoint gap(const Vec3& x) const override {
    const Mat3 P = Mat3::Identity() - a_ * a_.transpose();
    const Vec3 y = P * (x - p_);
    const double r = std::max(y.norm(), 1e-12 * R_);
    const Vec3 u = y / r;
    return {r - R_, u, (P - u * u.transpose()) / r};
  }
  std::string describe() const override {
    return fmt("cylinder R = %g mm through (%g, %g, %g) mm", R_, p_.x(), p_.y(), p_.z()) +
           fmt(" along (%g, %g, %g)", a_.x(), a_.y(), a_.z());
  }

 private:
  Vec3 p_, a_;
  double R_;
};

/// Vertical cylinder of radius R with a flat bottom at z = zb and the bottom edge rounded by r:
/// the exact signed distance of a rounded cylinder (semi-infinite upwards), in terms of
/// q = (rho - (R - r), zb + r - z).
class FlatPunch final : public RigidSurface {
 public:
  FlatPunch(double cx, double cy, double zb, double R, double r) : cx_(cx), cy_(cy), zb_(zb), R_(R), r_(r) {}
  GapPoint gap(const Vec3& x) const override {
    const double dx = x.x() - cx_, dy = x.y() - cy_;
    const double rho = std::hypot(dx, dy);
    const double q_rho = rho - (R_ - r_), q_z = zb_ + r_ - x.z();
    const Vec3 e_z = Vec3::UnitZ();
    const bool fillet = q_rho > 0.0 && q_z > 0.0;
    if (!fillet && (q_z >= q_rho || rho < 1e-12 * R_)) return {q_z - r_, -e_z, Mat3::Zero()};  // flat bottom
    const Vec3 e_rho(dx / rho, dy / rho, 0.0);
    Mat3 P_xy = Mat3::Zero();
    P_xy(0, 0) = P_xy(1, 1) = 1.0;
    const Mat3 d2rho = (P_xy - e_rho * e_rho.transpose()) / rho;  // Hessian of rho
    if (!fillet) return {q_rho - r_, e_rho, d2rho};                  // side wall
    // Below the fillet's centre circle: distance to that circle minus r.
    const double L = std::hypot(q_rho, q_z);
    GapPoint p;
    p.g = L - r_;
    p.grad = (q_rho / L) * e_rho - (q_z / L) * e_z;
    p.hess = (e_rho * e_rho.transpose() + e_z * e_z.transpose() - p.grad * p.grad.transpose()) / L +
             (q_rho / L) * d2rho;
    return p;
  }
  std::string describe() const override {
    return fmt("flat punch R = %g mm, edge radius %g mm, bottom z = %g mm", R_, r_, zb_) +
           fmt(" at (%g, %g) mm", cx_, cy_);
  }

 private:
  double cx_, cy_, zb_, R_, r_;
};

/// Solid ellipsoid (axis-aligned). Nearest point p on the surface from y = x - centre:
/// p_i = e_i^2 y_i / (e_i^2 + t) with t the root of sum (e_i y_i / (e_i^2 + t))^2 = 1; then
/// y - p = t D p (D = diag(1/e_i^2)), the signed distance is d = t |D p| and the normal D p / |D p|.
/// Shape operator W = P D P / |D p| (P = I - n n^T), Hessian H = W (I + d W)^-1.
GapPoint ellipsoid_gap(const Vec3& centre, const Vec3& e, const Vec3& x) {
  const Vec3 y = x - centre;
  const Vec3 e2 = e.cwiseProduct(e);
  auto F = [&](double t, double* dF) {
    double f = -1.0, df = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double s = e(i) * y(i) / (e2(i) + t);
      f += s * s;
      df += -2.0 * s * s / (e2(i) + t);
    }
    if (dF) *dF = df;
    return f;
  };
  const double e_min2 = e2.minCoeff();
  double lo = -e_min2 * (1.0 - 1e-12), hi = e.maxCoeff() * y.norm() + 1e-9;
  while (F(hi, nullptr) > 0.0) hi *= 2.0;
  double t = F(0.0, nullptr) > 0.0 ? std::min(hi, y.norm()) : 0.5 * lo;  // outside: t > 0
  for (int k = 0; k < 200; ++k) {
    double df;
    const double f = F(t, &df);
    if (f > 0.0) lo = t; else hi = t;
    double t_new = t - f / df;
    if (!(t_new > lo && t_new < hi)) t_new = 0.5 * (lo + hi);
    if (std::abs(t_new - t) <= 1e-15 * (std::abs(t) + e_min2)) { t = t_new; break; }
    t = t_new;
  }
  Vec3 p, Dp;
  for (int i = 0; i < 3; ++i) {
    p(i) = e2(i) * y(i) / (e2(i) + t);
    Dp(i) = p(i) / e2(i);
  }
  const double nDp = Dp.norm();
  GapPoint out;
  out.grad = Dp / nDp;
  out.g = t * nDp;
  const Mat3 P = Mat3::Identity() - out.grad * out.grad.transpose();
  const Mat3 W = P * Vec3(1.0 / e2(0), 1.0 / e2(1), 1.0 / e2(2)).asDiagonal() * P / nDp;
  const Mat3 hess = W * (Mat3::Identity() + out.g * W).inverse();  // symmetric but for round-off
  out.hess = 0.5 * (hess + hess.transpose());  // not from out.hess itself: its (0, 1) would read the new (1, 0)
  return out;
}

/// Rectangular plate (semi-infinite upwards) with rounded bottom edges: signed distance of a
/// rounded box with q = (|x - cx| - (hx - r), |y - cy| - (hy - r), zb + r - z).
GapPoint plate_gap(double cx, double cy, double hx, double hy, double zb, double r, const Vec3& x) {
  const Vec3 s(x.x() >= cx ? 1.0 : -1.0, x.y() >= cy ? 1.0 : -1.0, -1.0);
  const Vec3 q(std::abs(x.x() - cx) - (hx - r), std::abs(x.y() - cy) - (hy - r), zb + r - x.z());
  GapPoint out;
  const Vec3 qp = q.cwiseMax(0.0);
  const double L = qp.norm();
  if (L > 0.0) {
    out.g = L - r;
    const Vec3 u = qp / L;
    out.grad = s.cwiseProduct(u);
    Mat3 A = Mat3::Zero();
    for (int i = 0; i < 3; ++i) A(i, i) = q(i) > 0.0 ? 1.0 : 0.0;
    out.hess = s.asDiagonal() * (A - u * u.transpose()) * s.asDiagonal() / L;
    return out;
  }
  int i_max;
  out.g = q.maxCoeff(&i_max) - r;
  out.grad = Vec3::Zero();
  out.grad(i_max) = s(i_max);
  return out;
}

class SitBar final : public RigidSurface {
 public:
  explicit SitBar(const SitBarShape& s) : s_(s) {}
  GapPoint gap(const Vec3& x) const override {
    const double zc = s_.lowest_z + s_.c;
    const Vec3 e(s_.a, s_.b, s_.c);
    const GapPoint left = ellipsoid_gap(Vec3(s_.centre_x - 0.5 * s_.it_spacing, s_.centre_y, zc), e, x);
    const GapPoint right = ellipsoid_gap(Vec3(s_.centre_x + 0.5 * s_.it_spacing, s_.centre_y, zc), e, x);
    const GapPoint plate =
        plate_gap(s_.centre_x, s_.centre_y, 0.5 * s_.plate_x, 0.5 * s_.plate_y, zc, s_.plate_edge, x);
    return soft_min(soft_min(left, right, s_.blend), plate, s_.blend);
  }
  std::string describe() const override {
    return fmt("SIT-BAR surrogate: lobes a = %g, b = %g, c = %g mm", s_.a, s_.b, s_.c) +
           fmt(", spacing %g mm, blend %g mm, plate %g x %g mm", s_.it_spacing, s_.blend, s_.plate_x, s_.plate_y) +
           fmt(", lowest point z = %g mm", s_.lowest_z);
  }

 private:
  SitBarShape s_;
};

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("rigid surface: " + what);
}

}  // namespace

GapPoint soft_min(const GapPoint& a, const GapPoint& b, double k) {
  const double delta = a.g - b.g;
  if (delta >= k) return b;
  if (delta <= -k) return a;
  const double wa = 0.5 - delta / (2.0 * k), wb = 0.5 + delta / (2.0 * k);
  const Vec3 dgrad = a.grad - b.grad;
  GapPoint s;
  s.g = 0.5 * (a.g + b.g) - 0.25 * k - delta * delta / (4.0 * k);
  s.grad = wa * a.grad + wb * b.grad;
  s.hess = wa * a.hess + wb * b.hess - dgrad * dgrad.transpose() / (2.0 * k);
  return s;
}

std::shared_ptr<const RigidSurface> make_plane(const Vec3& point, const Vec3& normal) {
  require(normal.norm() > 0.0, "plane normal must not be zero");
  return std::make_shared<Plane>(point, normal);
}

std::shared_ptr<const RigidSurface> make_sphere(const Vec3& centre, double radius) {
  require(radius > 0.0, "sphere radius must be > 0");
  return std::make_shared<Sphere>(centre, radius);
}

std::shared_ptr<const RigidSurface> make_cylinder(const Vec3& point, const Vec3& axis, double radius) {
  require(radius > 0.0, "cylinder radius must be > 0");
  require(axis.norm() > 0.0, "cylinder axis must not be zero");
  return std::make_shared<Cylinder>(point, axis, radius);
}

std::shared_ptr<const RigidSurface> make_flat_punch(double cx, double cy, double bottom, double radius, double r_edge) {
  require(radius > 0.0, "punch radius must be > 0");
  require(r_edge > 0.0 && r_edge <= radius, "punch edge radius must be in (0, radius]");
  return std::make_shared<FlatPunch>(cx, cy, bottom, radius, r_edge);
}

std::shared_ptr<const RigidSurface> make_sitbar(const SitBarShape& s) {
  require(s.a > 0 && s.b > 0 && s.c > 0, "SIT-BAR semi-axes must be > 0");
  require(s.blend > 0, "SIT-BAR blend width must be > 0");
  require(s.it_spacing >= 0, "SIT-BAR lobe spacing must be >= 0");
  require(s.plate_edge > 0 && s.plate_x > 2 * s.plate_edge && s.plate_y > 2 * s.plate_edge,
          "SIT-BAR plate must be larger than twice its edge radius (> 0)");
  return std::make_shared<SitBar>(s);
}

}  // namespace cushion::solver
