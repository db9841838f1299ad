#include "calibration/hyperfoam_modes_fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "calibration/ceres_options.hpp"
#include "calibration/exponent_grid.hpp"
#include "calibration/prony_fit.hpp"
#include "material/stability.hpp"

namespace cushion::calibration {
namespace {

/// Normalisation of one test's residuals: its peak stress [MPa] and lateral range [-].
struct TestScale {
  double peak = 1.0, lateral_range = 1.0;
};

std::vector<TestScale> test_scales(const std::vector<HyperfoamTest>& tests) {
  std::vector<TestScale> out;
  for (const auto& t : tests) {
    TestScale s{0.0, 0.0};
    for (double p : t.stress) s.peak = std::max(s.peak, std::abs(p));
    for (double l : t.lateral) s.lateral_range = std::max(s.lateral_range, std::abs(l - 1.0));
    if (!(s.peak > 0.0)) s.peak = 1.0;
    if (!(s.lateral_range > 1e-6)) s.lateral_range = 1e-6;
    out.push_back(s);
  }
  return out;
}

/// Residuals of the objective (header) for parameters p[0] = mu/scale (N), p[1] = alpha (N), p[2] = nu (N or 1).
struct ModesResidual {
  const std::vector<HyperfoamTest>* tests;
  std::vector<TestScale> scales;
  double weight, scale;
  int N;
  bool common_nu;
  std::vector<std::pair<HyperfoamMode, double>> probes;  ///< Drucker penalty states (mode, stretch); empty: none
  double penalty = 0.0, margin = 0.0;                      ///< weight and required margin of the scaled measures
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    T mu[6], nu[6];
    for (int i = 0; i < N; ++i) {
      mu[i] = p[0][i] * scale;
      nu[i] = common_nu ? p[2][0] : p[2][i];
    }
    const HyperfoamTermsView<T> v{mu, p[1], nu, N};
    int k = 0;
    for (std::size_t t = 0; t < tests->size(); ++t) {
      const HyperfoamTest& test = (*tests)[t];
      for (std::size_t j = 0; j < test.control.size(); ++j) {
        const ModeResponse<T> m = mode_response(v, test.mode, test.control[j]);
        if (!m.ok) return false;
        r[k++] = (m.stress - test.stress[j]) / scales[t].peak;
        if (!test.lateral.empty()) r[k++] = weight * (m.lateral - test.lateral[j]) / scales[t].lateral_range;
        if (!detail::all_finite(r[k - 1]) || !detail::all_finite(m.stress)) return false;
      }
    }
    for (const auto& [mode, x] : probes) {
      T q[6];
      if (!drucker_measures(v, mode, x, scale, q)) return false;
      for (int a = 0; a < 6; ++a) {
        const T short_of = T(margin) - q[a];
        r[k++] = detail::value_of(short_of) > 0.0 ? penalty * short_of : T(0.0);
        if (!detail::all_finite(q[a])) return false;
      }
    }
    return true;
  }
  /// The data's part of every residual (residual = model part - data part).
  std::vector<double> data_part() const {
    std::vector<double> d;
    for (std::size_t t = 0; t < tests->size(); ++t)
      for (std::size_t j = 0; j < (*tests)[t].control.size(); ++j) {
        d.push_back((*tests)[t].stress[j] / scales[t].peak);
        if (!(*tests)[t].lateral.empty()) d.push_back(weight * (*tests)[t].lateral[j] / scales[t].lateral_range);
      }
    return d;
  }
  /// Which residuals are lateral-stretch ones (in residual order).
  std::vector<bool> lateral_rows() const {
    std::vector<bool> rows;
    for (const auto& t : *tests)
      for (std::size_t j = 0; j < t.control.size(); ++j) {
        rows.push_back(false);
        if (!t.lateral.empty()) rows.push_back(true);
      }
    return rows;
  }
  int residuals() const {
    int n = 0;
    for (const auto& t : *tests) n += int(t.control.size() * (t.lateral.empty() ? 1 : 2));
    return n + 6 * int(probes.size());
  }
};

struct Candidate {
  double cost;
  std::vector<double> mu, alpha, nu;  ///< mu in units of the scale; nu: N values (or 1 when common)
  bool non_negative;
};

std::vector<material::HyperfoamTerm> to_terms(const Candidate& c, double scale) {
  std::vector<material::HyperfoamTerm> t;
  for (std::size_t i = 0; i < c.mu.size(); ++i) t.push_back({c.mu[i] * scale, c.alpha[i], c.nu.size() == 1 ? c.nu[0] : c.nu[i]});
  return t;
}

/// Objective of a candidate with every free stretch solved (NaN when a point has no solution).
double candidate_cost(const ModesResidual& f, const Candidate& c) {
  std::vector<double> r(std::size_t(f.residuals()));
  const double* p[3] = {c.mu.data(), c.alpha.data(), c.nu.data()};
  if (!f(p, r.data())) return std::nan("");
  double sum = 0.0;
  for (double x : r) sum += x * x;
  return 0.5 * sum;
}

/// Step 1: the common-nu screen, exponent subsets with linear mu (header).
struct Screen {
  std::vector<Candidate> non_negative, free;
  int starts = 0;
};

void keep_best(std::vector<Candidate>& list, Candidate c, std::size_t keep) {
  for (const auto& other : list)
    if (other.alpha == c.alpha && other.nu == c.nu) return;
  list.push_back(std::move(c));
  std::sort(list.begin(), list.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  if (list.size() > keep) list.pop_back();
}

Screen screen(const ModesResidual& f, const HyperfoamFitSettings& s, const std::vector<double>& nus) {
  const std::vector<double> grid = alpha_grid(f.N, s.alpha_max);

  const auto combos = subsets(int(grid.size()), f.N);
  const std::size_t keep = std::size_t(std::max(1, s.polished));
  Screen out;
  for (double nu : nus) {
    // Columns: every residual of a one-term material (mu = scale) minus the data part, i.e. the model part.
    ModesResidual one = f;
    one.N = 1;
    one.common_nu = true;
    one.probes.clear();  // one term with mu > 0, nu >= 0 is stable
    const int rows = one.residuals();
    Eigen::MatrixXd columns(rows, Eigen::Index(grid.size()));
    Eigen::VectorXd y(rows), lateral(rows);
    std::vector<double> r(static_cast<std::size_t>(rows));
    const std::vector<double> data = one.data_part();
    for (int k = 0; k < rows; ++k) y(k) = data[std::size_t(k)];
    bool usable = true;
    for (std::size_t g = 0; g < grid.size(); ++g) {
      std::vector<double> unit{1.0};
      const double* p[3] = {unit.data(), &grid[g], &nu};
      usable = usable && one(p, r.data());
      for (int k = 0; k < rows; ++k) columns(k, Eigen::Index(g)) = r[std::size_t(k)] + y(k);
    }
    if (!usable) continue;
    // Lateral rows do not depend on mu (common nu): their model part is constant, moved into y.
    const std::vector<bool> lateral_row = one.lateral_rows();
    for (int k = 0; k < rows; ++k) lateral(k) = lateral_row[std::size_t(k)] ? columns(k, 0) : 0.0;
    for (int k = 0; k < rows; ++k)
      if (lateral_row[std::size_t(k)]) columns.row(k).setZero();
    for (const auto& combo : combos) {
      ++out.starts;
      Eigen::MatrixXd A(rows, f.N);
      std::vector<double> alpha(std::size_t(f.N));
      for (int i = 0; i < f.N; ++i) {
        A.col(i) = columns.col(combo[std::size_t(i)]);
        alpha[std::size_t(i)] = grid[std::size_t(combo[std::size_t(i)])];
      }
      const Eigen::VectorXd b = y - lateral;
      const Eigen::VectorXd m_nn = non_negative_least_squares(A, b);
      const double cost_nn = 0.5 * (A * m_nn - b).squaredNorm();
      const std::vector<double> nu_start(s.per_term_nu ? std::size_t(f.N) : 1, nu);
      if (std::isfinite(cost_nn) && m_nn.maxCoeff() > 0.0)
        keep_best(out.non_negative, {cost_nn, std::vector<double>(m_nn.data(), m_nn.data() + f.N), alpha, nu_start, true}, keep);
      const Eigen::VectorXd m_ls = A.colPivHouseholderQr().solve(b);
      const double cost_ls = 0.5 * (A * m_ls - b).squaredNorm();
      if (m_ls.allFinite() && m_ls.minCoeff() < 0.0 && std::isfinite(cost_ls) && cost_ls < cost_nn)
        keep_best(out.free, {cost_ls, std::vector<double>(m_ls.data(), m_ls.data() + f.N), alpha, nu_start, false}, keep);
    }
  }
  return out;
}

/// Step 2: Ceres polish of one start; empty cost (NaN) when the solve is unusable.
Candidate polish(const ModesResidual& f, const HyperfoamFitSettings& s, Candidate c) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<ModesResidual, 4>(new ModesResidual(f));
  cost->AddParameterBlock(f.N);
  cost->AddParameterBlock(f.N);
  cost->AddParameterBlock(int(c.nu.size()));
  cost->SetNumResiduals(f.residuals());
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, c.mu.data(), c.alpha.data(), c.nu.data());
  for (int i = 0; i < f.N; ++i) {
    if (c.non_negative) problem.SetParameterLowerBound(c.mu.data(), i, 0.0);
    const bool up = c.alpha[std::size_t(i)] > 0.0;
    problem.SetParameterLowerBound(c.alpha.data(), i, up ? s.alpha_min : -s.alpha_max);
    problem.SetParameterUpperBound(c.alpha.data(), i, up ? s.alpha_max : -s.alpha_min);
  }
  for (int i = 0; i < int(c.nu.size()); ++i) {
    problem.SetParameterLowerBound(c.nu.data(), i, 0.0);
    problem.SetParameterUpperBound(c.nu.data(), i, s.nu_max);
  }
  ceres::Solver::Summary summary;
  ceres::Solver::Options options = dense_fit_options({1e-14, 1e-14, 1e-12, 1000});
  options.max_num_consecutive_invalid_steps = 1000;  // a trial step where a free stretch has no root is only rejected
  ceres::Solve(options, &problem, &summary);
  c.cost = summary.IsSolutionUsable() ? candidate_cost(f, c) : std::nan("");
  return c;
}

