#include "calibration/hereditary_fit.hpp"

#include "calibration/ceres_options.hpp"
#include "calibration/segments.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace cushion::calibration {
namespace {

/// D_i(q) = J_i(t1_q) - J_i(t2_q) and its beta-derivative for one mode.
struct ModeDifference {
  std::vector<cplx> D, dD;
  std::vector<cplx> J1, dJ1, J2, dJ2;  ///< the kernel itself at t1 (loading) and t2 (unloading)
};

ModeDifference mode_difference(const StressStrainRecord& r, const StrainPairs& p, cplx beta) {
  std::vector<double> q = p.t1;
  q.insert(q.end(), p.t2.begin(), p.t2.end());
  const auto K = hereditary_kernel(r.time, r.strain, beta, q);
  const std::size_t n = p.t1.size();
  ModeDifference m;
  m.D.resize(n);
  m.dD.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.D[i] = K.J[i] - K.J[n + i];
    m.dD[i] = K.dJ_dbeta[i] - K.dJ_dbeta[n + i];
  }
  m.J1.assign(K.J.begin(), K.J.begin() + long(n));
  m.J2.assign(K.J.begin() + long(n), K.J.end());
  m.dJ1.assign(K.dJ_dbeta.begin(), K.dJ_dbeta.begin() + long(n));
  m.dJ2.assign(K.dJ_dbeta.begin() + long(n), K.dJ_dbeta.end());
  return m;
}

/// Measured stress at the pair times, in the fit's units, and the slack of the physical bounds.
struct PairStress {
  std::vector<double> loading, unloading;  ///< sigma(t1), sigma(t2)
  double slack = 0.02;                     ///< tolerance of the bounds below
};

/// Residuals model - measured; parameters [Re a, Im a, Re b, Im b] per mode (paper Table 2 order).
/// Model: delta_sigma = -Re sum alpha_i D_i, so d/dRe a = -Re D, d/dIm a = Im D,
/// d/dRe b = -Re(alpha D'), d/dIm b = Im(alpha D') (J holomorphic in beta).
/// Then 3 bound rows per pair (zero while the bound holds): the difference stress does not see a part of
/// sigma_v that depends on the strain only (a mode with beta T << 1 is a spring: -Re alpha eps(t)), so
/// without bounds a slow mode with a huge residue "fits" and the decomposition's elastic curve is that
/// spring (seen: alpha = 1e4 peak, an elastic curve of -90 MPa). A viscous overstress of a dissipative
/// material is, on loading, 0 <= sigma_v(t1) <= sigma(t1) (the elastic stress is compressive), and on
/// unloading sigma_v(t2) <= sigma(t2) (likewise; sigma_v itself may stay positive for a while after the turn);
/// the rows are max(0, violation - slack) (slack in units of the peak stress).
class DifferenceStressCost final : public ceres::CostFunction {
 public:
  DifferenceStressCost(const StressStrainRecord& r, const StrainPairs& p, const std::vector<double>& measured,
                       int modes, const PairStress* bounds = nullptr)
      : r_(r), p_(p), measured_(measured), modes_(modes), bounds_(bounds) {
    set_num_residuals(int(measured.size() * (bounds ? 4 : 1)));
    mutable_parameter_block_sizes()->push_back(4 * modes);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const std::size_t n = measured_.size();
    const std::size_t P = 4 * std::size_t(modes_);
    for (std::size_t q = 0; q < n; ++q) residuals[q] = -measured_[q];
    // sigma_v at t1 and t2 and their gradients (bounds only).
    std::vector<double> v1(n, 0.0), v2(n, 0.0), g1, g2;
    if (bounds_) {
      g1.assign(n * P, 0.0);
      g2.assign(n * P, 0.0);
    }
    for (int i = 0; i < modes_; ++i) {
      const cplx alpha(x[4 * i], x[4 * i + 1]), beta(x[4 * i + 2], x[4 * i + 3]);
      const auto m = mode_difference(r_, p_, beta);
      for (std::size_t q = 0; q < n; ++q) {
        residuals[q] -= (alpha * m.D[q]).real();
        if (!std::isfinite(residuals[q])) return false;
        if (jacobians && jacobians[0]) {
          double* row = jacobians[0] + q * P + 4 * i;
          const cplx aD = alpha * m.dD[q];
          row[0] = -m.D[q].real();
          row[1] = m.D[q].imag();
          row[2] = -aD.real();
          row[3] = aD.imag();
        }
        if (bounds_) {
          v1[q] -= (alpha * m.J1[q]).real();
          v2[q] -= (alpha * m.J2[q]).real();
          const cplx a1 = alpha * m.dJ1[q], a2 = alpha * m.dJ2[q];
          double* r1 = g1.data() + q * P + 4 * i;
          double* r2 = g2.data() + q * P + 4 * i;
          r1[0] = -m.J1[q].real(), r1[1] = m.J1[q].imag(), r1[2] = -a1.real(), r1[3] = a1.imag();
          r2[0] = -m.J2[q].real(), r2[1] = m.J2[q].imag(), r2[2] = -a2.real(), r2[3] = a2.imag();
        }
      }
    }
    if (!bounds_) return true;
    const double slack = bounds_->slack;
    for (std::size_t q = 0; q < n; ++q) {
      // row n + 3q: sigma_v(t1) >= 0; n + 3q + 1: sigma_v(t1) <= sigma(t1); n + 3q + 2: sigma_v(t2) <= sigma(t2).
      const double viol[3] = {-v1[q] - slack, v1[q] - bounds_->loading[q] - slack, v2[q] - bounds_->unloading[q] - slack};
      const double sign[3] = {-1.0, 1.0, 1.0};
      const std::vector<double>* grad[3] = {&g1, &g1, &g2};
      for (int b = 0; b < 3; ++b) {
        const std::size_t row = n + 3 * q + std::size_t(b);
        const bool active = viol[b] > 0.0;
        residuals[row] = active ? viol[b] : 0.0;
        if (!std::isfinite(residuals[row])) return false;
        if (jacobians && jacobians[0])
          for (std::size_t j = 0; j < P; ++j) jacobians[0][row * P + j] = active ? sign[b] * (*grad[b])[q * P + j] : 0.0;
      }
    }
    return true;
  }

