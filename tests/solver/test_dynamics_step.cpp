// The "dynamic" case step end to end (load_case + run_analysis):
//  (1) a neo-Hookean hex8 column, laterally confined (a 1D bar), base shaken by a sine amplitude
//      from rest: the top displacement history matches the closed-form modal solution of the 1D
//      chain (element stiffness (lambda + 2 mu) A / h, consistent mass rho A h / 6 [2 1; 1 2]);
//  (2) visco preload, steady_state sweep and a dynamic step driven by the same small base sine in
//      one case: the reaction reaches the sweep's steady amplitude and phase (Prony + Rayleigh on);
//  (3) free vibration after a static pull, undamped average-acceleration rule: kinetic energy plus
//      internal work is conserved, gamma = 0.6 dissipates, and splitting the step in two (velocity
//      carried) gives the same motion;
//  (4) bad input names the key; plus the amplitude derivatives the step uses;
//  (5) HHT-alpha (alpha = -0.1): the bar of (1) matches the HHT rule applied to the 1D chain in the
//      test (a separate integration of M a1 + (1 + alpha) G1 - alpha G0 = 0) to 2e-5 of the peak,
//      while differing from the plain rule by far more (the test can tell the two apart).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "io/input_error.hpp"
#include "solver/analysis/dynamic_step.hpp"
#include "test_run_support.hpp"

