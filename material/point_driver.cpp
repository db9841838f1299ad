#include "material/point_driver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "io/input_error.hpp"

namespace cushion::material {

namespace {

constexpr int default_steps_ramp_hold = 100;
constexpr int default_steps_per_cycle = 64;
constexpr double stretch_tolerance = 1e-12;  // Newton stop: the next correction |dl| <= 1e-12 l (not applied)
constexpr int max_newton_iterations = 60;
constexpr int max_backtracks = 30;

std::string time_text(double t) {
  std::ostringstream s;
  s.precision(10);
  s << "t = " << t << " s";
  return s.str();
}

/// The committed point: deformation gradient and internal state after the last accepted increment.
struct Committed {
  Mat3 F = Mat3::Identity();
  std::vector<double> state;
};

/// One integration from the committed point to F_new over dt, into `state_new`.
PointResponse integrate(const Material& material, const Committed& committed, const Mat3& F_new, double dt,
                        std::vector<double>& state_new) {
  return material.integrate(committed.F, F_new, dt, committed.state, state_new);
}

/// The unknowns of the free-stretch Newton: each moves the diagonal stretches F(a,a) of its axes together.
struct FreeUnknowns {
  int n = 0;
  std::array<std::array<int, 3>, 3> axes{};  ///< axes[k][0 .. size[k] - 1]: the axes of unknown k
  std::array<int, 3> size{};
};

/// One unknown per free axis; with `tie_equal`, free axes whose stretch starts equal share one unknown.
FreeUnknowns free_unknowns(const std::array<bool, 3>& free, const Mat3& F, bool tie_equal) {
  FreeUnknowns u;
  for (int a = 0; a < 3; ++a) {
    if (!free[a]) continue;
    int k = 0;
    while (k < u.n && !(tie_equal && F(u.axes[k][0], u.axes[k][0]) == F(a, a))) ++k;
    if (k == u.n) ++u.n;
    u.axes[k][u.size[k]++] = a;
  }
  return u;
}

/// Whether the tied axes of `u` carry equal stresses at r (to 1e-12 of the largest normal modulus): the material
/// responds isotropically, so the tied solution is the untied one.
bool ties_hold(const FreeUnknowns& u, const PointResponse& r) {
  const double modulus_scale = r.dS_dE.topLeftCorner<3, 3>().cwiseAbs().maxCoeff();
  for (int k = 0; k < u.n; ++k)
    for (int i = 1; i < u.size[k]; ++i)
      if (!(std::abs(r.S(u.axes[k][i]) - r.S(u.axes[k][0])) <= 1e-12 * modulus_scale)) return false;
  return true;
}

/// Solves S_aa = 0 for the diagonal stretches F(a,a) of the unknowns' axes (the others stay as given in F) by
/// Newton on the Green-Lagrange components E_aa = (F_aa^2 - 1)/2 with the consistent tangent dS/dE (a tied unknown:
/// the mean of its axes' S_aa and of their rows of dS/dE summed over the columns of each unknown), halving a step
/// that leaves the admissible range or makes the material fail. F must be diagonal in the free rows/columns.
/// Returns the response at the solution; F and state_new hold the solution.
PointResponse newton_free_axes(const Material& material, const Committed& committed, Mat3& F, const FreeUnknowns& u,
                               double dt, double time, std::vector<double>& state_new) {
  // At most 3 unknowns: fixed-capacity Eigen types, so the per-step solve allocates nothing.
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
  const int n = u.n;
  Vec E(n), E_previous(n), step = Vec::Zero(n);
  for (int k = 0; k < n; ++k) E(k) = 0.5 * (F(u.axes[k][0], u.axes[k][0]) * F(u.axes[k][0], u.axes[k][0]) - 1.0);
  E_previous = E;
  auto set_stretches = [&](const Vec& strain) {
    for (int k = 0; k < n; ++k) {
      if (!(1.0 + 2.0 * strain(k) > 0.0)) return false;
      for (int i = 0; i < u.size[k]; ++i) F(u.axes[k][i], u.axes[k][i]) = std::sqrt(1.0 + 2.0 * strain(k));
    }
    return true;
  };

  int backtracks = 0;
  for (int iteration = 0; iteration <= max_newton_iterations; ++iteration) {
    PointResponse r = set_stretches(E) ? integrate(material, committed, F, dt, state_new) : PointResponse{};
    const bool admissible = (1.0 + 2.0 * E.array() > 0.0).all() && r.status != Status::failed;
    if (!admissible) {
      if (iteration == 0 || ++backtracks > max_backtracks) {
        r.status = Status::failed;
        if (r.message.empty()) r.message = "non-positive stretch";
        return r;
      }
      step *= 0.5;  // back-track along the last Newton direction
      E = E_previous + step;
      continue;
    }
    if (n == 0) return r;
    Vec residual = Vec::Zero(n);
    Mat jacobian = Mat::Zero(n, n);
    double worst_residual = 0.0;  // a loop, not cwiseAbs().maxCoeff(): gcc 12 warns (falsely) on the packet read
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < u.size[k]; ++i) {
        const int a = u.axes[k][i];
        residual(k) += r.S(a) / u.size[k];
        worst_residual = std::max(worst_residual, std::abs(r.S(a)));
        for (int m = 0; m < n; ++m)
          for (int j = 0; j < u.size[m]; ++j) jacobian(k, m) += r.dS_dE(a, u.axes[m][j]) / u.size[k];
      }
    const double modulus_scale = r.dS_dE.topLeftCorner<3, 3>().cwiseAbs().maxCoeff();
    if (worst_residual <= 1e-15 * modulus_scale) return r;

    E_previous = E;
    step = n == 1 ? Vec::Constant(1, -residual(0) / jacobian(0, 0)) : Vec(jacobian.fullPivLu().solve(-residual));
    E = E_previous + step;
    backtracks = 0;
    double stretch_step = 0.0;  // the largest correction, relative to max(l, 1)
    for (int k = 0; k < n; ++k) {
      const double l_old = std::sqrt(1.0 + 2.0 * E_previous(k));
      const double l_new = 1.0 + 2.0 * E(k) > 0.0 ? std::sqrt(1.0 + 2.0 * E(k)) : 0.0;
      stretch_step = std::max(stretch_step, std::abs(l_new - l_old) / std::max(l_old, 1.0));
    }
    if (!std::isfinite(stretch_step)) break;
    // The next correction is below the tolerance: the point just evaluated (F and state_new hold it) is the solution
    // to 1e-12 l, so it is not evaluated once more (one material call of ~3 saved; physics.md 9.7).
    if (stretch_step <= stretch_tolerance) return r;
  }
  throw std::runtime_error("point driver: free-stretch Newton (S_aa = 0) did not converge in " +
                           std::to_string(max_newton_iterations) + " iterations at " + time_text(time));
}

/// Solves S_aa = 0 for the diagonal stretches F(a,a) with free[a] (newton_free_axes). Free axes that start at the
/// same stretch (the lateral axes of a uniaxial path) are first solved as one unknown: an isotropic material keeps
/// them equal, and equal stretches halve the hyperfoam's transcendental calls (hyperfoam.cpp). If their stresses
/// then differ (an anisotropic response), the axes are solved one unknown each from the same start.
PointResponse solve_free_axes(const Material& material, const Committed& committed, Mat3& F,
                              const std::array<bool, 3>& free, double dt, double time,
                              std::vector<double>& state_new) {
  const FreeUnknowns untied = free_unknowns(free, F, false), tied = free_unknowns(free, F, true);
  if (tied.n == untied.n) return newton_free_axes(material, committed, F, untied, dt, time, state_new);
  const Mat3 F_start = F;
  const PointResponse r = newton_free_axes(material, committed, F, tied, dt, time, state_new);
  if (r.status != Status::failed && ties_hold(tied, r)) return r;
  F = F_start;
  return newton_free_axes(material, committed, F, untied, dt, time, state_new);
}

/// Deformation gradient imposed by the control value in a mode (diagonal entries of free axes are
/// initial guesses taken from `previous`).
Mat3 imposed_F(LoadMode mode, double control, const Mat3& previous) {
  Mat3 F = Mat3::Identity();
  const double l = 1.0 + control;
  switch (mode) {
    case LoadMode::uniaxial_free:
      F(0, 0) = l;
      F(1, 1) = previous(1, 1);
      F(2, 2) = previous(2, 2);
      break;
    case LoadMode::uniaxial_constrained: F(0, 0) = l; break;
    case LoadMode::volumetric: F = l * Mat3::Identity(); break;
    case LoadMode::simple_shear: F(0, 1) = control; break;
  }
  return F;
}

/// Start of the free-stretch Newton: the diagonal of the committed F extrapolated linearly in time from the increment
/// before (ratio = dt/dt_before, at most 2; 0 at the first increment). Only a guess: Newton converges to the same point
/// from it, in one iteration fewer on a smooth path (a material whose free stretches move, e.g. an air pressure).
Mat3 extrapolated_guess(const Mat3& now, const Mat3& before, double ratio) {
  Mat3 guess = now;
  for (int a = 0; a < 3; ++a) {
    const double l = now(a, a) + ratio * (now(a, a) - before(a, a));
    if (l > 0.5 * now(a, a)) guess(a, a) = l;
  }
  return guess;
}

/// The control value a deformation gradient corresponds to in a mode.
double control_of(LoadMode mode, const Mat3& F) { return mode == LoadMode::simple_shear ? F(0, 1) : F(0, 0) - 1.0; }

void require_success(const PointResponse& r, double time) {
  if (r.status == Status::failed)
    throw std::runtime_error("point driver: material failed at " + time_text(time) + ": " +
                             (r.message.empty() ? std::string("no reason given") : r.message));
}

}  // namespace