 private:
  const StressStrainRecord& r_;
  const StrainPairs& p_;
  const std::vector<double>& measured_;
  int modes_;
  const PairStress* bounds_;
};

/// Variable projection (Golub-Pereyra with Kaufman's Jacobian): parameters are only the decay rates
/// [Re b, Im b] per mode; the residues are eliminated by linear least squares, residual
/// r(beta) = -(I - P) y with P the projection onto the columns Phi(beta) (-Re D_i, Im D_i), and
/// Jacobian J_p = (I - P) (dPhi/dp) alpha(beta).
class ProjectedCost final : public ceres::CostFunction {
 public:
  ProjectedCost(const StressStrainRecord& r, const StrainPairs& p, const std::vector<double>& measured, int modes)
      : r_(r), p_(p), y_(Eigen::Map<const Eigen::VectorXd>(measured.data(), Eigen::Index(measured.size()))),
        modes_(modes) {
    set_num_residuals(int(measured.size()));
    mutable_parameter_block_sizes()->push_back(2 * modes);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const Eigen::Index n = y_.size();
    Eigen::MatrixXd Phi(n, 2 * modes_), dPhi_r(n, 2 * modes_), dPhi_i(n, 2 * modes_);
    for (int i = 0; i < modes_; ++i) {
      const auto m = mode_difference(r_, p_, cplx(x[2 * i], x[2 * i + 1]));
      for (Eigen::Index q = 0; q < n; ++q) {
        Phi(q, 2 * i) = -m.D[q].real();
        Phi(q, 2 * i + 1) = m.D[q].imag();
        dPhi_r(q, 2 * i) = -m.dD[q].real();  // d/dRe beta
        dPhi_r(q, 2 * i + 1) = m.dD[q].imag();
        dPhi_i(q, 2 * i) = m.dD[q].imag();   // d/dIm beta: D' -> i D'
        dPhi_i(q, 2 * i + 1) = m.dD[q].real();
      }
    }
    if (!Phi.allFinite()) return false;
    Eigen::VectorXd scale = Phi.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Phi * scale.cwiseInverse().asDiagonal());
    const Eigen::VectorXd alpha = qr.solve(y_).cwiseQuotient(scale);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, qr.rank());
    auto project_out = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v - Q * (Q.transpose() * v); };
    Eigen::Map<Eigen::VectorXd>(residuals, n) = -project_out(y_);
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(jacobians[0], n, 2 * modes_);
      for (int i = 0; i < modes_; ++i) {
        const Eigen::VectorXd vr = dPhi_r.middleCols(2 * i, 2) * alpha.segment(2 * i, 2);
        const Eigen::VectorXd vi = dPhi_i.middleCols(2 * i, 2) * alpha.segment(2 * i, 2);
        J.col(2 * i) = project_out(vr);
        J.col(2 * i + 1) = project_out(vi);
      }
    }
    return true;
  }

 private:
  const StressStrainRecord& r_;
  const StrainPairs& p_;
  Eigen::VectorXd y_;
  int modes_;
};