namespace cushion::solver::test {
namespace {

using json = nlohmann::json;
using cplx = std::complex<double>;

fs::path write_json(const fs::path& file, const json& j) { return write_text(file, j.dump(2)); }

/// Column [0,10]^2 x [0,L] of nz hex8, sets all/base/top; Newton tolerances `tolerance` (relative).
json column_case(double L, int nz, const json& steps, double tolerance = 1e-10) {
  return {{"mesh", {{"generate", {{"type", "hex8"}, {"box_mm", {0, 10, 0, 10, 0, L}}, {"elements", {1, 1, nz}}}}}},
          {"material", {{"file", "material.json"}}},
          {"sets", {{"all", "all"}, {"base", "z == 0"}, {"top", "z == " + std::to_string(L)}}},
          {"solver", {{"residual_tolerance", tolerance}, {"correction_tolerance", tolerance}, {"threads", 1}}},
          {"steps", steps}};
}

json lateral() { return json::array({{{"set", "all"}, {"type", "symmetry_x"}}, {{"set", "all"}, {"type", "symmetry_y"}}}); }

json with(json list, const json& entry) {
  list.push_back(entry);
  return list;
}

/// Fixed-increment dynamic step.
json dynamic_step(const std::string& name, double period, double dt, const json& boundary) {
  return {{"name", name}, {"type", "dynamic"}, {"time_period_s", period},
          {"increment", {{"initial_s", dt}, {"max_s", dt}, {"fixed", true}, {"max_increments", 100000}}},
          {"boundary", boundary},
          {"output", {{"frames_every_s", period}, {"history", {{{"set", "top"}, {"quantities", {"U3", "RF3"}}},
                                                               {{"set", "base"}, {"quantities", {"RF3"}}}}}}}};
}

const std::vector<double>& col(const CsvTable& t, const std::string& name) { return t.col(name); }

// (1) ------------------------------------------------------------------------------------------
TEST(DynamicStep, BarUnderSineBaseMotionMatchesModalSolution) {
  const fs::path dir = scratch_dir();
  const double mu = 0.010, lambda = 0.020, rho = 6.5e-11;  // [MPa], [t/mm^3]
  write_text(dir / "material.json", R"({"density_kg_m3": 65, "neo_hookean": {"mu_kPa": 10, "lambda_kPa": 20}})");
  const int N = 10;
  const double L = 100.0, h = L / N, A = 100.0, U = 1e-3, f = 20.0, Omega = 2 * M_PI * f;  // first mode ~62 Hz
  const double T = 0.1, dt = 1e-4;
  json amplitudes = {{"drive", {{"type", "sine"}, {"frequency_Hz", f}}}};
  json steps = json::array({dynamic_step(
      "shake", T, dt, with(lateral(), {{"set", "base"}, {"dof", "z"}, {"value_mm", U}, {"amplitude", "drive"}}))});
  json c = column_case(L, N, steps, 1e-8);  // forces ~1e-5 N: 1e-10 would be below round-off
  c["amplitudes"] = amplitudes;
  run_case(write_json(dir / "case.json", c), dir / "out");
  const CsvTable hist = read_history(dir / "out");

  // Closed form: 1D chain, free nodes 1..N, base node 0 driven by U sin(Omega t), from rest.
  const double k = (lambda + 2 * mu) * A / h, m = rho * A * h / 6.0;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N), M = Eigen::MatrixXd::Zero(N, N);
  for (int e = 0; e < N; ++e) {  // element between nodes e and e+1 (free index e-1, e)
    const int i = e - 1, j = e;
    if (i >= 0) K(i, i) += k, M(i, i) += 2 * m, K(i, j) -= k, K(j, i) -= k, M(i, j) += m, M(j, i) += m;
    K(j, j) += k, M(j, j) += 2 * m;
  }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(N);
  b(0) = (k + Omega * Omega * m) * U;  // -(K_fb - Omega^2 M_fb) U with K_fb = -k, M_fb = m
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(K, M);  // phi^T M phi = I
  const Eigen::VectorXd omega = modes.eigenvalues().cwiseSqrt();
  std::printf("  first mode %.3f Hz, drive %.1f Hz\n", omega(0) / (2 * M_PI), f);
  auto top_exact = [&](double t) {
    double u = 0.0;
    for (int i = 0; i < N; ++i) {
      const double p = modes.eigenvectors().col(i).dot(b), w = omega(i);
      u += modes.eigenvectors()(N - 1, i) * p / (w * w - Omega * Omega) * (std::sin(Omega * t) - Omega / w * std::sin(w * t));
    }
    return u;
  };
  // The same average-acceleration rule applied to the 1D chain (a second, independent integration).
  Eigen::MatrixXd u_chain(N, 1 + static_cast<Eigen::Index>(std::lround(T / dt)));
  {
    const double c_a = 4.0 / (dt * dt);
    const Eigen::LDLT<Eigen::MatrixXd> S(K + c_a * M);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(N), v = q, a = q;  // a(0) = 0: the base starts at u = a = 0
    u_chain.col(0) = q;
    for (Eigen::Index i = 1; i < u_chain.cols(); ++i) {
      const Eigen::VectorXd rhs = b * std::sin(Omega * i * dt) + M * (c_a * q + 4.0 / dt * v + a);
      const Eigen::VectorXd q_new = S.solve(rhs), a_new = c_a * (q_new - q) - 4.0 / dt * v - a;
      v += 0.5 * dt * (a + a_new), a = a_new, q = q_new;
      u_chain.col(i) = q;
    }
  }
  const auto& t = col(hist, "time_s");
  const auto& u_top = col(hist, "top.U3_mm");
  ASSERT_EQ(t.size(), static_cast<std::size_t>(u_chain.cols()));
  double err = 0.0, err_chain = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    err = std::max(err, std::abs(u_top[i] - top_exact(t[i])));
    err_chain = std::max(err_chain, std::abs(u_top[i] - u_chain(N - 1, static_cast<Eigen::Index>(i))));
    peak = std::max(peak, std::abs(top_exact(t[i])));
  }
  std::printf("  top displacement: peak %.4e mm, max error vs closed form %.3e mm (%.3f %% of peak), vs the "
              "Newmark chain %.3e mm\n", peak, err, 100 * err / peak, err_chain);
  EXPECT_GT(peak, 1.5 * U);  // the dynamic amplification is visible
  // Same rule, same discrete model: equal up to the Newton tolerance and geometric nonlinearity (strain 2e-5).
  EXPECT_LT(err_chain, 2e-5 * peak);
  // Closed form: the rule's period error (omega dt)^2 / 12 is 1.3e-4 in mode 1 but grows to ~6 % in
  // the highest chain modes (omega dt ~ 0.9) that the base's velocity jump at t = 0 excites.
  EXPECT_LT(err, 2.5e-2 * peak);
}

