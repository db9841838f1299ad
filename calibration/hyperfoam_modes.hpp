#pragma once
/// Homogeneous test modes of the ABAQUS hyperfoam with one Poisson ratio PER TERM (docs/physics.md 2.7):
///   W = sum_i 2 mu_i/alpha_i^2 (l1^a_i + l2^a_i + l3^a_i - 3 + (J^(-a_i b_i) - 1)/b_i),  b_i = nu_i/(1 - 2 nu_i),
///   Kirchhoff principal stress tau_a = sum_i c_i (l_a^a_i - J^(-a_i b_i)),  c_i = 2 mu_i/alpha_i,
///   nominal stress P_a = tau_a / l_a. Tension positive; mu [MPa], stresses [MPa], stretches [-].
/// Modes (control x):
///   uniaxial     x = l1;       l2 = l3 = lf free, tau_2 = 0:  J = l1 lf^2
///   equibiaxial  x = l1 = l2;  l3 = lf free, tau_3 = 0:       J = l1^2 lf
///   planar       x = l1, l2 = 1; l3 = lf free, tau_3 = 0:     J = l1 lf
///   volumetric   x = l1 = l2 = l3 (no free direction):        J = x^3, lf = x
///   simple_shear x = gamma, F = I + gamma e1 (x) e2, J = 1 kinematically; principal stretches
///                l_1,2 = sqrt(1 + gamma^2/4) +- gamma/2, l3 = 1; stress P12 = sigma12 = (tau_1 - tau_2)/(l_1 + l_2); lf = 1.
/// The loaded-direction stress is P_1 (uniaxial, equibiaxial, planar, volumetric) or P12 (simple shear).
/// With per-term nu the free stretch solves g(s) = sum_i c_i (e^(a_i s) - J(s)^(-a_i b_i)) = 0, s = ln lf,
/// J = e^(k s + m ln x): a safeguarded Newton-bisection in double, then ONE Newton step in T from the
/// converged root, which for ceres::Jet gives the implicit-function derivative ds/dp = -(dg/dp)/(dg/ds)
/// exactly (g = 0 in value there). g' = sum_i 2 mu_i (e^(a_i s) + k b_i J^(-a_i b_i)) > 0 when every
/// mu_i > 0 and nu_i >= 0, so the root is then unique.
#include <cmath>
#include <string>