constexpr HyperfoamMode kStabilityModes[4] = {HyperfoamMode::uniaxial, HyperfoamMode::equibiaxial, HyperfoamMode::planar,
                                             HyperfoamMode::volumetric};  // material::StabilityMode order

/// The Drucker penalty states: each mode at 16 stretches from its lower stable stretch to 1 and 8 from 1 to its upper,
/// geometric (the final check, material/stability.hpp, is finer).
std::vector<std::pair<HyperfoamMode, double>> drucker_probes(const StableStretch& ranges) {
  std::vector<std::pair<HyperfoamMode, double>> out;
  for (int m = 0; m < 4; ++m) {
    for (int k = 0; k < 16; ++k) out.push_back({kStabilityModes[m], std::pow(ranges[std::size_t(m)].first, 1.0 - k / 16.0)});
    for (int k = 1; k <= 8; ++k) out.push_back({kStabilityModes[m], std::pow(ranges[std::size_t(m)].second, k / 8.0)});
  }
  return out;
}

}  // namespace

std::string describe(const StableStretch& r) {
  const char* names[4] = {"uniaxial", "equibiaxial", "planar", "volumetric"};
  std::ostringstream o;
  for (std::size_t m = 0; m < 4; ++m) o << (m ? ", " : "") << names[m] << " [" << r[m].first << ", " << r[m].second << "]";
  return o.str();
}

