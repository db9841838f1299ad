#include "material/stability.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {

constexpr int kShearVoigt[3] = {3, 4, 5};  // pairs (0,1), (1,2), (0,2)
constexpr int kShearA[3] = {0, 1, 0};
constexpr int kShearB[3] = {1, 2, 2};

/// tanh(d)/d with its limit 1 at d = 0 (no cancellation for small d).
double tanh_ratio(double d) { return d == 0.0 ? 1.0 : std::tanh(d) / d; }

/// Which principal axes a mode drives with the nominal stretch l and which are free (zero stress).
struct ModeKinematics {
  bool driven[3];  ///< axis stretched to l
  bool free[3];    ///< axis with zero normal stress; others (neither) are held at stretch 1
};
ModeKinematics kinematics(StabilityMode mode) {
  switch (mode) {
    case StabilityMode::uniaxial: return {{true, false, false}, {false, true, true}};
    case StabilityMode::equibiaxial: return {{true, true, false}, {false, false, true}};
    case StabilityMode::planar: return {{true, false, false}, {false, false, true}};
    case StabilityMode::volumetric: return {{true, true, true}, {false, false, false}};
  }
  return {};
}

/// Solves the free stretches of `s` (ln l, updated in place; driven and held entries are already set)
/// for zero principal Kirchhoff stress tau_a = l_a^2 S_a on the free axes (bounded even when a free
/// stretch becomes small), by Newton in ln l with dtau_a/d ln l_b = 2 tau_a delta_ab + l_a^2 l_b^2 D_aabb.
/// Converged when the Newton update is below 1e-10 in ln l, or when it stops shrinking below 1e-6
/// (the round-off floor when the stresses on the driven axes are huge). Returns false when the model
/// fails or Newton does not converge.
bool solve_lateral(const Hyperelastic& model, const ModeKinematics& k, Vec3& s) {
  int idx[3], n = 0;
  for (int a = 0; a < 3; ++a)
    if (k.free[a]) idx[n++] = a;
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 60; ++it) {
    const Vec3 c = (2.0 * s).array().exp();  // l^2
    const ElasticEval e = model.evaluate(Mat3(s.array().exp().matrix().asDiagonal()));
    if (e.status == Status::failed) return false;
    if (n == 0) return true;
    const Vec3 tau = c.cwiseProduct(e.S.head<3>());
    Eigen::VectorXd r(n);
    Eigen::MatrixXd J(n, n);
    for (int i = 0; i < n; ++i) {
      const int a = idx[i];
      r(i) = tau(a);
      for (int j = 0; j < n; ++j) {
        const int b = idx[j];
        J(i, j) = (a == b ? 2.0 * tau(a) : 0.0) + c(a) * c(b) * e.dS_dE(a, b);
      }
    }
    if (r.cwiseAbs().maxCoeff() == 0.0) return true;
    Eigen::VectorXd ds = J.fullPivLu().solve(-r);
    if (!ds.allFinite()) return false;
    const double step = ds.cwiseAbs().maxCoeff();
    if (step > 0.5) ds *= 0.5 / step;  // damped: at most a factor e^0.5 in a stretch per iteration
    for (int i = 0; i < n; ++i) s(idx[i]) += ds(i);
    if (step <= 1e-10 || (step < 1e-6 && step > 0.5 * last_step)) return true;
    last_step = step;
  }
  return false;
}

/// Positive definiteness of the log tangent: K_ab > 0, M_aa > 0 and the Jacobi-scaled
/// D^-1/2 M D^-1/2 (D = diag M) with smallest eigenvalue above 1e-12. The scaling makes the test
/// independent of the very different magnitudes of the principal stiffnesses at large stretch.
bool drucker_stable(const Mat6& T) {
  if (!T.allFinite()) return false;
  for (int p = 3; p < 6; ++p)
    if (!(T(p, p) > 0.0)) return false;
  const Mat3 M = 0.5 * (T.topLeftCorner<3, 3>() + T.topLeftCorner<3, 3>().transpose());
  if (!(M.diagonal().minCoeff() > 0.0)) return false;
  const Vec3 d = M.diagonal().cwiseSqrt().cwiseInverse();
  const Mat3 Ms = d.asDiagonal() * M * d.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Mat3>(Ms, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() > 1e-12;
}

/// State of the continuation along a mode: log stretches s and their rate ds/d(ln l_driven), which
/// is 1 on driven axes, 0 on held axes and the last secant slope on free axes.
struct PathState {
  Vec3 s = Vec3::Zero();
  Vec3 slope = Vec3::Zero();
};

/// Initial slope of the free log stretches from the log tangent M at the start: M_ff slope_f = -M_fd 1_d.
Vec3 initial_slope(const ModeKinematics& k, const Mat3& M) {
  Vec3 slope = Vec3::Zero();
  int f[3], n = 0;
  for (int a = 0; a < 3; ++a) {
    if (k.driven[a]) slope(a) = 1.0;
    if (k.free[a]) f[n++] = a;
  }
  if (n == 0) return slope;
  Eigen::MatrixXd Mff(n, n);
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i) {
    rhs(i) = 0.0;
    for (int b = 0; b < 3; ++b)
      if (k.driven[b]) rhs(i) -= M(f[i], b);
    for (int j = 0; j < n; ++j) Mff(i, j) = M(f[i], f[j]);
  }
  const Eigen::VectorXd x = Mff.fullPivLu().solve(rhs);
  for (int i = 0; i < n; ++i) slope(f[i]) = std::isfinite(x(i)) ? x(i) : 0.0;
  return slope;
}