namespace cushion::calibration {

enum class HyperfoamMode { uniaxial, equibiaxial, planar, simple_shear, volumetric };

std::string to_string(HyperfoamMode mode);
/// The mode has a free (stress-free) direction whose stretch a test may measure.
bool has_free_direction(HyperfoamMode mode);

/// Terms of the fit's hyperfoam: arrays of N values mu [MPa], alpha [-], nu [-] in [0, 0.5).
template <typename T>
struct HyperfoamTermsView {
  const T* mu;
  const T* alpha;
  const T* nu;
  int N;
};

/// Loaded-direction nominal stress [MPa] and free-direction stretch [-] at one control value.
template <typename T>
struct ModeResponse {
  T stress;
  T lateral;
  bool ok = true;  ///< false: the free stretch has no root in [e^-10, e^10] (the material is unusable there)
};

namespace detail {

inline double value_of(double x) { return x; }
template <typename J>
double value_of(const J& x) {
  return x.a;  // ceres::Jet
}

/// Value and every derivative finite (ceres::isfinite checks only the value of a Jet).
inline bool all_finite(double x) { return std::isfinite(x); }
template <typename J>
bool all_finite(const J& x) {
  return std::isfinite(x.a) && x.v.allFinite();
}

/// J = e^(k s + m ln x) of the modes with a free direction (uniaxial k = 2, m = 1; equibiaxial 1, 2; planar 1, 1).
struct FreeKinematics {
  double k, m;
};

inline FreeKinematics free_kinematics(HyperfoamMode mode) {
  if (mode == HyperfoamMode::uniaxial) return {2.0, 1.0};
  if (mode == HyperfoamMode::equibiaxial) return {1.0, 2.0};
  return {1.0, 1.0};  // planar
}

/// g(s) and dg/ds of the free-direction condition (see top).
template <typename T>
void free_condition(const HyperfoamTermsView<T>& t, FreeKinematics q, double ln_x, const T& s, T& g, T& dg) {
  using std::exp;
  g = T(0.0);
  dg = T(0.0);
  for (int i = 0; i < t.N; ++i) {
    const T b = t.nu[i] / (1.0 - 2.0 * t.nu[i]);
    const T Jb = exp(-t.alpha[i] * b * (q.k * s + q.m * ln_x));  // J^(-a b)
    const T ls = exp(t.alpha[i] * s);                              // lf^a
    g += (2.0 * t.mu[i] / t.alpha[i]) * (ls - Jb);
    dg += 2.0 * t.mu[i] * (ls + q.k * b * Jb);
  }
}

/// Root s of g in double: bracket by stepping from the common-nu estimate, then Newton kept inside the bracket.
template <typename T>
bool solve_free_stretch(const HyperfoamTermsView<T>& t, FreeKinematics q, double ln_x, double& s) {
  double mu_sum = 0.0, b_mean = 0.0;
  for (int i = 0; i < t.N; ++i) {
    const double nu = value_of(t.nu[i]), w = std::abs(value_of(t.mu[i]));
    mu_sum += w;
    b_mean += w * nu / (1.0 - 2.0 * nu);
  }
  b_mean = mu_sum > 0.0 ? b_mean / mu_sum : 0.0;
  double mu[6], alpha[6], nu[6];
  for (int i = 0; i < t.N && i < 6; ++i) mu[i] = value_of(t.mu[i]), alpha[i] = value_of(t.alpha[i]), nu[i] = value_of(t.nu[i]);
  const HyperfoamTermsView<double> d{mu, alpha, nu, t.N < 6 ? t.N : 6};
  auto eval = [&](double x, double& g, double& dg) { free_condition(d, q, ln_x, x, g, dg); };
  s = -q.m * b_mean * ln_x / (1.0 + q.k * b_mean);  // exact for a common nu
  double g = 0.0, dg = 0.0;
  eval(s, g, dg);
  if (!std::isfinite(g)) return false;
  if (g == 0.0) return true;
  // Bracket [lo, hi] with g(lo) < 0 < g(hi) (g increases for a stable material), widening from s.
  double lo = s, hi = s, width = 0.05;
  for (;;) {
    const double x = g > 0.0 ? s - width : s + width;
    double gx = 0.0, dx = 0.0;
    eval(x, gx, dx);
    if (!std::isfinite(gx) || width > 10.0) return false;
    if (g > 0.0) {
      if (gx < 0.0) { lo = x; break; }
      hi = x;
    } else {
      if (gx > 0.0) { hi = x; break; }
      lo = x;
    }
    width *= 2.0;
  }
  s = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    eval(s, g, dg);
    if (g == 0.0) return true;
    (g < 0.0 ? lo : hi) = s;
    double next = s - g / dg;
    if (!(dg > 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - s) < 1e-15 * (1.0 + std::abs(s))) return true;
    s = next;
    if (hi - lo < 1e-15) return true;
  }
  return true;
}

/// Kirchhoff principal stress along a principal stretch l_a [-] at volume ratio J.
template <typename T, typename L, typename V>
T principal_tau(const HyperfoamTermsView<T>& t, const L& ln_l, const V& ln_J) {
  using std::exp;
  T tau(0.0);
  for (int i = 0; i < t.N; ++i) {
    const T b = t.nu[i] / (1.0 - 2.0 * t.nu[i]);
    tau += (2.0 * t.mu[i] / t.alpha[i]) * (exp(t.alpha[i] * ln_l) - exp(-t.alpha[i] * b * ln_J));
  }
  return tau;
}

}  // namespace detail