ceres::Solver::Options solver_options(const HereditaryFitOptions& o) {
  return dense_fit_options({o.function_tolerance, o.gradient_tolerance, o.parameter_tolerance, o.max_iterations});
}

}  // namespace

std::vector<HereditaryMode> best_residues(const StressStrainRecord& r, const StrainPairs& p,
                                          const std::vector<double>& measured, const std::vector<cplx>& betas) {
  const int M = int(betas.size());
  const std::size_t n = measured.size();
  Eigen::MatrixXd A(n, 2 * M);
  Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(measured.data(), Eigen::Index(n));
  for (int i = 0; i < M; ++i) {
    const auto m = mode_difference(r, p, betas[i]);
    for (std::size_t q = 0; q < n; ++q) {
      A(q, 2 * i) = -m.D[q].real();
      A(q, 2 * i + 1) = m.D[q].imag();
    }
  }
  // Column scaling for conditioning; rank-revealing QR gives the minimum-norm-like basic solution.
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0.0 ? scale(j) : 1.0;
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd y = As.colPivHouseholderQr().solve(b).cwiseQuotient(scale);
  std::vector<HereditaryMode> modes(M);
  for (int i = 0; i < M; ++i) modes[i] = {cplx(y(2 * i), y(2 * i + 1)), betas[i]};
  return modes;
}

