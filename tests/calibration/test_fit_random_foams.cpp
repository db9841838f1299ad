// Round trip of `cushion fit` over seeded random plausible foams (random_foam.hpp): each foam is written
// as a material file, measured NOISE-FREE by `cushion lab` with the paper's protocols (three quasi-static
// rates, dynamic 1..20 Hz about a 25 % preload), read back as a campaign and fitted by fit_pipeline with
// the default options; the outputs are written (write_fit_outputs, no plots drawn).
//
// Two parts:
//   1. ROBUSTNESS, hard requirements. Each of them failed on some random foam before the fit-robust branch (the fit
//      threw, or handed out an unstable material, or wrote NaN, or gave no reason, or threw in the final comparison:
//      seed 31):
//        - the fit completes (no exception) and writes material.json, report.json, report.md;
//        - the default material is accepted by the material reader and Drucker-stable over [-peak strain, 0.5];
//        - no NaN/inf in the log nor anywhere in report.json; a failed prediction is "n/a (reason)", never a bare NaN;
//        - the solver's model of the default material runs every calibration test;
//        - the refit's rejection reason is never empty when it is not accepted; the default's reason never empty;
//        - the default is the best of the usable candidates (paper's, refit: converged, readable, Drucker-stable,
//          running every calibration test) on the calibration tests: its joint error there (solver's model,
//          sqrt((RMS_qs^2 + E_dyn^2)/2), RMS_qs over the quasi-static calibration tests, E_dyn the |E*| error on the
//          dynamic one) is at most best_margin_relative above the better candidate's (the refit chooses by its own
//          joint cost in E', E'' with the fast uniaxial model, hence a margin rather than equality).
//   2. ACCURACY (issue 15):
//        - the default's long-term curve within 1 % of the truth's peak stress over [0, peak strain];
//        - its |E*| about the preload (the solver's model along the test schedule) within 2 % at every frequency.
// ctest runs both parts on seeds 1..40 (FitRandomFoams.NoFailureAndWithinToleranceOnFortyFoams) and on six former
// refit misses; the 200-foam acceptance run (about 9 minutes) is DISABLED_:
//   build/tests/test_calibration --gtest_also_run_disabled_tests --gtest_filter='FitRandomFoams.DISABLED_*'
// Each prints one line per foam (for a foam off tolerance also the truth, the paper's and the refit's materials with
// their errors), the count within tolerance and the worst figures. CUSHION_RANDOM_FOAMS="first,count" or
// CUSHION_RANDOM_FOAM_SEEDS="3 15 18" picks other seeds for any of them; CUSHION_RANDOM_FOAMS_LOG=1 prints the fit log.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "calibration/campaign.hpp"
#include "calibration/fit_output.hpp"
#include "calibration/fit_pipeline.hpp"
#include "calibration/report_fit.hpp"
#include "calibration/hyperfoam_fit.hpp"
#include "material/hyperfoam.hpp"
#include "material/stability.hpp"
#include "random_foam.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;
namespace rf = cushion::random_foam;
namespace fs = std::filesystem;

namespace {

constexpr double curve_tolerance = 0.01;    // of the truth's peak stress
constexpr double modulus_tolerance = 0.02;  // relative |E*| at every frequency
constexpr double best_margin_relative = 0.05;  // default's joint calibration error vs the better usable candidate's

struct Outcome {
  unsigned long long seed = 0;
  std::string failure;                       ///< robustness (part 1) failures; empty: passed
  std::string inaccuracy;                    ///< accuracy (part 2) misses; empty: within tolerance
  std::string choice;                        ///< "paper" | "refit"
  double curve_error = NAN, modulus_error = NAN;
  double joint_default = NAN, joint_best = NAN;  ///< joint calibration error of the default, of the better usable candidate
  double lab_seconds = 0.0, fit_seconds = 0.0;
  std::string log;
  std::string na;                            ///< predictions reported n/a (test: material: reason)
  std::string detail;                        ///< for a foam off tolerance: the fitted materials and their errors
};

double curve_error(const cal::ViscoHyperfoam& truth, const cal::ViscoHyperfoam& m, double peak_strain) {
  std::vector<double> e;
  for (int i = 0; i <= 150; ++i) e.push_back(peak_strain * i / 150.0);
  const auto t = cal::hyperfoam_uniaxial_stress(truth.terms, 0.0, cal::Lateral::free, e);
  const auto f = cal::hyperfoam_uniaxial_stress(m.terms, m.terms.front().nu, cal::Lateral::free, e);
  double err = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    err = std::max(err, std::abs(f[i] - t[i]));
    peak = std::max(peak, std::abs(t[i]));
  }
  return err / peak;
}