// (5) ------------------------------------------------------------------------------------------
TEST(DynamicStep, HhtAlphaBarMatchesTheHhtChain) {
  const fs::path dir = scratch_dir();
  const double mu = 0.010, lambda = 0.020, rho = 6.5e-11;  // [MPa], [t/mm^3]
  write_text(dir / "material.json", R"({"density_kg_m3": 65, "neo_hookean": {"mu_kPa": 10, "lambda_kPa": 20}})");
  const int N = 10;
  const double L = 100.0, h = L / N, A = 100.0, U = 1e-3, f = 20.0, Omega = 2 * M_PI * f;
  const double T = 0.05, dt = 2e-4, alpha = -0.1;
  json step = dynamic_step("shake", T, dt, with(lateral(), {{"set", "base"}, {"dof", "z"}, {"value_mm", U},
                                                            {"amplitude", "drive"}}));
  step["newmark"] = {{"alpha", alpha}};
  json c = column_case(L, N, json::array({step}), 1e-8);
  c["amplitudes"] = {{"drive", {{"type", "sine"}, {"frequency_Hz", f}}}};
  run_case(write_json(dir / "case.json", c), dir / "out");
  const CsvTable hist = read_history(dir / "out");

  // The chain: free nodes 1..N, base node 0 at u_b = U sin(Omega t), a_b = -Omega^2 u_b.
  const double k = (lambda + 2 * mu) * A / h, m = rho * A * h / 6.0;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N), M = Eigen::MatrixXd::Zero(N, N);
  for (int e = 0; e < N; ++e) {
    const int i = e - 1, j = e;
    if (i >= 0) K(i, i) += k, M(i, i) += 2 * m, K(i, j) -= k, K(j, i) -= k, M(i, j) += m, M(j, i) += m;
    K(j, j) += k, M(j, j) += 2 * m;
  }
  const auto steps = static_cast<Eigen::Index>(std::lround(T / dt));
  auto integrate = [&](double a_hht) {  // top displacement per step
    const double gamma = 0.5 - a_hht, beta = 0.25 * (1 - a_hht) * (1 - a_hht), c_a = 1.0 / (beta * dt * dt);
    const Eigen::LDLT<Eigen::MatrixXd> S((1 + a_hht) * K + c_a * M);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(N), v = q, a = q, e0 = q;
    e0(0) = 1.0;
    // G = K q - k u_b e0 (internal force of the free nodes), from rest: M a0 = -G0 - m a_b0 e0 = 0.
    std::vector<double> top{0.0};
    for (Eigen::Index n = 1; n <= steps; ++n) {
      const double ub0 = U * std::sin(Omega * (n - 1) * dt), ub1 = U * std::sin(Omega * n * dt);
      const Eigen::VectorXd G0 = K * q - k * ub0 * e0;
      // M a1 + m a_b1 e0 + (1 + alpha) (K q1 - k ub1 e0) - alpha G0 = 0, a1 = c_a (q1 - q) - c_a dt v - (1/(2 beta) - 1) a.
      const Eigen::VectorXd rhs = M * (c_a * q + c_a * dt * v + (0.5 / beta - 1.0) * a) + Omega * Omega * m * ub1 * e0 +
                                  (1 + a_hht) * k * ub1 * e0 + a_hht * G0;
      const Eigen::VectorXd q1 = S.solve(rhs);
      const Eigen::VectorXd a1 = c_a * (q1 - q) - c_a * dt * v - (0.5 / beta - 1.0) * a;
      v += dt * ((1 - gamma) * a + gamma * a1), a = a1, q = q1;
      top.push_back(q(N - 1));
    }
    return top;
  };
  const std::vector<double> hht = integrate(alpha), plain = integrate(0.0);
  const auto& u_top = col(hist, "top.U3_mm");
  ASSERT_EQ(u_top.size(), hht.size());
  double err = 0.0, gap = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < hht.size(); ++i) {
    err = std::max(err, std::abs(u_top[i] - hht[i]));
    gap = std::max(gap, std::abs(hht[i] - plain[i]));
    peak = std::max(peak, std::abs(hht[i]));
  }
  std::printf("  HHT alpha = %.2f: peak %.4e mm, max error vs the HHT chain %.3e mm, HHT vs plain rule %.3e mm\n",
              alpha, peak, err, gap);
  EXPECT_LT(err, 2e-5 * peak);
  EXPECT_GT(gap, 100 * err);
}