std::string to_string(LoadMode mode) {
  switch (mode) {
    case LoadMode::uniaxial_free: return "uniaxial_free";
    case LoadMode::uniaxial_constrained: return "uniaxial_constrained";
    case LoadMode::volumetric: return "volumetric";
    case LoadMode::simple_shear: return "simple_shear";
  }
  return "unknown";
}

LoadMode load_mode_from_string(const std::string& name) {
  for (LoadMode mode : {LoadMode::uniaxial_free, LoadMode::uniaxial_constrained, LoadMode::volumetric,
                        LoadMode::simple_shear})
    if (to_string(mode) == name) return mode;
  throw InputError("mode '" + name + "': must be one of uniaxial_free, uniaxial_constrained, volumetric, simple_shear");
}

History build_history(const std::vector<Segment>& segments, AxisControl axis_control) {
  History h;
  h.axis_control = axis_control;
  h.time.push_back(0.0);
  h.control.push_back(0.0);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Segment& seg = segments[s];
    const std::string name = "protocol segment " + std::to_string(s + 1);
    auto require = [&](bool ok, const std::string& problem) {
      if (!ok) throw InputError(name + ": " + problem);
    };
    require(seg.steps >= 0, "steps must be >= 0 (0: default)");
    const double t0 = h.time.back(), c0 = h.control.back();
    switch (seg.kind) {
      case Segment::Kind::ramp:
      case Segment::Kind::hold: {
        const bool ramp = seg.kind == Segment::Kind::ramp;
        require(std::isfinite(seg.duration) && seg.duration > 0.0, "duration must be > 0 s");
        require(!ramp || std::isfinite(seg.target), "target must be finite");
        const int n = seg.steps > 0 ? seg.steps : default_steps_ramp_hold;
        const double c1 = ramp ? seg.target : c0;
        for (int k = 1; k <= n; ++k) {
          h.time.push_back(t0 + seg.duration * k / n);
          h.control.push_back(c0 + (c1 - c0) * k / n);
        }
        break;
      }
      case Segment::Kind::sine: {
        require(std::isfinite(seg.amplitude) && seg.amplitude >= 0.0, "amplitude must be >= 0");
        require(std::isfinite(seg.frequency) && seg.frequency > 0.0, "frequency must be > 0 Hz");
        require(std::isfinite(seg.cycles) && seg.cycles > 0.0, "cycles must be > 0");
        const double duration = seg.cycles / seg.frequency;
        const int n = seg.steps > 0 ? seg.steps
                                    : std::max(1, static_cast<int>(std::ceil(default_steps_per_cycle * seg.cycles - 1e-9)));
        for (int k = 1; k <= n; ++k) {
          const double t_local = duration * k / n;
          h.time.push_back(t0 + t_local);
          h.control.push_back(c0 + seg.amplitude * std::sin(2.0 * std::numbers::pi * seg.frequency * t_local));
        }
        break;
      }
    }
  }
  return h;
}