double driven_log_stretch(const ModeKinematics& k, const Vec3& s) {
  for (int a = 0; a < 3; ++a)
    if (k.driven[a]) return s(a);
  return 0.0;
}

/// Advances the path to driven log stretch `target`, checking stability at every accepted sub-state.
/// Predictor: the secant slope of the path (so Newton stays on the smooth continuation where two
/// lateral branches cross, as the closed-form hyperfoam branch does). A step is accepted when Newton
/// converges within 0.25 |d ln l_driven| of the prediction; otherwise it is halved. If 24 halvings do
/// not help, the lateral solution has a fold or bifurcation inside the step (a singular lateral
/// stiffness, itself Drucker-unstable): reported as unstable.
bool advance_stable(const Hyperelastic& model, const ModeKinematics& k, PathState& path, double target, int depth) {
  const double step = target - driven_log_stretch(k, path.s);
  const Vec3 predicted = path.s + step * path.slope;
  Vec3 trial = predicted;
  const bool converged = solve_lateral(model, k, trial);
  if (converged && (trial - predicted).cwiseAbs().maxCoeff() <= 0.25 * std::abs(step) + 1e-12) {
    if (!drucker_stable(kirchhoff_log_tangent(model, trial.array().exp()))) return false;
    if (step != 0.0) path.slope = (trial - path.s) / step;
    path.s = trial;
    return true;
  }
  if (depth >= 24) return false;
  return advance_stable(model, k, path, target - 0.5 * step, depth + 1) &&
         advance_stable(model, k, path, target, depth + 1);
}

/// Marches from strain 0 to `end` in `steps` steps; returns the first unstable nominal strain.
std::optional<double> first_unstable(const Hyperelastic& model, StabilityMode mode, double end, int steps) {
  const ModeKinematics k = kinematics(mode);
  PathState path;
  if (!solve_lateral(model, k, path.s)) return 0.0;
  const Mat6 T0 = kirchhoff_log_tangent(model, path.s.array().exp());
  if (!drucker_stable(T0)) return 0.0;
  path.slope = initial_slope(k, T0.topLeftCorner<3, 3>());
  for (int i = 1; i <= steps; ++i) {
    const double strain = end * i / steps;
    if (!(1.0 + strain > 0.0) || !advance_stable(model, k, path, std::log1p(strain), 0)) return strain;
  }
  return std::nullopt;
}

}  // namespace

std::string to_string(StabilityMode mode) {
  switch (mode) {
    case StabilityMode::uniaxial: return "uniaxial";
    case StabilityMode::equibiaxial: return "equibiaxial";
    case StabilityMode::planar: return "planar";
    case StabilityMode::volumetric: return "volumetric";
  }
  return "unknown";
}

Mat6 kirchhoff_log_tangent(const Hyperelastic& model, const Vec3& l) {
  Mat6 T = Mat6::Zero();
  const ElasticEval e = model.evaluate(Mat3(l.asDiagonal()));
  if (e.status == Status::failed) return Mat6::Constant(std::numeric_limits<double>::quiet_NaN());
  const Vec3 c = l.cwiseProduct(l);
  Vec3 tau;
  for (int a = 0; a < 3; ++a) tau(a) = c(a) * e.S(a);  // tau = F S F^T, F = diag(l)
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) T(a, b) = (a == b ? 2.0 * tau(a) : 0.0) + c(a) * c(b) * e.dS_dE(a, b);
  for (int p = 0; p < 3; ++p) {
    const int a = kShearA[p], b = kShearB[p], v = kShearVoigt[p];
    const double d = std::log(l(a)) - std::log(l(b));
    T(v, v) = (2.0 * c(a) * c(b) * e.dS_dE(v, v) + tau(a) + tau(b)) * tanh_ratio(d);
  }
  return T;
}

bool StabilityReport::stable() const {
  for (const StabilityModeResult& m : modes)
    if (m.first_unstable_compression || m.first_unstable_tension) return false;
  return true;
}

std::string StabilityReport::summary() const {
  std::ostringstream o;
  for (const StabilityModeResult& m : modes) {
    o << to_string(m.mode) << ": ";
    if (!m.first_unstable_compression && !m.first_unstable_tension) {
      o << "stable over [" << min_strain << ", " << max_strain << "]\n";
      continue;
    }
    o << "compression " << (m.first_unstable_compression ? "unstable from strain " + std::to_string(*m.first_unstable_compression)
                                                         : "stable to " + std::to_string(min_strain));
    o << ", tension " << (m.first_unstable_tension ? "unstable from strain " + std::to_string(*m.first_unstable_tension)
                                                   : "stable to " + std::to_string(max_strain));
    o << "\n";
  }
  return o.str();
}

StabilityReport check_stability(const Hyperelastic& model, double min_strain, double max_strain, int steps) {
  if (steps < 1 || !(min_strain <= 0.0) || !(max_strain >= 0.0) || !(min_strain > -1.0))
    throw std::invalid_argument("check_stability: need steps >= 1 and -1 < min_strain <= 0 <= max_strain");
  StabilityReport report;
  report.min_strain = min_strain;
  report.max_strain = max_strain;
  for (StabilityMode mode :
       {StabilityMode::uniaxial, StabilityMode::equibiaxial, StabilityMode::planar, StabilityMode::volumetric}) {
    report.modes.push_back({mode, first_unstable(model, mode, min_strain, steps),
                            first_unstable(model, mode, max_strain, steps)});
  }
  return report;
}

}  // namespace cushion::material
