#include "material/calibration/refit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "material/hyperfoam.hpp"
#include "material/stability.hpp"

namespace cushion::calibration {

namespace {

/// What the residuals compare against, prepared once.
struct QuasiStaticSamples {
  QuasiStaticProtocol protocol;
  std::vector<double> times, stress;    ///< selected record samples (model time) and their stress [MPa]
  double weight = 0.0;                  ///< 1 / (peak sqrt(K tests))
};

struct Targets {
  LabSpecimen specimen;
  std::vector<QuasiStaticSamples> quasi_static;
  std::size_t quasi_static_residuals = 0;
  double preload = 0.0;
  DynamicModuli moduli;
  std::size_t hyperfoam_terms = 0;
  double nu = 0.0;
  std::vector<double> tau;
  std::optional<DynamicSchedule> schedule;
};

/// Parameter vector x = [mu_1..N, alpha_1..N, a_1..M].
std::vector<double> pack(const ViscoHyperfoam& m) {
  std::vector<double> x;
  for (const auto& t : m.terms) x.push_back(t.mu);
  for (const auto& t : m.terms) x.push_back(t.alpha);
  for (double a : long_term_ratios(m.prony)) x.push_back(a);
  return x;
}

ViscoHyperfoam unpack(const Targets& g, const double* x) {
  ViscoHyperfoam m;
  const std::size_t N = g.hyperfoam_terms;
  for (std::size_t i = 0; i < N; ++i) m.terms.push_back({x[i], x[N + i], g.nu});
  m.prony = prony_from_long_term_ratios(std::vector<double>(x + 2 * N, x + 2 * N + g.tau.size()), g.tau);
  return m;
}

std::size_t residual_count(const Targets& g) { return g.quasi_static_residuals + 2 * g.moduli.frequency.size(); }

/// Residuals of the parameters x; false if the model fails (non-physical parameters).
bool residuals(const Targets& g, const double* x, double* r, std::string* why = nullptr) {
  try {
    const ViscoHyperfoam m = unpack(g, x);
    const auto model = build_model(m);
    const material::Hyperfoam base(m.terms);
    std::size_t o = 0;
    for (const QuasiStaticSamples& q : g.quasi_static) {
      const QuasiStaticRecord run = run_quasi_static(*model, g.specimen, q.protocol);
      std::vector<double> sigma;
      for (double f : run.force_N) sigma.push_back(f / g.specimen.area());
      for (std::size_t k = 0; k < q.times.size(); ++k)
        r[o++] = (interpolate(run.time_s, sigma, q.times[k]) - q.stress[k]) * q.weight;
    }
    const DynamicModuli d = model_dynamic_moduli(*model, base, g.preload, g.moduli.frequency, Lateral::free,
                                                 g.schedule ? &*g.schedule : nullptr);
    const std::size_t F = d.frequency.size();
    const double wd = 1.0 / std::sqrt(2.0 * F);
    for (std::size_t i = 0; i < F; ++i) {
      r[o + 2 * i] = (d.storage[i] / g.moduli.storage[i] - 1.0) * wd;
      r[o + 2 * i + 1] = (d.loss[i] / g.moduli.loss[i] - 1.0) * wd;
    }
    for (std::size_t k = 0; k < residual_count(g); ++k)
      if (!std::isfinite(r[k])) return false;
    return true;
  } catch (const std::exception& e) {
    if (why) *why = e.what();
    return false;
  }
}

/// One residual block: all residuals, forward-difference Jacobian with parallel columns.
class JointCost final : public ceres::CostFunction {
 public:
  JointCost(const Targets& g, std::size_t n, int threads, const std::vector<double>& lower,
            const std::vector<double>& upper, int& evaluations)
      : g_(g), n_(n), threads_(std::max(1, threads)), lower_(lower), upper_(upper), evaluations_(evaluations) {
    set_num_residuals(static_cast<int>(residual_count(g)));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(n));
  }