HereditaryFit fit_hereditary(const StressStrainRecord& r, const Segments& s, const StrainPairs& p,
                             const HereditaryFitOptions& o) {
  const int M = o.modes;
  if (M < 1) throw std::invalid_argument("fit_hereditary: need at least one mode");
  if (p.t1.size() < std::size_t(4 * M))
    throw std::invalid_argument(r.source + ": only " + std::to_string(p.t1.size()) +
                                " loading/unloading pairs: too few to fit " + std::to_string(4 * M) + " parameters");
  const std::vector<double> measured = measured_difference_stress(r, p);
  // The kernels run over the slope changes of the strain history only (collinear samples add nothing), up
  // to the last paired time: far fewer pieces than samples (a few for a constant-rate test).
  StressStrainRecord knots;
  {
    const double last = *std::max_element(p.t2.begin(), p.t2.end());
    std::size_t end = 1;
    while (end < r.time.size() && r.time[end - 1] < last) ++end;
    const std::vector<double> time(r.time.begin(), r.time.begin() + end), strain(r.strain.begin(), r.strain.begin() + end);
    for (std::size_t k : piecewise_linear_knots(time, strain, 1e-6 * std::max(s.peak_strain, 1e-3))) {
      knots.time.push_back(time[k]);
      knots.strain.push_back(strain[k]);
    }
  }
  const double T = r.time[s.unload_end] - r.time[s.load_begin];
  const double peak = std::max(s.peak_stress, std::numeric_limits<double>::min());
  const double beta_max = o.beta_max_factor / T, alpha_max = o.alpha_max_factor;
  // Work in units of the peak stress so that the cost and the tolerances are O(1); alpha scales back.
  std::vector<double> y(measured.size());
  for (std::size_t q = 0; q < y.size(); ++q) y[q] = measured[q] / peak;

  // Deterministic starts: all M-subsets of the decay-rate grid, plus Table 2.
  std::vector<double> grid = o.start_decay_rates;
  if (grid.empty()) grid = {0.01 / T, 0.1 / T, 1.0 / T, 10.0 / T};
  std::vector<std::vector<cplx>> starts;
  std::vector<int> pick(M);
  std::function<void(int, int)> choose = [&](int depth, int from) {
    if (depth == M) {
      std::vector<cplx> b;
      for (int k : pick) b.emplace_back(grid[k], o.start_imag_ratio * grid[k]);
      starts.push_back(b);
      return;
    }
    for (int k = from; k < int(grid.size()); ++k) {
      pick[depth] = k;
      choose(depth + 1, k + 1);
    }
  };
  choose(0, 0);
  if (o.paper_start && M == 2) {
    std::vector<cplx> b;
    for (const auto& m : paper_table2_modes()) b.push_back(m.beta);
    starts.push_back(b);
  }

  // Stage 1 for every start: variable projection over the decay rates only (bounded).
  struct Projected {
    std::vector<cplx> betas;
    double cost;
  };
  std::vector<Projected> projected;
  for (const auto& betas : starts) {
    std::vector<double> b(2 * M);
    for (int i = 0; i < M; ++i) {
      b[2 * i] = std::clamp(betas[i].real(), 0.0, beta_max);
      b[2 * i + 1] = std::clamp(betas[i].imag(), 0.0, beta_max);
    }
    ceres::Problem problem;
    problem.AddResidualBlock(new ProjectedCost(knots, p, y, M), nullptr, b.data());
    for (int j = 0; j < 2 * M; ++j) {
      problem.SetParameterLowerBound(b.data(), j, 0.0);
      problem.SetParameterUpperBound(b.data(), j, beta_max);
    }
    ceres::Solver::Options so = solver_options(o);
    so.max_num_iterations = o.max_projected_iterations;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    std::vector<cplx> found;
    for (int i = 0; i < M; ++i) found.emplace_back(b[2 * i], b[2 * i + 1]);
    projected.push_back({found, summary.IsSolutionUsable() ? summary.final_cost : std::numeric_limits<double>::infinity()});
  }
  std::stable_sort(projected.begin(), projected.end(), [](const Projected& a, const Projected& b) { return a.cost < b.cost; });

  // Stage 2: all 4M parameters with the physical bounds on sigma_v (DifferenceStressCost), from the best
  // projected solutions and from the grid starts themselves (a projected solution may sit at beta -> 0, the
  // unbounded spring the bounds exclude); residues by linear least squares, clipped to the bounds.
  PairStress bounds;
  for (std::size_t q = 0; q < p.t1.size(); ++q) {
    bounds.loading.push_back(interpolate(r.time, r.stress, p.t1[q]) / peak);
    bounds.unloading.push_back(interpolate(r.time, r.stress, p.t2[q]) / peak);
  }
  std::vector<std::vector<cplx>> refine;
  for (std::size_t k = 0; k < projected.size() && k < std::size_t(std::max(1, o.refined_starts)); ++k)
    refine.push_back(projected[k].betas);
  const std::size_t projected_refines = refine.size();
  for (const auto& b : starts) refine.push_back(b);
  HereditaryFit best;
  best.starts = int(starts.size());
  double best_cost = std::numeric_limits<double>::infinity();
  bool best_bounded = false;  // a bound row is active at the best solution
  for (std::size_t k = 0; k < refine.size(); ++k) {
    // The grid starts only when the projected solutions end against the bounds.
    if (k == projected_refines && !best.modes.empty() && !best_bounded) break;
    const auto& betas = refine[k];
    std::vector<HereditaryMode> init = best_residues(knots, p, y, betas);
    std::vector<double> x(4 * M);
    for (int i = 0; i < M; ++i) {
      x[4 * i] = std::clamp(init[i].alpha.real(), -alpha_max, alpha_max);
      x[4 * i + 1] = std::clamp(init[i].alpha.imag(), -alpha_max, alpha_max);
      x[4 * i + 2] = std::clamp(init[i].beta.real(), 0.0, beta_max);
      x[4 * i + 3] = std::clamp(init[i].beta.imag(), 0.0, beta_max);
    }
    ceres::Problem problem;
    problem.AddResidualBlock(new DifferenceStressCost(knots, p, y, M, &bounds), nullptr, x.data());
    for (int i = 0; i < M; ++i) {
      for (int j = 0; j < 2; ++j) {
        problem.SetParameterLowerBound(x.data(), 4 * i + j, -alpha_max);
        problem.SetParameterUpperBound(x.data(), 4 * i + j, alpha_max);
        problem.SetParameterLowerBound(x.data(), 4 * i + 2 + j, 0.0);
        problem.SetParameterUpperBound(x.data(), 4 * i + 2 + j, beta_max);
      }
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options(o), &problem, &summary);
    if (summary.IsSolutionUsable() && summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      std::vector<double> res;
      problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &res, nullptr, nullptr);
      best_bounded = false;
      for (std::size_t q = y.size(); q < res.size(); ++q) best_bounded = best_bounded || res[q] != 0.0;
      best.modes.resize(M);
      for (int i = 0; i < M; ++i) best.modes[i] = {cplx(x[4 * i], x[4 * i + 1]) * peak, cplx(x[4 * i + 2], x[4 * i + 3])};
      best.report = summary.BriefReport();
    }
  }
  if (best.modes.empty()) throw std::runtime_error(r.source + ": hereditary fit failed from every start");
  best.modes = canonical(best.modes);
  best.measured = measured;
  best.model = model_difference_stress(r, p, best.modes);
  best.rmse = rmse(best.model, measured);
  best.rmse_relative = best.rmse / peak;
  return best;
}

}  // namespace cushion::calibration
