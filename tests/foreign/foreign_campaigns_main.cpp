// foreign_campaigns --out DIR --count N --seed S [--pairs P] [--controls C] [--dynamic-noise amplitude|reading]
//                   [--protocol recorded|unrecorded]
//                   [--extra-rate MM_MIN]... [--extra-preload STRAIN]... [--extra-hold S]...
//                   [--base-refit none|report|scale] [--only NAME]... [--sweep-substeps N]
// Test-data generation for the diagnose benchmark (issue 15), independent of cushion's material/ and
// calibration/: writes N seeded campaigns DIR/c000 ... in cushion's campaign format, each with truth.json,
// and DIR/index.csv. Defaults: P = C = round(N/6). Deterministic for a seed.
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "foreign_campaign.hpp"

namespace {

int usage(const std::string& message) {
  std::cerr
      << (message.empty() ? "" : "foreign_campaigns: " + message + "\n")
      << "usage: foreign_campaigns --out DIR --count N --seed S [--pairs P] [--controls C]\n"
         "                         [--dynamic-noise amplitude|reading] [--protocol recorded|unrecorded]\n"
         "                         [--extra-rate MM_MIN]... [--extra-preload STRAIN]... [--extra-hold S]...\n"
         "                         [--base-refit none|report|scale] [--only NAME]... [--sweep-substeps N]\n"
         "  N campaigns DIR/c000... (P with two effect families, C controls without effect, the rest one\n"
         "  family each, balanced over families and forms), each campaign.json + CSV + truth.json +\n"
         "  drawn_noise.json (the sweeps' |E*| and phase noise per frequency), and\n"
         "  DIR/index.csv. Defaults: P = C = round(N/6); dynamic noise relative to the oscillating force;\n"
         "  protocol recorded (unrecorded: each campaign runs its own dynamic protocol, keys left out).\n"
         "  --extra-rate / --extra-preload / --extra-hold: one more quasi-static test at that rate / dynamic sweep\n"
         "  at that preload / 120 mm/min test holding S seconds at the peak in every campaign (validation), the\n"
         "  truth and the other records unchanged.\n"
         "  --base-refit: report also records in truth.json what a refitted base of the generator's own family\n"
         "  leaves of the effects (and, of each member of a pair, what that base refitted with the other member\n"
         "  leaves: beyond_partner_refit); scale sizes each effect by that instead of by its difference from the\n"
         "  true base (default none).\n"
         "  --only: write just the campaign so named (c038: the 39th), the same as in the whole set.\n"
         "  --sweep-substeps: integration steps of the foam per sample of a sweep (default 1, one a sample, the\n"
         "  dashpots' secant rate then lags by half a sample interval as in cushion's model; n: n times less).\n";
  return message.empty() ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out, dynamic_noise = "amplitude", protocol = "recorded", base_refit = "none";
  long count = -1, pairs = -1, controls = -1, sweep_substeps = 1;
  long long seed = -1;
  std::vector<double> extra_rates, extra_preloads, extra_holds;
  std::set<std::string> only;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") return usage("");
      if (i + 1 >= argc) return usage("missing value after " + a);
      const std::string v = argv[++i];
      if (a == "--out") out = v;
      else if (a == "--count") count = std::stol(v);
      else if (a == "--seed") seed = std::stoll(v);
      else if (a == "--pairs") pairs = std::stol(v);
      else if (a == "--controls") controls = std::stol(v);
      else if (a == "--dynamic-noise") dynamic_noise = v;
      else if (a == "--protocol") protocol = v;
      else if (a == "--base-refit") base_refit = v;
      else if (a == "--only") only.insert(v);
      else if (a == "--sweep-substeps")
        sweep_substeps = std::stol(v);
      else if (a == "--extra-rate")
        extra_rates.push_back(std::stod(v));
      else if (a == "--extra-preload")
        extra_preloads.push_back(std::stod(v));
      else if (a == "--extra-hold")
        extra_holds.push_back(std::stod(v));
      else return usage("unknown option " + a);
    }
  } catch (const std::exception&) {
    return usage("bad number");
  }
  if (out.empty() || count < 1 || seed < 0) return usage("--out, --count >= 1 and --seed >= 0 are required");
  if (dynamic_noise != "amplitude" && dynamic_noise != "reading") return usage("--dynamic-noise: amplitude or reading");
  if (protocol != "recorded" && protocol != "unrecorded") return usage("--protocol: recorded or unrecorded");
  if (base_refit != "none" && base_refit != "report" && base_refit != "scale")
    return usage("--base-refit: none, report or scale");
  for (double r : extra_rates)
    if (!(r > 0.0 && r <= 1e5)) return usage("--extra-rate: a crosshead rate in (0, 1e5] mm/min");
  for (double p : extra_preloads)
    if (!(p > 0.0 && p < 0.9)) return usage("--extra-preload: a nominal preload strain in (0, 0.9)");
  for (double h : extra_holds)
    if (!(h >= 0.0 && h <= 1e4)) return usage("--extra-hold: a hold in [0, 1e4] s");
  if (!(sweep_substeps >= 1 && sweep_substeps <= 1000)) return usage("--sweep-substeps: an integer in [1, 1000]");
  if (pairs < 0) pairs = std::lround(count / 6.0);
  if (controls < 0) controls = std::lround(count / 6.0);
  try {
    foreign_bench::TestPlan plan = foreign_bench::standard_plan();
    plan.noise.dynamic_relative_to_reading = dynamic_noise == "reading";
    plan.unrecorded_protocol = protocol == "unrecorded";
    for (auto& d : plan.dynamic) d.integration_substeps = static_cast<int>(sweep_substeps);
    for (double r : extra_rates) plan.extra_quasi_static.push_back(foreign_bench::extra_rate(r));
    for (double p : extra_preloads) plan.extra_dynamic.push_back(foreign_bench::extra_preload(plan, p));
    for (double h : extra_holds) plan.extra_quasi_static.push_back(foreign_bench::extra_hold(h));
    foreign_bench::write_campaign_set(out, static_cast<int>(count), static_cast<int>(pairs), static_cast<int>(controls),
                                      static_cast<std::uint64_t>(seed), plan, std::cout,
                                      base_refit == "scale"    ? foreign_bench::BaseRefitUse::scale
                                      : base_refit == "report" ? foreign_bench::BaseRefitUse::report
                                                               : foreign_bench::BaseRefitUse::none,
                                      only);
  } catch (const std::exception& e) {
    std::cerr << "foreign_campaigns: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