/// Non-finite numbers in a JSON document (nlohmann keeps NaN/inf as numbers and dumps them as null): their paths.
void non_finite(const nlohmann::json& j, const std::string& path, std::vector<std::string>& out) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) out.push_back(path);
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) non_finite(it.value(), path + "/" + it.key(), out);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) non_finite(j[i], path + "/" + std::to_string(i), out);
}

double modulus_error(const cal::DynamicPrediction& p) {
  double err = 0.0;
  for (std::size_t i = 0; i < p.measured.frequency.size(); ++i) {
    const double m = std::hypot(p.model.storage[i], p.model.loss[i]);
    const double d = std::hypot(p.measured.storage[i], p.measured.loss[i]);
    const double e = std::abs(m / d - 1.0);
    err = std::isfinite(e) ? std::max(err, e) : INFINITY;
  }
  return err;
}

std::string terms_text(const cal::ViscoHyperfoam& m) {
  std::ostringstream o;
  o.precision(4);
  for (const auto& t : m.terms) o << " (mu " << t.mu * 1e3 << " kPa, alpha " << t.alpha << ")";
  o << "; g";
  for (const auto& p : m.prony) o << " " << p.g << "@" << p.tau << "s";
  return o.str();
}

/// For a foam off tolerance: the truth, the paper's and the refit's materials with their curve and |E*| errors.
std::string miss_detail(const rf::RandomFoam& foam, const cal::FitResult& R) {
  std::ostringstream o;
  o.precision(4);
  const double ep = R.segments.peak_strain;
  o << "    truth:" << terms_text(foam.material) << "\n    paper:" << terms_text(R.paper_material) << "  curve "
    << 100.0 * curve_error(foam.material, R.paper_material, ep) << " % (hyperfoam fit RMS " << 100.0 * R.hyperfoam.rms_error
    << " % of the elastic curve)";
  for (const auto& c : R.comparisons)
    if (c.kind == "dynamic" && c.name == R.dynamic_name && c.dynamic_paper) o << "  |E*| " << 100.0 * modulus_error(*c.dynamic_paper) << " %";
  if (R.refit) {
    o << "\n    refit:" << terms_text(R.refit->material) << "  curve " << 100.0 * curve_error(foam.material, R.refit->material, ep) << " %";
    for (const auto& c : R.comparisons)
      if (c.kind == "dynamic" && c.name == R.dynamic_name && c.dynamic_refit) o << "  |E*| " << 100.0 * modulus_error(*c.dynamic_refit) << " %";
    o << "  cost " << R.refit->cost_start << " -> " << R.refit->cost << " (qs " << 100.0 * R.refit->quasi_static_rms
      << " %, dyn " << 100.0 * R.refit->dynamic_rms << " %)" << (R.refit->accepted() ? "" : "  rejected: " + R.refit->rejection);
  }
  o << "\n    decomposition branch mismatch " << 100.0 * R.decomposition.branch_mismatch << " %, hereditary RMSE "
    << 100.0 * R.hereditary.rmse_relative << " %, Prony chi2 " << R.prony.chi2 << "\n";
  return o.str();
}