  bool Evaluate(double const* const* parameters, double* r, double** jacobians) const override {
    const double* x = parameters[0];
    ++evaluations_;
    if (!residuals(g_, x, r)) return false;
    if (!jacobians || !jacobians[0]) return true;
    const std::size_t m = residual_count(g_);
    double* J = jacobians[0];  // row-major m x n
    std::vector<char> ok(n_, 1);
    auto column = [&](std::size_t j) {
      std::vector<double> xp(x, x + n_), rp(m);
      double h = 1e-6 * std::max(std::abs(x[j]), 1e-3);
      if (x[j] + h > upper_[j]) h = -h;  // stay inside the bounds
      xp[j] += h;
      if (!residuals(g_, xp.data(), rp.data())) {
        ok[j] = 0;
        return;
      }
      for (std::size_t k = 0; k < m; ++k) J[k * n_ + j] = (rp[k] - r[k]) / h;
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads_; ++t)
      pool.emplace_back([&, t] {
        for (std::size_t j = t; j < n_; j += threads_) column(j);
      });
    for (std::size_t j = 0; j < n_; j += threads_) column(j);
    for (auto& th : pool) th.join();
    evaluations_ += static_cast<int>(n_);
    return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
  }

 private:
  const Targets& g_;
  std::size_t n_;
  int threads_;
  std::vector<double> lower_, upper_;
  int& evaluations_;
};

/// A Drucker-stable hyperfoam (every mu_i alpha_i > 0) close to `terms` over nominal compression
/// 0..peak: fixed positive alphas, mu by linear least squares on the curve of `terms`, clamped >= 0.
std::vector<material::HyperfoamTerm> stable_start(const std::vector<material::HyperfoamTerm>& terms, double peak) {
  static const double pattern[] = {2.0, 8.0, 20.0, 1.0, 4.0, 40.0};
  const double nu = terms.front().nu;
  std::vector<double> eps;
  for (int i = 1; i <= 40; ++i) eps.push_back(peak * i / 40.0);
  const auto y = hyperfoam_uniaxial_stress(terms, nu, Lateral::free, eps);
  const std::size_t N = terms.size();
  Eigen::MatrixXd A(eps.size(), N);
  Eigen::VectorXd b(eps.size());
  for (std::size_t j = 0; j < N; ++j) {
    const auto col = hyperfoam_uniaxial_stress({{1.0, pattern[j], nu}}, nu, Lateral::free, eps);
    for (std::size_t i = 0; i < eps.size(); ++i) A(i, j) = col[i];
  }
  for (std::size_t i = 0; i < eps.size(); ++i) b(i) = y[i];
  const Eigen::VectorXd mu = A.colPivHouseholderQr().solve(b);
  double scale = 0.0;
  for (std::size_t j = 0; j < N; ++j) scale = std::max(scale, std::abs(mu(j)));
  std::vector<material::HyperfoamTerm> out;
  for (std::size_t j = 0; j < N; ++j) out.push_back({std::max(mu(j), 1e-3 * scale), pattern[j], nu});
  return out;
}

double rms_of(const double* r, std::size_t begin, std::size_t end) {
  double s = 0.0;
  for (std::size_t k = begin; k < end; ++k) s += r[k] * r[k];
  return std::sqrt(s);  // residuals already carry 1/sqrt(count)
}

}  // namespace

