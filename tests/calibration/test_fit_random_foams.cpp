// Round trip of `cushion fit` over seeded random plausible foams (random_foam.hpp): each foam is written
// as a material file, measured NOISE-FREE by `cushion lab` with the paper's protocols (three quasi-static
// rates, dynamic 1..20 Hz about a 25 % preload), read back as a campaign and fitted by fit_pipeline with
// the default options. For the material the fit hands out as its default (material.json):
//   - the fit does not fail (no exception), the material is Drucker-stable over the tested range and
//     accepted by the material reader, and the log and report hold no NaN/inf;
//   - its long-term curve is within 1 % of the peak stress of the truth's over [0, peak strain];
//   - its |E*| about the preload (the solver's model along the test schedule) is within 2 % of the
//     measured one at every frequency.
// ctest runs 40 foams (seeds 1..40); the 200-foam figures come from the DISABLED_ test:
//   build/tests/test_calibration --gtest_also_run_disabled_tests --gtest_filter='FitRandomFoams.DISABLED_*'
// (CUSHION_RANDOM_FOAMS="first,count" picks other seeds).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
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

struct Outcome {
  unsigned long long seed = 0;
  std::string failure;                       ///< empty: passed
  std::string choice;                        ///< "paper" | "refit"
  double curve_error = NAN, modulus_error = NAN;
  double lab_seconds = 0.0, fit_seconds = 0.0;
  std::string log;
  std::string na;                            ///< predictions reported n/a (test: material: reason)
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
    o.curve_error = curve_error(foam.material, m, R.segments.peak_strain);
    for (const auto& c : R.comparisons)
      if (c.kind == "dynamic" && c.name == R.dynamic_name)
        o.modulus_error = modulus_error(o.choice == "refit" ? *c.dynamic_refit : *c.dynamic_paper);
    if (!(o.curve_error < curve_tolerance)) problems.push_back("long-term curve off");
    if (!(o.modulus_error < modulus_tolerance)) problems.push_back("|E*| off");
    for (const auto& p : problems) o.failure += (o.failure.empty() ? "" : "; ") + p;
  } catch (const std::exception& e) {
    o.failure = std::string("lab failed: ") + e.what();
  }
  fs::remove_all(dir);
  return o;
}

/// Runs seeds [first, first + count), one line per foam, a summary; expects every foam to pass.
void run_foams(unsigned long long first, int count) {
  if (const char* env = std::getenv("CUSHION_RANDOM_FOAMS")) {
    std::istringstream in(env);
    char comma = 0;
    in >> first >> comma >> count;
  }
  int failures = 0;
  double worst_curve = 0.0, worst_modulus = 0.0, fit_seconds = 0.0, lab_seconds = 0.0, slowest = 0.0;
  int refit_default = 0;
  for (int k = 0; k < count; ++k) {
    const Outcome o = round_trip(first + k);
    const bool ok = o.failure.empty();
    failures += ok ? 0 : 1;
    worst_curve = std::max(worst_curve, std::isfinite(o.curve_error) ? o.curve_error : INFINITY);
    worst_modulus = std::max(worst_modulus, std::isfinite(o.modulus_error) ? o.modulus_error : INFINITY);
    fit_seconds += o.fit_seconds;
    lab_seconds += o.lab_seconds;
    slowest = std::max(slowest, o.fit_seconds);
    refit_default += o.choice == "refit" ? 1 : 0;
    std::cout << "foam " << std::setw(4) << o.seed << ": " << std::setw(5) << o.choice << std::fixed << std::setprecision(3)
              << "  curve " << std::setw(8) << 100.0 * o.curve_error << " %  |E*| " << std::setw(8) << 100.0 * o.modulus_error
              << " %  lab " << std::setprecision(2) << o.lab_seconds << " s  fit " << o.fit_seconds << " s"
              << (o.na.empty() ? "" : "  n/a: " + o.na) << (ok ? "" : "  FAILED: " + o.failure) << std::defaultfloat << "\n";
    EXPECT_TRUE(ok) << rf::make_random_foam(o.seed).describe() << "\n" << o.failure << "\n" << o.log;
  }
  std::cout << std::setprecision(4) << "random foams: " << count << " (seeds " << first << ".." << first + count - 1
            << "), failures " << failures << ", worst long-term curve error " << 100.0 * worst_curve
            << " % of peak, worst |E*| error " << 100.0 * worst_modulus << " %, default refit " << refit_default
            << "/" << count << ", fit " << fit_seconds / count << " s per foam (slowest " << slowest << " s), lab "
            << lab_seconds / count << " s per foam\n";
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

TEST(FitRandomFoams, FortyNoiseFreeFoamsRoundTrip) { run_foams(1, 40); }

TEST(FitRandomFoams, DISABLED_TwoHundredNoiseFreeFoamsRoundTrip) { run_foams(1, 200); }