PointResult run_point(const Material& material, LoadMode mode, const History& history) {
  if (history.time.size() != history.control.size())
    throw InputError("point history: " + std::to_string(history.time.size()) + " times but " +
                     std::to_string(history.control.size()) + " control values");
  const bool platen = history.axis_control == AxisControl::platen;
  if (platen && mode != LoadMode::uniaxial_free && mode != LoadMode::uniaxial_constrained)
    throw InputError("platen control needs mode uniaxial_free or uniaxial_constrained, not " + to_string(mode));

  PointResult result;
  const std::size_t steps = history.time.size();
  result.time.reserve(steps);
  result.control.reserve(steps);
  result.F.reserve(steps);
  result.P.reserve(steps);
  result.sigma.reserve(steps);
  result.in_contact.reserve(steps);
  Committed committed;
  committed.state.assign(material.state_size(), 0.0);
  material.initial_state(committed.state);
  std::vector<double> state_new(committed.state.size()), state_free(committed.state.size());

  auto record = [&](double t, double control, const PointResponse& r, bool in_contact) {
    const Mat3 S = from_voigt_stress(r.S);
    result.time.push_back(t);
    result.control.push_back(control);
    result.F.push_back(committed.F);
    result.P.push_back(pk1_from_pk2(committed.F, S));
    result.sigma.push_back(cauchy_from_pk2(committed.F, S));
    result.in_contact.push_back(in_contact);
    if (r.status == Status::unreliable &&
        std::find(result.warnings.begin(), result.warnings.end(), r.message) == result.warnings.end())
      result.warnings.push_back(r.message);
  };

  Mat3 F_before = committed.F;  // the committed F one increment earlier, and that increment's dt
  double dt_before = 0.0;
  auto commit = [&](const Mat3& F, std::vector<double>& state, double dt) {
    F_before = committed.F;
    dt_before = dt;
    committed.F = F;
    committed.state.swap(state);
  };

  // One increment from the committed point to `control` over dt; commits and records it.
  auto advance = [&](double t, double control, double dt) {
    const std::array<bool, 3> lateral_free = {false, mode == LoadMode::uniaxial_free, mode == LoadMode::uniaxial_free};
    const Mat3 guess = extrapolated_guess(committed.F, F_before, dt_before > 0.0 ? std::min(dt / dt_before, 2.0) : 0.0);
    Mat3 F = imposed_F(mode, control, guess);
    const PointResponse r = solve_free_axes(material, committed, F, lateral_free, dt, t, state_new);
    // A platen only pushes. While the imposed stretch needs a compressive S11 the foam presses on it; a tensile S11
    // means the foam recovers more slowly than the platen retracts: it is free (S11 = 0) and short of the platen. For a
    // stable material S11 > 0 at the imposed stretch is the same as a free stretch below it, so the free state is
    // solved only then (most increments hold contact: one solve instead of two), or when the imposed stretch fails.
    if (platen && (r.status == Status::failed || r.S(0) > 0.0)) {
      Mat3 F_free = guess;
      const PointResponse free = solve_free_axes(material, committed, F_free, {true, lateral_free[1], lateral_free[2]},
                                                 dt, t, state_free);
      require_success(free, t);
      if (F_free(0, 0) < 1.0 + control) {  // lift-off
        commit(F_free, state_free, dt);
        PointResponse clear = free;
        clear.S.setZero();  // S = 0 to the Newton tolerance; reported as exactly zero force
        record(t, control_of(mode, F_free), clear, false);
        return;
      }
    }
    require_success(r, t);
    commit(F, state_new, dt);
    record(t, control, r, true);
  };

  if (history.time.empty()) return result;
  if (history.control.front() == 0.0) {
    PointResponse virgin = material.integrate(committed.F, committed.F, 0.0, committed.state, state_new);
    require_success(virgin, history.time.front());
    record(history.time.front(), 0.0, virgin, true);
  } else {
    advance(history.time.front(), history.control.front(), 0.0);
  }
  for (std::size_t n = 1; n < history.time.size(); ++n) {
    const double dt = history.time[n] - history.time[n - 1];
    if (!(dt > 0.0))
      throw InputError("point history: times must increase strictly (" + time_text(history.time[n]) + ")");
    advance(history.time[n], history.control[n], dt);
  }
  return result;
}

}  // namespace cushion::material