// (2) ------------------------------------------------------------------------------------------
/// Phasor Y of y(t) ~ c0 + c1 t + Re(Y e^{i w t}) by least squares.
cplx fit_phasor(const std::vector<double>& t, const std::vector<double>& y, double w, double t_from) {
  std::vector<Eigen::Vector4d> rows;
  std::vector<double> rhs;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t_from) rows.emplace_back(1.0, t[i], std::cos(w * t[i]), std::sin(w * t[i])), rhs.push_back(y[i]);
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 4);
  Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) A.row(static_cast<Eigen::Index>(i)) = rows[i], b(static_cast<Eigen::Index>(i)) = rhs[i];
  const Eigen::Vector4d c = A.colPivHouseholderQr().solve(b);
  return {c(2), -c(3)};
}

TEST(DynamicStep, SineAfterViscoPreloadReachesSteadyStateStepResponse) {
  const fs::path dir = scratch_dir();
  // Hyperfoam + Prony (tau 0.02 s, 0.2 s); heavy density: first mode ~60 Hz, inertia visible at 20 Hz.
  write_text(dir / "material.json", R"({"density_kg_m3": 150000, "hyperfoam": {"terms": [
      {"mu_kPa": 10.0, "alpha": 10.0, "nu": 0.1}, {"mu_kPa": 0.1, "alpha": -2.0, "nu": 0.1},
      {"mu_kPa": 0.5, "alpha": 3.0, "nu": 0.1}]},
      "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.3, "tau_s": 0.02}, {"g": 0.2, "tau_s": 0.2}]}})");
  const double f = 20.0, U = 0.005, cycles = 32, per_cycle = 100;  // 32 cycles = 8 tau_2 of transient decay
  const json damping = {{"rayleigh_alpha_1_s", 180}, {"rayleigh_beta_s", 1e-4}};
  const json base_fixed = {{"set", "base"}, {"type", "symmetry_z"}};
  json press = {{"name", "press"}, {"type", "visco"}, {"time_period_s", 1}, {"increment", {{"initial_s", 0.1}}},
                {"boundary", with(with(lateral(), base_fixed), {{"set", "top"}, {"dof", "z"}, {"value_mm", -2}})}};
  json hold = press;
  hold["name"] = "hold", hold["time_period_s"] = 10, hold["increment"] = {{"initial_s", 0.1}, {"max_s", 5}};
  json sweep = {{"name", "sweep"}, {"type", "steady_state"},
                {"steady_state", {{"frequencies_Hz", {f}},
                                  {"excitation", {{"set", "base"}, {"dof", "z"}, {"displacement_amplitude_mm", U}}},
                                  {"held", {{{"set", "top"}, {"dof", "z"}}, {{"set", "all"}, {"dof", "xy"}}}},
                                  {"measure", "top"}, {"damping", damping}, {"area_mm2", 100}, {"thickness_mm", 10},
                                  {"output", {{"vtk", false}}}, {"linear_solver", "direct"}}}};
  json shake = dynamic_step("shake", cycles / f, 1.0 / (f * per_cycle),
                            with(with(lateral(), {{"set", "top"}, {"dof", "z"}, {"value_mm", -2}}),
                                 {{"set", "base"}, {"dof", "z"}, {"value_mm", U}, {"amplitude", "drive"}}));
  shake["damping"] = damping;
  json c = column_case(10.0, 3, json::array({press, hold, sweep, shake}));
  c["amplitudes"] = {{"drive", {{"type", "sine"}, {"frequency_Hz", f}}}};
  run_case(write_json(dir / "case.json", c), dir / "out");

  const CsvTable ss = read_csv(dir / "out" / "sweep_sweep.csv");
  const cplx K_ssd = cplx(col(ss, "indenter_RF_real_N")[0], col(ss, "indenter_RF_imag_N")[0]) / U;
  const CsvTable hist = read_history(dir / "out");
  const double t_shake = 11.0, w = 2 * M_PI * f;
  std::vector<double> t, r;
  for (std::size_t i = 0; i < hist.rows(); ++i)
    if (col(hist, "time_s")[i] > t_shake + 1e-9) t.push_back(col(hist, "time_s")[i] - t_shake), r.push_back(col(hist, "top.RF3_N")[i]);
  ASSERT_EQ(t.size(), static_cast<std::size_t>(cycles * per_cycle));
  // Drive U sin(w t) has the phasor -i U.
  const cplx K_time = fit_phasor(t, r, w, (cycles - 2) / f) / cplx(0.0, -U);
  const double amp_err = std::abs(std::abs(K_time) / std::abs(K_ssd) - 1.0);
  const double phase_err = std::abs(std::arg(K_time / K_ssd)) * 180 / M_PI;
  std::printf("  %.0f Hz: |K| steady state %.6g, time %.6g N/mm (%.3f %%), phase %.4f vs %.4f deg (%.4f deg)\n", f,
              std::abs(K_ssd), std::abs(K_time), 100 * amp_err, std::arg(K_ssd) * 180 / M_PI,
              std::arg(K_time) * 180 / M_PI, phase_err);
  EXPECT_LT(amp_err, 1e-2);
  EXPECT_LT(phase_err, 0.5);
}