RefitResult refit(const ViscoHyperfoam& start, const Specimen& specimen, const std::vector<QuasiStaticTarget>& quasi_static,
                  const DynamicTest& dynamic, const RefitOptions& options) {
  const auto clock0 = std::chrono::steady_clock::now();
  if (quasi_static.empty()) throw std::invalid_argument("refit: no quasi-static test");
  Targets g;
  g.specimen = LabSpecimen{specimen.length, specimen.width, specimen.thickness, 65.0};
  double peak_strain = 0.0;
  for (const QuasiStaticTarget& target : quasi_static) {
    const QuasiStaticTest& test = *target.test;
    const Segments& segments = target.segments;
    QuasiStaticSamples q;
    q.protocol = protocol_of(test, segments, std::min(options.max_sample_hz, sampling_rate(test.record)));
    const StressStrainRecord& rec = test.record;
    const double strain_rate = test.rate / specimen.thickness;
    const double t0 = rec.time[segments.load_begin] - rec.strain[segments.load_begin] / strain_rate;
    const double t_end = 2.0 * q.protocol.max_strain / strain_rate + q.protocol.hold_s;
    std::vector<std::size_t> usable;
    for (std::size_t i = segments.load_begin; i < rec.time.size(); ++i)
      if (rec.time[i] - t0 <= t_end + 1e-9) usable.push_back(i);
    const std::size_t K = std::min<std::size_t>(usable.size(), std::max(10, options.max_quasi_static_points));
    for (std::size_t k = 0; k < K; ++k) {
      const std::size_t i = usable[(k * (usable.size() - 1)) / std::max<std::size_t>(1, K - 1)];
      q.times.push_back(rec.time[i] - t0);
      q.stress.push_back(rec.stress[i]);
    }
    q.weight = 1.0 / (segments.peak_stress * std::sqrt(static_cast<double>(K * quasi_static.size())));
    g.quasi_static_residuals += K;
    g.quasi_static.push_back(std::move(q));
    peak_strain = std::max(peak_strain, segments.peak_strain);
  }
  g.preload = dynamic.preload_strain;
  g.schedule = options.schedule;
  g.moduli = dynamic.moduli;
  g.hyperfoam_terms = start.terms.size();
  g.nu = start.terms.front().nu;
  for (const auto& t : start.prony) g.tau.push_back(t.tau);
  RefitResult result;
  result.start = start;
  result.material = start;
  // An unstable start (the paper's hyperfoam may be) can fail in the driver: start from a stable one.
  ViscoHyperfoam first = start;
  if (!material::check_stability(material::Hyperfoam(start.terms), -peak_strain, options.stability_tension).stable()) {
    first.terms = stable_start(start.terms, peak_strain);
    result.started_stable = true;
  }
  std::vector<double> x = pack(first);
  const std::size_t n = x.size(), N = g.hyperfoam_terms, m = residual_count(g);
  std::vector<double> lower(n), upper(n);
  double mu_scale = 0.0;
  for (std::size_t i = 0; i < N; ++i) mu_scale = std::max(mu_scale, std::abs(x[i]));
  for (std::size_t i = 0; i < N; ++i) {
    lower[i] = -10.0 * mu_scale;
    upper[i] = 10.0 * mu_scale;
    const double s = x[N + i] >= 0.0 ? 1.0 : -1.0;
    lower[N + i] = s > 0 ? 0.2 : -50.0;
    upper[N + i] = s > 0 ? 50.0 : -0.2;
  }
  for (std::size_t i = 2 * N; i < n; ++i) {
    lower[i] = 0.0;
    upper[i] = 1e3;
  }
  for (std::size_t i = 0; i < n; ++i) x[i] = std::clamp(x[i], lower[i], upper[i]);

  std::vector<double> r(m);
  if (std::string why; !residuals(g, x.data(), r.data(), &why)) {
    result.report = "the start material fails in the point driver: " + why;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
    return result;
  }
  result.quasi_static_rms_start = rms_of(r.data(), 0, g.quasi_static_residuals);
  result.dynamic_rms_start = rms_of(r.data(), g.quasi_static_residuals, m);
  result.cost_start = 0.5 * (std::pow(result.quasi_static_rms_start, 2) + std::pow(result.dynamic_rms_start, 2));

  ceres::Problem problem;
  problem.AddResidualBlock(new JointCost(g, n, options.threads, lower, upper, result.evaluations), nullptr, x.data());
  for (std::size_t i = 0; i < n; ++i) {
    problem.SetParameterLowerBound(x.data(), static_cast<int>(i), lower[i]);
    problem.SetParameterUpperBound(x.data(), static_cast<int>(i), upper[i]);
  }
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = options.max_iterations;
  so.function_tolerance = options.function_tolerance;
  so.gradient_tolerance = options.gradient_tolerance;
  so.parameter_tolerance = options.parameter_tolerance;
  so.logging_type = ceres::SILENT;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  result.report = summary.BriefReport();
  result.iterations = static_cast<int>(summary.iterations.size());
  result.converged = summary.IsSolutionUsable();

  if (result.converged && residuals(g, x.data(), r.data())) {
    result.quasi_static_rms = rms_of(r.data(), 0, g.quasi_static_residuals);
    result.dynamic_rms = rms_of(r.data(), g.quasi_static_residuals, m);
    result.cost = 0.5 * (std::pow(result.quasi_static_rms, 2) + std::pow(result.dynamic_rms, 2));
    result.material = unpack(g, x.data());
  } else {
    result.converged = false;
    result.quasi_static_rms = result.quasi_static_rms_start;
    result.dynamic_rms = result.dynamic_rms_start;
    result.cost = result.cost_start;
  }
  result.improved = result.cost < result.cost_start;
  const material::Hyperfoam refitted(result.material.terms);
  result.stable = material::check_stability(refitted, -peak_strain, options.stability_tension).stable();
  result.stability = material::check_stability(refitted).summary();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  return result;
}

}  // namespace cushion::calibration