namespace {

std::string join(const std::vector<double>& v) {
  std::ostringstream o;
  for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
  return o.str();
}

}  // namespace

HyperfoamTestFigures evaluate_hyperfoam_test(const std::vector<material::HyperfoamTerm>& terms, const HyperfoamTest& test) {
  std::vector<double> mu, alpha, nu;
  for (const auto& t : terms) mu.push_back(t.mu), alpha.push_back(t.alpha), nu.push_back(t.nu);
  const HyperfoamTermsView<double> v{mu.data(), alpha.data(), nu.data(), int(terms.size())};
  HyperfoamTestFigures f;
  double peak = 0.0, mean = 0.0, ss_res = 0.0, ss_tot = 0.0, lat2 = 0.0;
  for (double p : test.stress) peak = std::max(peak, std::abs(p)), mean += p / double(test.stress.size());
  for (std::size_t j = 0; j < test.control.size(); ++j) {
    const ModeResponse<double> m = mode_response(v, test.mode, test.control[j]);
    f.ok = f.ok && m.ok;
    f.stress.push_back(m.stress);
    f.lateral.push_back(m.lateral);
    const double d = m.stress - test.stress[j];
    ss_res += d * d;
    ss_tot += (test.stress[j] - mean) * (test.stress[j] - mean);
    f.max = std::max(f.max, std::abs(d) / peak);
    if (!test.lateral.empty()) {
      const double e = m.lateral / test.lateral[j] - 1.0;
      f.lateral_max = std::max(f.lateral_max, std::abs(e));
      lat2 += e * e;
    }
  }
  const double n = double(test.control.size());
  f.r2 = ss_tot > 0.0 ? 1.0 - ss_res / ss_tot : std::nan("");
  f.rms = std::sqrt(ss_res / n) / peak;
  if (!test.lateral.empty()) f.lateral_rms = std::sqrt(lat2 / n);
  return f;
}