// (3) ------------------------------------------------------------------------------------------
/// Static pull of the top of an elastic hyperfoam column, then free vibration in `free_steps`
/// dynamic steps of equal length (top released at once). Returns the run folder.
fs::path free_vibration(const fs::path& dir, double gamma, int free_steps, double period, double dt) {
  write_text(dir / "material.json", foam_json(0.1, false));
  const json base_fixed = {{"set", "base"}, {"type", "symmetry_z"}};
  json steps = json::array({{{"name", "pull"}, {"type", "static"}, {"time_period_s", 1},
                             {"increment", {{"initial_s", 0.25}}},
                             {"boundary", with(with(lateral(), base_fixed), {{"set", "top"}, {"dof", "z"}, {"value_mm", -4}})}}});
  for (int i = 0; i < free_steps; ++i) {
    json s = dynamic_step("free" + std::to_string(i), period / free_steps, dt, with(lateral(), base_fixed));
    s["newmark"] = {{"gamma", gamma}};
    steps.push_back(s);
  }
  run_case(write_json(dir / "case.json", column_case(40.0, 4, steps)), dir / "out");
  return dir / "out";
}

TEST(DynamicStep, AverageAccelerationConservesEnergyInFreeVibration) {
  const double period = 0.08, dt = 1.6e-4;  // ~10 periods of the first mode (~120 Hz), ~50 increments each
  const fs::path out = free_vibration(scratch_dir("_avg"), 0.5, 1, period, dt);
  const CsvTable e = read_csv(out / "free0_energy.csv");
  const auto &ke = col(e, "kinetic_energy_mJ"), &w_int = col(e, "internal_work_mJ");
  double ke_max = 0.0, drift = 0.0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    ke_max = std::max(ke_max, ke[i]);
    drift = std::max(drift, std::abs(ke[i] + w_int[i]));  // energy at the start: 0 (at rest, work from 0)
    EXPECT_NEAR(col(e, "energy_balance_mJ")[i], 0.0, 1e-9 * ke_max + 1e-15);
    EXPECT_NEAR(col(e, "external_work_mJ")[i], 0.0, 1e-8 * ke_max + 1e-15);  // fixed supports do no work
  }
  std::printf("  free vibration: max kinetic energy %.5e mJ, max |KE + W_int| %.3e mJ (%.2e relative)\n", ke_max,
              drift, drift / ke_max);
  ASSERT_GT(ke_max, 0.0);
  EXPECT_LT(drift, 1e-6 * ke_max);
  // No numerical damping: the kinetic energy peaks in the last fifth of the step are as high as in
  // the first fifth (the modes beat, so compare the largest peaks, not single ones).
  const auto& t = col(e, "time_s");
  double first = 0.0, last = 0.0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    if (t[i] - t.front() < 0.2 * period) first = std::max(first, ke[i]);
    if (t.back() - t[i] < 0.2 * period) last = std::max(last, ke[i]);
  }
  std::printf("  kinetic energy peak in the first / last fifth: %.5e / %.5e mJ\n", first, last);
  EXPECT_GT(last, 0.9 * first);

  // Numerical dissipation of gamma = 0.6: the same energy measure decays (the test can tell).
  const fs::path damped = free_vibration(scratch_dir("_damped"), 0.6, 1, period, dt);
  const CsvTable d = read_csv(damped / "free0_energy.csv");
  const double lost = -(col(d, "kinetic_energy_mJ").back() + col(d, "internal_work_mJ").back());
  std::printf("  gamma = 0.6: energy lost %.3e mJ (%.1f %% of the max kinetic energy)\n", lost, 100 * lost / ke_max);
  EXPECT_GT(lost, 0.1 * ke_max);

  // Two consecutive dynamic steps (velocity carried) move exactly as one.
  const fs::path split = free_vibration(scratch_dir("_split"), 0.5, 2, period, dt);
  const CsvTable one = read_history(out), two = read_history(split);
  ASSERT_EQ(one.rows(), two.rows());
  double diff = 0.0, amp = 0.0;
  for (std::size_t i = 0; i < one.rows(); ++i) {
    EXPECT_NEAR(col(one, "time_s")[i], col(two, "time_s")[i], 1e-9);
    diff = std::max(diff, std::abs(col(one, "top.U3_mm")[i] - col(two, "top.U3_mm")[i]));
    amp = std::max(amp, std::abs(col(one, "top.U3_mm")[i]));
  }
  std::printf("  split in two steps: max difference of the top displacement %.3e mm (amplitude %.3g mm)\n", diff, amp);
  EXPECT_LT(diff, 1e-7 * amp);
}