Outcome round_trip(unsigned long long seed) {
  Outcome o;
  o.seed = seed;
  const rf::RandomFoam foam = rf::make_random_foam(seed);
  const fs::path dir = fs::temp_directory_path() / ("cushion_random_foam_" + std::to_string(::getpid()) + "_" + std::to_string(seed));
  auto t0 = std::chrono::steady_clock::now();
  try {
    const cal::Campaign campaign = cal::read_campaign(rf::make_random_foam_campaign(foam, dir));
    auto t1 = std::chrono::steady_clock::now();
    o.lab_seconds = std::chrono::duration<double>(t1 - t0).count();
    std::ostringstream log;
    cal::FitResult R;
    try {
      R = cal::fit_pipeline(campaign, cal::FitOptions{}, log);
    } catch (const std::exception& e) {
      o.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      o.log = log.str();
      o.failure = std::string("fit failed: ") + e.what();
      fs::remove_all(dir);
      return o;
    }
    o.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    o.log = log.str();
    o.choice = R.default_choice == cal::DefaultMaterial::refit ? "refit" : "paper";
    const cal::ViscoHyperfoam& m = R.default_material;
    std::vector<std::string> problems;
    if (!cal::material_problem(m).empty()) problems.push_back("default material rejected: " + cal::material_problem(m));
    if (!mat::check_stability(mat::Hyperfoam(m.terms), -R.segments.peak_strain, 0.5).stable())
      problems.push_back("default material Drucker-unstable");
    if (!R.hyperfoam.stable) problems.push_back("paper's hyperfoam reported unstable");
    if (std::regex_search(o.log, std::regex(R"(\b(nan|-?inf)\b)", std::regex::icase)))
      problems.push_back("NaN/inf in the log");
    // A failed prediction (one material, one test) is reported "n/a (reason)" and does not abort the fit (seed 31:
    // the point driver's free-stretch Newton did not converge for one material on one test).
    for (const auto& c : R.comparisons) {
      if (!std::isfinite(c.error_paper) && c.failure_paper.empty()) problems.push_back("NaN/inf paper error without a reason on " + c.name);
      if (!std::isfinite(c.error_refit) && c.failure_refit.empty()) problems.push_back("NaN/inf refit error without a reason on " + c.name);
      if (!c.failure_paper.empty() || !c.failure_refit.empty()) o.na += c.name + ": paper " + (c.failure_paper.empty() ? "ok" : c.failure_paper) + ", refit " + (c.failure_refit.empty() ? "ok" : c.failure_refit) + "; ";
    }
    // The solver runs the default material on every calibration test (the fit switches to the other material otherwise).
    for (const auto& c : R.comparisons)
      if (c.use == "calibration" && !(o.choice == "refit" ? c.failure_refit : c.failure_paper).empty())
        problems.push_back("the default material fails on calibration test " + c.name);
    // The outputs (materials, report.json) are written whatever failed in the comparison.
    std::ostringstream out_log;
    try {
      cal::write_fit_outputs(R, campaign, dir / "fit", "", out_log);
      for (const char* f : {"material.json", "report.json", "report.md"})
        if (!fs::exists(dir / "fit" / f)) problems.push_back(std::string("no ") + f + " written");
      std::vector<std::string> bad;
      non_finite(cal::report_json(R, campaign), "", bad);
      for (const auto& b : bad) problems.push_back("non-finite figure in report.json at " + b);
    } catch (const std::exception& e) {
      problems.push_back(std::string("writing the outputs failed: ") + e.what());
    }
    if (R.default_reason.empty()) problems.push_back("no default reason");
    if (R.refit && !R.refit->accepted() && R.refit->rejection.empty()) problems.push_back("refit rejected without a reason");
    // The default is the best usable candidate on the calibration tests.
    auto joint = [&](bool refit_material) {
      double qs2 = 0.0, dyn = NAN;
      int n = 0;
      for (const auto& c : R.comparisons) {
        if (c.use != "calibration") continue;
        const double e = refit_material ? c.error_refit : c.error_paper;
        if (!std::isfinite(e)) return static_cast<double>(NAN);
        if (c.kind == "quasi_static") qs2 += e * e, ++n;
        else if (c.name == R.dynamic_name) dyn = e;
      }
      return n > 0 && std::isfinite(dyn) ? std::sqrt((qs2 / n + dyn * dyn) / 2.0) : static_cast<double>(NAN);
    };
    const double j_paper = R.paper_problem.empty() ? joint(false) : NAN;
    const double j_refit = R.refit && R.refit->converged && R.refit_problem.empty() ? joint(true) : NAN;
    o.joint_default = o.choice == "refit" ? j_refit : j_paper;
    o.joint_best = std::fmin(j_paper, j_refit);
    if (!(o.joint_default <= o.joint_best * (1.0 + best_margin_relative)))
      problems.push_back("default (" + o.choice + ") joint calibration error " + std::to_string(o.joint_default) +
                         " above the better candidate's " + std::to_string(o.joint_best) + " (paper " + std::to_string(j_paper) +
                         ", refit " + std::to_string(j_refit) + ")");
    for (const auto& p : problems) o.failure += (o.failure.empty() ? "" : "; ") + p;
    // Accuracy (part 2).
    o.curve_error = curve_error(foam.material, m, R.segments.peak_strain);
    for (const auto& c : R.comparisons)
      if (c.kind == "dynamic" && c.name == R.dynamic_name) {
        const auto& d = o.choice == "refit" ? c.dynamic_refit : c.dynamic_paper;
        if (d) o.modulus_error = modulus_error(*d);
      }
    if (!(o.curve_error < curve_tolerance)) o.inaccuracy += "long-term curve off; ";
    if (!(o.modulus_error < modulus_tolerance)) o.inaccuracy += "|E*| off; ";
    if (!o.inaccuracy.empty()) o.detail = miss_detail(foam, R);
  } catch (const std::exception& e) {
    o.failure = std::string("lab failed: ") + e.what();
  }
  fs::remove_all(dir);
  return o;
}