StableStretch default_stable_stretch(const std::vector<HyperfoamTest>& tests) {
  std::array<double, 4> lo{1.0, 1.0, 1.0, 1.0}, hi{1.0, 1.0, 1.0, 1.0};
  std::array<bool, 4> tested{};
  for (const auto& t : tests) {
    const bool shear = t.mode == HyperfoamMode::simple_shear;
    const std::size_t m = shear ? 2 : std::size_t(std::find(kStabilityModes, kStabilityModes + 4, t.mode) - kStabilityModes);
    tested[m] = true;
    for (double x : t.control) {
      const double l = shear ? std::sqrt(1.0 + 0.25 * x * x) + 0.5 * std::abs(x) : x;  // shear: l and 1/l
      lo[m] = std::min(lo[m], shear ? 1.0 / l : l);
      hi[m] = std::max(hi[m], l);
    }
  }
  StableStretch r;
  std::pair<double, double> narrowest{0.0, 1e300};
  for (std::size_t m = 0; m < 4; ++m)
    if (tested[m]) {
      r[m] = {0.8 * lo[m], std::max(1.5, 1.2 * hi[m])};
      narrowest = {std::max(narrowest.first, r[m].first), std::min(narrowest.second, r[m].second)};
    }
  for (std::size_t m = 0; m < 4; ++m)
    if (!tested[m]) r[m] = narrowest;
  return r;
}