// (4) ------------------------------------------------------------------------------------------
std::string error_of(const fs::path& dir, const json& c, const std::string& material = "") {
  write_text(dir / "material.json", material.empty() ? foam_json(0.1, false) : material);
  try {
    run_case(write_json(dir / "case.json", c), dir / "out");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& message, const std::string& where, const std::string& what) {
  EXPECT_NE(message.find(where), std::string::npos) << "expected '" << where << "' in: " << message;
  EXPECT_NE(message.find(what), std::string::npos) << "expected '" << what << "' in: " << message;
}

TEST(DynamicStep, BadInputNamesTheKey) {
  const fs::path dir = scratch_dir();
  const json fixed = with(lateral(), {{"set", "base"}, {"type", "symmetry_z"}});
  const json good = column_case(10.0, 1, json::array({dynamic_step("shake", 0.01, 0.001, fixed)}));
  auto edited = [&](const std::string& key, const json& value) {
    json c = good;
    c["steps"][0][key] = value;
    return c;
  };
  EXPECT_EQ(error_of(dir, good), "");
  // Missing density: found by load_case, before the preceding static step runs.
  json two = good;
  two["steps"] = json::array({{{"name", "pre"}, {"type", "static"}, {"time_period_s", 1}, {"boundary", fixed}},
                              good["steps"][0]});
  std::string no_density = foam_json(0.1, false);
  no_density.replace(no_density.find(R"("density_kg_m3": 65, )"), 21, "");
  expect_error(error_of(dir, two, no_density), "steps[1]", "density_kg_m3");
  expect_error(error_of(dir, two, no_density), "mass density of material", "material.json");
  // Newmark parameters outside the unconditionally stable range.
  expect_error(error_of(dir, edited("newmark", {{"gamma", 0.4}})), "steps[0].newmark.gamma", "unstable");
  expect_error(error_of(dir, edited("newmark", {{"gamma", 0.5}, {"beta", 0.1}})), "steps[0].newmark.beta",
               "unconditional stability");
  expect_error(error_of(dir, edited("newmark", {{"gamma", 0.6}, {"beta", 0.25}})), "steps[0].newmark.beta", "0.3025");
  // Unknown keys and wrong units.
  expect_error(error_of(dir, edited("newmark", {{"alpha", -0.5}})), "steps[0].newmark.alpha", "[-1/3, 0]");
  expect_error(error_of(dir, edited("newmark", {{"alpha", 0.05}})), "steps[0].newmark.alpha", "[-1/3, 0]");
  expect_error(error_of(dir, edited("newmark", {{"delta", 0.5}})), "steps[0].newmark", "delta");
  expect_error(error_of(dir, edited("damping", {{"rayleigh_alpha", 1}})), "steps[0].damping", "rayleigh_alpha");
  expect_error(error_of(dir, edited("damping", {{"rayleigh_beta_ms", 1}})), "steps[0].damping.rayleigh_beta_ms",
               "wrong unit");
  expect_error(error_of(dir, edited("damping", {{"rayleigh_alpha_1_s", -1}})), "steps[0].damping.rayleigh_alpha_1_s",
               ">= 0");
  expect_error(error_of(dir, edited("hht_alpha", -0.05)), "steps[0]", "hht_alpha");
  json static_damped = good;
  static_damped["steps"][0]["type"] = "static";
  static_damped["steps"][0]["increment"].erase("fixed");
  static_damped["steps"][0]["damping"] = {{"rayleigh_alpha_1_s", 1}};
  expect_error(error_of(dir, static_damped), "steps[0].damping", "applies to \"dynamic\" steps only");
  // Sine amplitudes.
  json sine = good;
  sine["amplitudes"] = {{"drive", {{"type", "sine"}, {"frequency_Hz", 0}}}};
  expect_error(error_of(dir, sine), "amplitudes.drive.frequency_Hz", "> 0");
  sine["amplitudes"] = {{"drive", {{"type", "sine"}, {"frequency_Hz", 5}, {"time_s", {0, 1}}}}};
  expect_error(error_of(dir, sine), "amplitudes.drive", "time_s");
  sine["amplitudes"] = {{"drive", {{"type", "cosine"}, {"frequency_Hz", 5}}}};
  expect_error(error_of(dir, sine), "amplitudes.drive.type", "cosine");
}

TEST(DynamicStep, AmplitudeDerivatives) {
  Amplitude sine;
  sine.kind = Amplitude::Kind::sine, sine.frequency = 3.0, sine.start = 0.1;
  const double h = 1e-5;
  for (double t : {0.15, 0.3, 0.77}) {
    EXPECT_NEAR(sine.rate(t), (sine.at(t + h) - sine.at(t - h)) / (2 * h), 1e-6 * 2 * M_PI * 3);
    EXPECT_NEAR(sine.second_rate(t), (sine.rate(t + h) - sine.rate(t - h)) / (2 * h), 1e-5 * std::pow(2 * M_PI * 3, 2));
  }
  EXPECT_EQ(sine.at(0.05), 0.0);
  EXPECT_EQ(sine.rate(0.05), 0.0);
  Amplitude table;
  table.time = {0.0, 1.0, 3.0}, table.value = {0.0, 2.0, 1.0};
  EXPECT_DOUBLE_EQ(table.rate(0.5), 2.0);
  EXPECT_DOUBLE_EQ(table.rate(1.0), 2.0);  // left derivative at a corner: the segment just completed
  EXPECT_DOUBLE_EQ(table.rate(2.0), -0.5);
  EXPECT_DOUBLE_EQ(table.rate(3.5), 0.0);
  EXPECT_DOUBLE_EQ(table.second_rate(0.5), 0.0);
  BoundarySpec ramp;
  ramp.dofs = {false, false, true}, ramp.value = 3.0;
  const PrescribedMotion m = prescribed_motion(ramp, {}, 1.0, 0.5, 2.0, 10.0);
  EXPECT_DOUBLE_EQ(m.u, 1.5);
  EXPECT_DOUBLE_EQ(m.v, 1.0);
  EXPECT_DOUBLE_EQ(m.a, 0.0);
}

}  // namespace
}  // namespace cushion::solver::test