/// Runs `seeds`, one line per foam, a summary. Expects part 1 on every foam; with `accuracy`, also part 2 (the
/// long-term curve and |E*| within tolerance). CUSHION_RANDOM_FOAMS="first,count" (a range) or
/// CUSHION_RANDOM_FOAM_SEEDS="3 15 18" (a list) picks other seeds.
void run_foams(std::vector<unsigned long long> seeds, bool accuracy) {
  if (const char* env = std::getenv("CUSHION_RANDOM_FOAMS")) {
    std::istringstream in(env);
    unsigned long long first = 1;
    int count = 0;
    char comma = 0;
    in >> first >> comma >> count;
    seeds.clear();
    for (int k = 0; k < count; ++k) seeds.push_back(first + k);
  }
  if (const char* env = std::getenv("CUSHION_RANDOM_FOAM_SEEDS")) {
    std::istringstream in(env);
    seeds.assign(std::istream_iterator<unsigned long long>(in), std::istream_iterator<unsigned long long>());
  }
  const int count = int(seeds.size());
  int failures = 0, accurate = 0, curve_ok = 0, modulus_ok = 0, refit_default = 0;
  double worst_curve = 0.0, worst_modulus = 0.0, worst_joint_ratio = 0.0, fit_seconds = 0.0, lab_seconds = 0.0, slowest = 0.0;
  unsigned long long worst_curve_seed = 0, worst_modulus_seed = 0;
  const auto start = std::chrono::steady_clock::now();
  for (unsigned long long seed : seeds) {
    const Outcome o = round_trip(seed);
    const bool ok = o.failure.empty();
    failures += ok ? 0 : 1;
    accurate += o.inaccuracy.empty() ? 1 : 0;
    curve_ok += o.curve_error < curve_tolerance ? 1 : 0;
    modulus_ok += o.modulus_error < modulus_tolerance ? 1 : 0;
    const double ce = std::isfinite(o.curve_error) ? o.curve_error : INFINITY;
    const double me = std::isfinite(o.modulus_error) ? o.modulus_error : INFINITY;
    if (ce > worst_curve) worst_curve = ce, worst_curve_seed = o.seed;
    if (me > worst_modulus) worst_modulus = me, worst_modulus_seed = o.seed;
    if (std::isfinite(o.joint_default / o.joint_best)) worst_joint_ratio = std::max(worst_joint_ratio, o.joint_default / o.joint_best);
    fit_seconds += o.fit_seconds;
    lab_seconds += o.lab_seconds;
    slowest = std::max(slowest, o.fit_seconds);
    refit_default += o.choice == "refit" ? 1 : 0;
    std::cout << "foam " << std::setw(4) << o.seed << ": " << std::setw(5) << o.choice << std::fixed << std::setprecision(3)
              << "  curve " << std::setw(8) << 100.0 * o.curve_error << " %  |E*| " << std::setw(8) << 100.0 * o.modulus_error
              << " %  joint default/best " << std::setprecision(4) << o.joint_default / o.joint_best << "  lab "
              << std::setprecision(2) << o.lab_seconds << " s  fit " << o.fit_seconds << " s"
              << (o.na.empty() ? "" : "  n/a: " + o.na) << (o.inaccuracy.empty() ? "" : "  inaccurate: " + o.inaccuracy)
              << (ok ? "" : "  FAILED: " + o.failure) << std::defaultfloat << "\n";
    if (!o.detail.empty()) std::cout << "    " << rf::make_random_foam(o.seed).describe() << "\n" << o.detail;
    if (std::getenv("CUSHION_RANDOM_FOAMS_LOG")) std::cout << o.log;
    EXPECT_TRUE(ok) << rf::make_random_foam(o.seed).describe() << "\n" << o.failure << "\n" << o.log;
    if (accuracy) {
      EXPECT_TRUE(o.inaccuracy.empty()) << rf::make_random_foam(o.seed).describe() << "\n" << o.inaccuracy;
    }
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << std::setprecision(4) << "random foams: " << count << " (seeds " << seeds.front() << ".." << seeds.back()
            << "), robustness failures " << failures << "; within tolerance (curve < " << 100.0 * curve_tolerance
            << " % of peak and |E*| < " << 100.0 * modulus_tolerance << " %): " << accurate << "/" << count << " (curve "
            << curve_ok << ", |E*| " << modulus_ok << "); worst long-term curve error " << 100.0 * worst_curve
            << " % of peak (seed " << worst_curve_seed << "), worst |E*| error " << 100.0 * worst_modulus << " % (seed "
            << worst_modulus_seed << "); worst default/best joint calibration error " << worst_joint_ratio
            << "; default refit " << refit_default << "/" << count << ", fit " << fit_seconds / count
            << " s per foam (slowest " << slowest << " s), lab " << lab_seconds / count << " s per foam, total " << total << " s\n";
}

}  // namespace