bool stable_over(const material::Hyperelastic& model, const StableStretch& ranges) {
  double lo = 1.0, hi = 1.0;
  for (const auto& [a, b] : ranges) lo = std::min(lo, a), hi = std::max(hi, b);
  const material::StabilityReport report = material::check_stability(model, lo - 1.0, hi - 1.0);
  for (std::size_t m = 0; m < 4 && m < report.modes.size(); ++m) {
    const auto& mode = report.modes[m];
    if (mode.first_unstable_compression && *mode.first_unstable_compression >= ranges[m].first - 1.0) return false;
    if (mode.first_unstable_tension && *mode.first_unstable_tension <= ranges[m].second - 1.0) return false;
  }
  return true;
}

HyperfoamModesFit fit_hyperfoam_modes(const std::vector<HyperfoamTest>& tests, const HyperfoamFitSettings& s) {
  const int N = s.terms;
  if (N < 1 || N > 6) throw std::invalid_argument("fit_hyperfoam_modes: terms must be 1..6");
  HyperfoamModesFit fit;
  const std::vector<TestScale> scales = test_scales(tests);
  double scale = 0.0;
  for (const auto& t : scales) scale = std::max(scale, t.peak);
  fit.stable_stretch = default_stable_stretch(tests);
  if (s.stable_stretch) fit.stable_stretch.fill(*s.stable_stretch);
  ModesResidual f{&tests, scales, s.lateral_weight, scale, N, !s.per_term_nu, {}, 0.0, 0.0};
  f.probes = drucker_probes(fit.stable_stretch);
  f.penalty = 100.0;
  f.margin = 0.0;

  for (int k = 0; k < 10; ++k) fit.nu_screen.push_back(0.05 * k);

  // 1. Screen.
  const Screen scr = screen(f, s, fit.nu_screen);
  fit.starts = scr.starts;
  // 2. Polish every kept start; the start itself stays a candidate (fallback when its polish is unstable).
  std::vector<Candidate> finals;
  for (const auto* list : {&scr.non_negative, &scr.free})
    for (const Candidate& start : *list) {
      if (!std::isfinite(candidate_cost(f, start))) continue;  // a free stretch without root: nothing to polish
      Candidate c = polish(f, s, start);
      ++fit.polishes;
      if (std::isfinite(c.cost)) finals.push_back(std::move(c));
      Candidate fallback = start;
      fallback.cost = candidate_cost(f, start);
      if (std::isfinite(fallback.cost)) finals.push_back(std::move(fallback));
    }
  std::stable_sort(finals.begin(), finals.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  // 3. The best Drucker-stable candidate.
  auto stable = [&](const Candidate& c) {
    double sum = 0.0;
    for (double m : c.mu) sum += m;
    return sum > 0.0 && stable_over(material::Hyperfoam(to_terms(c, scale)), fit.stable_stretch);
  };
  const Candidate* chosen = nullptr;
  for (const auto& c : finals) {
    if (stable(c)) {
      chosen = &c;
      break;
    }
    ++fit.rejected_unstable;
  }
  if (!chosen) {
    std::ostringstream msg;
    msg << "fit: no Drucker-stable " << N << "-term hyperfoam over stretch " << describe(fit.stable_stretch) << ": screened "
        << fit.starts << " exponent subsets x common nu {" << join(fit.nu_screen) << "}, polished " << fit.polishes
        << " starts; all " << finals.size() << " candidates unstable";
    throw std::runtime_error(msg.str());
  }
  if (fit.rejected_unstable > 0)
    fit.warnings.push_back(std::to_string(fit.rejected_unstable) + " better fit(s) rejected as Drucker-unstable");
  fit.terms = to_terms(*chosen, scale);
  fit.cost = chosen->cost;
  for (const auto& t : tests) fit.tests.push_back(evaluate_hyperfoam_test(fit.terms, t));
  double lo = 1.0, hi = 1.0;
  for (const auto& [a, b] : fit.stable_stretch) lo = std::min(lo, a), hi = std::max(hi, b);
  fit.stability = material::check_stability(material::Hyperfoam(fit.terms), lo - 1.0, hi - 1.0).summary();
  return fit;
}

}  // namespace cushion::calibration