/// Response of the mode at control x (stretch, or gamma in simple shear); x > 0 except simple shear.
template <typename T>
ModeResponse<T> mode_response(const HyperfoamTermsView<T>& t, HyperfoamMode mode, double x) {
  using std::exp;
  ModeResponse<T> r;
  if (mode == HyperfoamMode::simple_shear) {
    const double l1 = std::sqrt(1.0 + 0.25 * x * x) + 0.5 * x, l2 = 1.0 / l1;
    const T tau1 = detail::principal_tau(t, std::log(l1), 0.0), tau2 = detail::principal_tau(t, std::log(l2), 0.0);
    r.stress = (tau1 - tau2) / (l1 + l2);
    r.lateral = T(1.0);
    return r;
  }
  const double ln_x = std::log(x);
  if (mode == HyperfoamMode::volumetric) {
    r.stress = detail::principal_tau(t, ln_x, 3.0 * ln_x) / x;
    r.lateral = T(x);
    return r;
  }
  const detail::FreeKinematics q = detail::free_kinematics(mode);
  double s0 = 0.0;
  r.ok = detail::solve_free_stretch(t, q, ln_x, s0);
  T g, dg;
  detail::free_condition(t, q, ln_x, T(s0), g, dg);
  const T s = T(s0) - g / dg;  // value s0; derivatives of the implicit root
  const T ln_J = q.k * s + q.m * ln_x;
  r.stress = detail::principal_tau(t, ln_x, ln_J) / x;
  r.lateral = exp(s);
  r.ok = r.ok && std::isfinite(detail::value_of(r.stress));
  return r;
}

/// Drucker measures of the state of `mode` at control x (not simple shear), in units of mu_s [MPa] (docs/physics.md
/// 2.7): the principal log-strain tangent M_ab = dtau_a/d ln l_b = d_a delta_ab + c with d_a = 2 sum mu_i l_a^a_i,
/// c = 2 sum mu_i b_i J^(-a_i b_i), is positive definite iff the pivots of its LDL^T factorisation are > 0:
/// q0 = M_11, q1 = (M_11 M_22 - c^2)/M_11, q2 = det M / (M_11 M_22 - c^2), det M = d1 d2 d3 + c (d1 d2 + d2 d3 + d1 d3);
/// the shear terms K_ab = (tau_a - tau_b)/(ln l_a - ln l_b) (limit d_a at equal stretches) must be > 0 too:
/// q3, q4, q5 = K_12, K_23, K_13. All > 0 means Drucker-stable at that state. false when the free stretch fails.
template <typename T>
bool drucker_measures(const HyperfoamTermsView<T>& t, HyperfoamMode mode, double x, double mu_s, T q[6]) {
  using std::exp;
  const ModeResponse<T> r = mode_response(t, mode, x);
  if (!r.ok) return false;
  const double lx = std::log(x);
  const T lf = log(r.lateral);
  T ln_l[3];
  switch (mode) {
    case HyperfoamMode::uniaxial: ln_l[0] = T(lx), ln_l[1] = lf, ln_l[2] = lf; break;
    case HyperfoamMode::equibiaxial: ln_l[0] = T(lx), ln_l[1] = T(lx), ln_l[2] = lf; break;
    case HyperfoamMode::planar: ln_l[0] = T(lx), ln_l[1] = T(0.0), ln_l[2] = lf; break;
    default: ln_l[0] = T(lx), ln_l[1] = T(lx), ln_l[2] = T(lx); break;
  }
  const T ln_J = ln_l[0] + ln_l[1] + ln_l[2];
  T d[3] = {T(0.0), T(0.0), T(0.0)}, tau[3], c(0.0);
  for (int a = 0; a < 3; ++a) tau[a] = detail::principal_tau(t, ln_l[a], ln_J);
  for (int i = 0; i < t.N; ++i) {
    const T b = t.nu[i] / (1.0 - 2.0 * t.nu[i]);
    for (int a = 0; a < 3; ++a) d[a] += 2.0 * t.mu[i] * exp(t.alpha[i] * ln_l[a]);
    c += 2.0 * t.mu[i] * b * exp(-t.alpha[i] * b * ln_J);
  }
  const T m1 = d[0] + c, m2 = (d[0] + c) * (d[1] + c) - c * c;
  q[0] = m1 / mu_s;
  q[1] = m2 / m1 / mu_s;
  q[2] = (d[0] * d[1] * d[2] + c * (d[0] * d[1] + d[1] * d[2] + d[0] * d[2])) / m2 / mu_s;
  const int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (int k = 0; k < 3; ++k) {
    const int a = pairs[k][0], b = pairs[k][1];
    const T de = ln_l[a] - ln_l[b];
    using std::abs;
    q[3 + k] = (abs(detail::value_of(de)) < 1e-9 ? d[a] : (tau[a] - tau[b]) / de) / mu_s;
  }
  return true;
}

}  // namespace cushion::calibration