TEST(RandomFoam, DrawsArePlausibleStableAndRepeatable) {
  for (unsigned long long seed = 1; seed <= 200; ++seed) {
    const rf::RandomFoam a = rf::make_random_foam(seed), b = rf::make_random_foam(seed);
    ASSERT_EQ(a.describe(), b.describe());
    ASSERT_GE(a.material.terms.size(), 2u);
    ASSERT_LE(a.material.terms.size(), 4u);
    const double s50 = cal::hyperfoam_uniaxial_stress(a.material.terms, 0.0, cal::Lateral::free, {0.5}).front();
    EXPECT_GE(s50, 1e-3 * (1 - 1e-9));
    EXPECT_LE(s50, 1e-2 * (1 + 1e-9));
    EXPECT_TRUE(mat::check_stability(mat::Hyperfoam(a.material.terms), -0.9, 0.5).stable()) << a.describe();
    double g = 0.0;
    for (const auto& p : a.material.prony) g += p.g;
    EXPECT_GE(g, 0.2 - 1e-12);
    EXPECT_LE(g, 0.6 + 1e-12);
    EXPECT_GE(a.density_kg_m3, 30.0);
    EXPECT_LE(a.density_kg_m3, 80.0);
  }
}

std::vector<unsigned long long> seed_range(unsigned long long first, int count) {
  std::vector<unsigned long long> seeds;
  for (int k = 0; k < count; ++k) seeds.push_back(first + k);
  return seeds;
}

// Parts 1 and 2 on seeds 1..40, run by ctest.
TEST(FitRandomFoams, NoFailureAndWithinToleranceOnFortyFoams) { run_foams(seed_range(1, 40), true); }

// Parts 1 and 2 on foams beyond seed 40 that the refit missed before its relaxed global screen, diverse multi-start
// polish and bound handling (curve 2-82 % of peak off): 70 (4 terms, 3 negative exponents), 139 (all exponents
// positive, relaxation only at 10 and 100 s: a_i = 0 at the bound stalled the polish), 158 (the better starts had
// the wrong sign pattern), 188 (two equal exponents with cancelling moduli), 195 (tiny densification terms); and 117
// (a 4-term foam: curve 1.01 % of peak with 3 terms, within tolerance only with the N + 1-term refit).
TEST(FitRandomFoams, FormerRefitMissesWithinTolerance) { run_foams({70, 139, 158, 188, 195, 117}, true); }

// Part 2 (accuracy acceptance) on seeds 1..200: 200/200 (measured 2026-11-25: worst curve 0.87 % of peak, seed 139;
// worst |E*| 1.24 %, seed 1); before the N + 1-term refit 199/200 (seed 117, a 4-term foam fitted with 3 terms, curve
// 1.01 % of peak; 0.29 % with 4). Re-run 2026-11-25 after the time polish took the bisection line search: 200/200,
// same worst cases, 2.57 s a fit (8.7 minutes on two cores, alone), so not run by ctest.
TEST(FitRandomFoams, DISABLED_TwoHundredNoiseFreeFoamsRoundTrip) { run_foams(seed_range(1, 200), true); }
