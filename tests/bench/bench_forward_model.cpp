/// Benchmark of the test forward model that `cushion compare` and every model run of `cushion diagnose` use
/// (calibration::compare_campaign), never run by ctest (speed is measured, not tested).
///
///   bench_forward_model MATERIAL.json CAMPAIGN.json [ROUNDS]
///
/// Times each test of the campaign alone (quasi-static and dynamic, one campaign of one test each) and the whole
/// campaign, under the dynamic schedules a diagnosis could use, interleaved round by round on one thread so that a
/// change of the machine's speed falls on every schedule alike; prints the median wall time per run [ms], the ratio
/// to the default schedule (CompareOptions' dynamic_steps_per_cycle and dynamic_transient_steps_per_cycle), and how far
/// each schedule's |E*| and phase lie from a fine reference (256 steps a cycle everywhere) and from the default, in
/// units of the test's noise at each frequency (max over the frequencies). The quasi-static tests do not depend on the
/// dynamic schedule: their ratios show the timer's scatter. Structure-level tests of the campaign are left out.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "material/io/material_file.hpp"

using namespace cushion;
using calibration::Campaign;
using calibration::CompareOptions;

namespace {

struct Schedule {
  std::string name;
  CompareOptions options;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// The campaign with test k alone (quasi-static first, then dynamic, as compare orders them).
Campaign only_test(const Campaign& c, std::size_t k) {
  Campaign one = c;
  one.quasi_static.clear();
  one.dynamic.clear();
  if (k < c.quasi_static.size())
    one.quasi_static.push_back(c.quasi_static[k]);
  else
    one.dynamic.push_back(c.dynamic[k - c.quasi_static.size()]);
  return one;
}

double seconds_of(const material::Material& m, const Campaign& c, const CompareOptions& o,
                  const std::vector<calibration::TestNoise>& noise) {
  const auto t0 = std::chrono::steady_clock::now();
  const calibration::CompareResult r = calibration::compare_campaign(m, c, o, noise);
  for (const auto& t : r.tests)
    if (!t.failure.empty()) std::fprintf(stderr, "warning: %s: %s\n", t.name.c_str(), t.failure.c_str());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Largest |E*| and phase deviation of `r` from `ref` over a dynamic test's frequencies, in noise units.
std::pair<double, double> deviation(const calibration::TestCompare& r, const calibration::TestCompare& ref) {
  double dm = 0.0, dp = 0.0;
  for (std::size_t i = 0; i < r.model.size(); ++i) {
    const double sm = i < r.noise.modulus_local.size() ? r.noise.modulus_local[i] : r.noise.modulus;
    const double sp = i < r.noise.phase_local.size() ? r.noise.phase_local[i] : r.noise.phase;
    if (sm > 0.0) dm = std::max(dm, std::abs(r.model[i] - ref.model[i]) / sm);
    if (sp > 0.0) dp = std::max(dp, std::abs(r.model_phase[i] - ref.model_phase[i]) / sp);
  }
  return {dm, dp};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: bench_forward_model MATERIAL.json CAMPAIGN.json [ROUNDS (default 20)]\n");
    return 2;
  }
  try {
    const auto def = material::read_material_file(argv[1]);
    // The material-level tests (quasi-static, dynamic); structure-level ones run the FE solver and are left out.
    Campaign campaign = calibration::read_campaign(argv[2]);
    campaign.indentation.clear();
    campaign.stiffness.clear();
    int rounds = 20;
    if (argc == 4) {
      std::size_t used = 0;
      try {
        rounds = std::stoi(argv[3], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != std::string(argv[3]).size() || rounds < 1 || rounds > 10000) {
        std::fprintf(stderr, "bench_forward_model: ROUNDS '%s': must be a whole number in [1, 10000]\n", argv[3]);
        return 2;
      }
    }
    const auto noise = calibration::estimate_noise(campaign);

    std::vector<Schedule> schedules;
    schedules.push_back({"default", CompareOptions{}});
    // {fitted-cycle steps, transient-cycle steps}: the default's neighbours
    for (auto [fitted, transient] : std::vector<std::array<int, 2>>{{64, 32}, {64, 16}, {64, 8}, {32, 32}, {128, 16}}) {
      CompareOptions o;
      o.dynamic_steps_per_cycle = fitted;
      o.dynamic_transient_steps_per_cycle = transient;
      schedules.push_back({"fitted " + std::to_string(fitted) + ", transient " + std::to_string(transient), o});
    }
    CompareOptions fine;
    fine.dynamic_steps_per_cycle = 256;
    fine.dynamic_transient_steps_per_cycle = 256;
    const calibration::CompareResult ref = calibration::compare_campaign(*def.model, campaign, fine, noise);

    const std::size_t n_tests = campaign.quasi_static.size() + campaign.dynamic.size();
    std::vector<Campaign> parts;
    for (std::size_t k = 0; k < n_tests; ++k) parts.push_back(only_test(campaign, k));
    // times[schedule][test] (n_tests: the whole campaign)
    std::vector<std::vector<std::vector<double>>> times(schedules.size(),
                                                        std::vector<std::vector<double>>(n_tests + 1));
    for (int round = 0; round < rounds; ++round)
      for (std::size_t s = 0; s < schedules.size(); ++s) {
        for (std::size_t k = 0; k < n_tests; ++k)
          times[s][k].push_back(seconds_of(*def.model, parts[k], schedules[s].options, {noise[k]}));
        times[s][n_tests].push_back(seconds_of(*def.model, campaign, schedules[s].options, noise));
      }

    std::printf("forward model of %s with %s, %d rounds, one thread; median ms per run (ratio to the default)\n",
                argv[2], argv[1], rounds);
    std::printf("%-36s", "schedule");
    for (const auto& t : ref.tests) std::printf(" %14s", t.name.c_str());
    std::printf(" %14s\n", "campaign");
    const double base_total = median(times[0][n_tests]);
    for (std::size_t s = 0; s < schedules.size(); ++s) {
      std::printf("%-36s", schedules[s].name.c_str());
      for (std::size_t k = 0; k <= n_tests; ++k) {
        const double ms = 1e3 * median(times[s][k]);
        std::printf(" %7.2f (%4.2f)", ms, ms / (1e3 * median(times[0][k])));
      }
      std::printf("\n");
    }
    std::printf(
        "total of the default: %.2f ms; max deviation over the frequencies from 256 steps a cycle everywhere "
        "(and from the default), |E*| / phase in noise units:\n",
        1e3 * base_total);
    const calibration::CompareResult standard = calibration::compare_campaign(*def.model, campaign, {}, noise);
    for (const auto& s : schedules) {
      const calibration::CompareResult r = calibration::compare_campaign(*def.model, campaign, s.options, noise);
      std::printf("%-36s", s.name.c_str());
      for (std::size_t k = 0; k < r.tests.size(); ++k)
        if (r.tests[k].kind == "dynamic") {
          const auto [dm, dp] = deviation(r.tests[k], ref.tests[k]);
          const auto [sm, sp] = deviation(r.tests[k], standard.tests[k]);
          std::printf("  %s %.3f / %.3f (from the default %.3f / %.3f)", r.tests[k].name.c_str(), dm, dp, sm, sp);
        }
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_forward_model: %s\n", e.what());
    return 1;
  }
  return 0;
}
