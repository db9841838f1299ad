// `cushion diagnose [MATERIAL.json] CAMPAIGN.json -o DIR`: which effect of the catalogue is missing from a
// calibrated material (ranked candidates, evidence, material-file fragment), calibration/diagnose.hpp.
// Without MATERIAL.json (the default path, from raw test files) the base is calibrated first by the `cushion fit`
// job into DIR/fit/, and every candidate is then fitted jointly with the base moduli (--joint-base), because a base
// fitted on data that contain the effect has absorbed part of it.
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "calibration/diagnose.hpp"
#include "calibration/diagnose_output.hpp"
#include "calibration/plot.hpp"
#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "material/io/material_file.hpp"
#include "tools/command.hpp"
#include "tools/fit_job.hpp"
#include "tools/forward_model_cli.hpp"
#include "tools/gnuplot.hpp"

namespace {

/// The base for a campaign given without a material: the `cushion fit` job with diagnose_base_fit_options() (refit on
/// every test, noise-weighted) into OUT/fit
/// (OUT prepared already). Returns the path of the material it wrote; throws std::runtime_error (exit 1) when
/// the fit wrote none.
std::string fit_base(const cushion::calibration::Campaign& campaign, const std::filesystem::path& out) {
  const std::filesystem::path fit_out = out / "fit";
  std::cout << "diagnose: no material given: calibrating the base from the campaign (cushion fit --refit-on all --refit-weights noise --free-tau -> " << fit_out.string()
            << ")\n";
  const auto result = cushion::tools::run_fit_job(campaign, cushion::calibration::diagnose_base_fit_options(), fit_out);
  const auto material = fit_out / "material.json";
  if (!std::filesystem::exists(material))
    throw std::runtime_error("diagnose: the fit of " + campaign.manifest.string() + " gave no usable material (paper: " +
                             result.paper_problem + "; refit: " + result.refit_problem + "); see " +
                             (fit_out / "report.md").string());
  return material.string();
}

/// From raw data: the base was fitted with the campaign's protocol defaults. The unrecorded protocol keys are searched
/// with that base (protocol_search.hpp); when other values fit better the base is fitted once more with them (into
/// OUT/fit, replacing the first fit) and `campaign` takes them; diagnose then searches again about them. Once: a second
/// fit/search round (measured 2026-11-25 on the one foreign control of ten that stays at 2.3x noise; the slow Prony
/// terms of a base fitted under one protocol trade against the dwell and cycles of another) moved nothing that
/// mattered and took 13 s more.
void fit_base_and_protocol(cushion::calibration::Campaign& campaign, const std::filesystem::path& out,
                           const cushion::calibration::DiagnoseOptions& o, cushion::material::MaterialDefinition& def) {
  using namespace cushion::calibration;
  const ProtocolSearch p = search_protocol(*def.model, campaign, estimate_noise(campaign), o.compare, o.strong_evidence);
  if (!p.moved) return;
  std::cout << "diagnose: the campaign does not record";
  for (const auto& k : p.keys) std::cout << " " << k.key << " (" << k.chosen << (k.chosen == k.assumed ? ", the default)" : ")");
  std::cout << ": these values fit the dynamic tests better with this base (chi2 " << p.chi2_assumed << " -> "
            << p.chi2_chosen << "); fitting the base again with them\n";
  campaign = p.campaign;
  def = cushion::material::read_material_file(fit_base(campaign, out));
}

struct DiagnoseCli {
  std::vector<std::string> files;  // [material] campaign
  cushion::io::OutputFolder out;
  std::vector<std::string> candidates;
  std::vector<double> noise_uncertainty;  // --noise-uncertainty QS,DYN (empty: the defaults)
  std::vector<double> polish_bounds;      // --polish-bounds TAU,ALPHA [decades] (empty: the defaults)
  bool held_out = false;
  bool fixed_base = false;
  bool fixed_times = false;
  bool assume_protocol = false;
  cushion::calibration::DiagnoseOptions options;
};

const cushion::tools::Registrar reg{"diagnose", [](CLI::App& app) {
  auto opt = std::make_shared<DiagnoseCli>();
  CLI::App* sub = app.add_subcommand(
      "diagnose", "Name the physical effect missing from a calibrated material: refit each catalogue effect, rank by BIC");
  sub->add_option("files", opt->files,
                  "[MATERIAL.json] CAMPAIGN.json: the campaign manifest, optionally after a calibrated base material; "
                  "without one the base is fitted first (cushion fit, into OUTPUT/fit) and --joint-base is implied")
      ->required()
      ->expected(1, 2);
  cushion::tools::add_output_folder_options(sub, opt->out, "output folder (diagnosis.md, report.json, fragment.json, plots)");
  opt->out.markers = {"diagnosis.md"};
  sub->add_option("--candidates", opt->candidates, "only these effect kinds (default: the whole catalogue)")->delimiter(',');
  sub->add_flag("--joint-base", opt->options.joint_base,
                "fit each effect together with the base moduli, started from the base refit (the default)");
  sub->add_flag("--fixed-base", opt->fixed_base,
                "fit only each effect's parameters on the given base (faster; an effect must then beat a refitted base "
                "on its own)")
      ->excludes("--joint-base");
  sub->add_flag("--fixed-prony-times", opt->fixed_times,
                "with a MATERIAL: the base refit keeps its Prony times tau_i (default: a factor in [0.316, 3.16] on each is "
                "fitted too); from raw data the fit has placed them already and they are always kept");
  sub->add_flag("--refit-exponents", opt->options.base_exponents,
                "the base refit and every joint candidate also fit a factor in [0.63, 1.58] on each hyperfoam exponent "
                "alpha_i; the base refit runs twice (exponents fixed, then free) and the candidates start from its first run "
                "(off by default: it loses some Mullins campaigns, docs/physics.md 9.8)");
  sub->add_option(
         "--polish", opt->options.polished_singles,
         "refit the N best supported singles once more with the base's Prony times and hyperfoam exponents free "
         "too and rank them by that fit (default " +
             std::to_string(cushion::calibration::DiagnoseOptions{}.polished_singles) +
             "; 0: off; support is still judged against the base refit without them)")
      ->check(CLI::Range(0, 5));
  sub->add_flag(
      "--polish-mullins-beta,!--no-polish-mullins-beta", opt->options.fit_polished_only,
      "after the polish, when the best single is Mullins, fit it once more from there with its beta free too and "
      "rank the single by that fit; the pairs start from the polish with beta held at 0.1 (on by default; "
      "--no-polish-mullins-beta holds beta at 0.1 throughout, docs/physics.md 9.41-9.42)");
  sub->add_flag("--continue-polish,!--no-continue-polish", opt->options.continue_unfinished_polish,
                "after the polish, when the best single's polish stopped at --max-iterations with a test still beyond "
                "noise, fit it once more from there for as many iterations and rank the single by that fit; the "
                "pairs start from the polish (on by default; docs/physics.md 9.44)");
  sub->add_option("--continuation-rounds", opt->options.continuation_rounds,
                  "a single named alone whose fit stopped at --max-iterations with a test beyond noise is fitted on "
                  "from there, up to N rounds of --max-iterations in all counting its polish's continuation, while "
                  "each gains at least dBIC 10; after the ranking, so it refines the named model only (default 3; "
                  "1: off; docs/physics.md 9.45)")
      ->check(CLI::Range(1, 10));
  sub->add_option(
         "--polish-challengers", opt->options.polished_challengers,
         "when a single is supported, polish also the N best near misses (singles above the base refit's "
         "dBIC but not by 10) and the base refit, and judge them against that polished refit; one ranks ahead of the "
         "leader only when it beats it by dBIC 10, else it is named as the leader's equal (default " +
             std::to_string(cushion::calibration::DiagnoseOptions{}.polished_challengers) +
             "; 0: off; docs/physics.md 9.29, 9.48)")
      ->check(CLI::Range(0, 4));
  sub->add_option(
         "--pair-share", opt->options.pair_share,
         "a pair is named only when its second effect explains at least this share of the chi2 the best single "
         "leaves, besides beating it by dBIC 10 (default " +
             cushion::io::format_double(cushion::calibration::DiagnoseOptions{}.pair_share) +
             "; 0: the dBIC rule alone; docs/physics.md 9.13)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_flag("--stop-at-noise", opt->options.stop_at_noise,
                "a baseline already within 1.5x its noise on every test ends the diagnosis at once with \"No effect is "
                "missing\" (faster; by default the candidates are still fitted and one beating a refitted base by dBIC "
                "10 is named: a pattern within 1.5x noise per test can still be evidence, docs/physics.md 9.33)");
  sub->add_option("--pair-stop-share", opt->options.pair_stop_share,
                  "a pair's fit stops after " +
                      std::to_string(cushion::calibration::DiagnoseOptions{}.pair_stop_iteration) +
                      " iterations when its second effect then explains less than this share of the chi2 the best "
                      "single leaves, and a pair whose start scan leaves it below this share is fitted again from "
                      "both single fits (default " +
                      cushion::io::format_double(cushion::calibration::DiagnoseOptions{}.pair_stop_share) +
                      "; 0: never stopped, and refitted only when no better than the single; docs/physics.md 9.21, "
                      "9.37)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_flag("--no-damage-start{false}", opt->options.damage_start,
                "fit Mullins only from the base refit, not also from a damage start (its d_inf and e_d estimated from "
                "the slowest quasi-static test's unloading over loading, relative to the base refit's where that "
                "reproduces the test within 3x noise; the hyperfoam refitted to the first loadings over 1 - d; "
                "docs/physics.md 9.27, 9.28)");
  sub->add_option("--pairs-from", opt->options.pairs_from,
                  "pairs are the best single with each of the next N - 1 singles that beat the baseline by dBIC 10 "
                  "(default " +
                      std::to_string(cushion::calibration::DiagnoseOptions{}.pairs_from) + "; 1: no pairs; " +
                      std::to_string(cushion::material::effect_catalog().size()) +
                      ": the best single with every other family of the catalogue)")
      ->check(CLI::Range(1, static_cast<int>(cushion::material::effect_catalog().size())));
  sub->add_option("--noise-uncertainty", opt->noise_uncertainty,
                  "QS,DYN: how far (a factor >= 1 on the RMS noise) each quasi-static and each dynamic test's noise "
                  "estimate may be off when deciding whether another family explains the tests about as well as the "
                  "winner (default " +
                      cushion::io::format_double(cushion::calibration::NoiseUncertainty{}.quasi_static) + "," +
                      cushion::io::format_double(cushion::calibration::NoiseUncertainty{}.dynamic) +
                      ", as measured for the estimators; 1,1: the plain dBIC rule; docs/physics.md 9.31)")
      ->expected(2)
      ->delimiter(',')
      ->check(CLI::Range(1.0, 100.0));
  const cushion::calibration::BaseFactorBounds polish_default = cushion::calibration::DiagnoseOptions{}.polish_bounds;
  sub->add_option("--polish-bounds", opt->polish_bounds,
                  "TAU,ALPHA: how far the polish may move each Prony time and each hyperfoam exponent, in decades (a "
                  "factor in [10^-b, 10^b]; default " +
                      cushion::io::format_double(polish_default.time_decades) + "," +
                      cushion::io::format_double(polish_default.exponent_decades) + ", the base refit's; " +
                      cushion::io::format_double(cushion::calibration::follow_up_polish_bounds.time_decades) + "," +
                      cushion::io::format_double(cushion::calibration::follow_up_polish_bounds.exponent_decades) +
                      ": what the verdict proposes when a polished winner leaves a test beyond noise; docs/physics.md "
                      "9.35)")
      ->expected(2)
      ->delimiter(',')
      ->check(CLI::Range(0.0, 2.0));
  sub->add_flag("--held-out", opt->held_out,
                "name an effect only if it also predicts each test left out of its fit better than the base refit "
                "(leave one test out; slower; off by default: with five tests of different kinds it vetoed the right "
                "family on 3 of 6 foreign effect campaigns, README)");
  sub->add_option("--threads", opt->options.threads, "candidates fitted in parallel (default 2)")->check(CLI::Range(1, 2));
  sub->add_option("--max-iterations", opt->options.max_iterations,
                  "Levenberg-Marquardt iterations per candidate (default " +
                      std::to_string(cushion::calibration::DiagnoseOptions{}.max_iterations) +
                      "; a candidate stopped by the limit is ranked with a warning)")
      ->check(CLI::Range(1, 1000));
  sub->add_option("--jacobian-steps-per-cycle", opt->options.jacobian_steps_per_cycle,
                  "time steps per fitted sine cycle of the cheaper model each Levenberg-Marquardt Jacobian is "
                  "differenced from (the cycles before them at half that; default " +
                      std::to_string(cushion::calibration::DiagnoseOptions{}.jacobian_steps_per_cycle) +
                      "; 0: the model itself; the cost and every accepted point stay the full model's; docs/physics.md "
                      "9.36)")
      ->check(CLI::IsMember(std::vector<int>{0}) | CLI::Range(16, 1000));
  sub->add_flag("--assume-protocol", opt->assume_protocol,
                "model every dynamic protocol key the campaign leaves out at its default (20 cycles, last 10 fitted; the "
                "--preload-rate ramp; no dwell; peak-to-peak amplitude) instead of searching it as a nuisance parameter");
  cushion::tools::add_forward_model_options(sub, opt->options.compare);
  sub->callback([opt] {
    using namespace cushion::calibration;
    const bool raw = opt->files.size() == 1;
    opt->out.inputs.assign(opt->files.begin(), opt->files.end());
    cushion::io::check_output_folder(opt->out);
    DiagnoseOptions o = opt->options;
    o.candidates = opt->candidates;
    if (opt->fixed_base && raw)
      throw cushion::InputError("--fixed-base: needs a material (a base fitted here is fitted jointly with each effect)");
    o.joint_base = !opt->fixed_base;
    o.held_out = opt->held_out;
    if (!opt->noise_uncertainty.empty())
      o.noise_uncertainty = {opt->noise_uncertainty.at(0), opt->noise_uncertainty.at(1)};
    if (!opt->polish_bounds.empty()) o.polish_bounds = {opt->polish_bounds.at(0), opt->polish_bounds.at(1)};
    o.search_protocol = !opt->assume_protocol;
    o.base_times = !opt->fixed_times && !raw;  // from raw data the fit has placed the times (--free-tau)
    for (const auto& k : o.candidates)
      if (!cushion::material::find_effect(k)) throw cushion::InputError("--candidates: unknown effect kind '" + k + "'");
    const std::string campaign_path = opt->files.back();
    std::optional<cushion::material::MaterialDefinition> given;
    if (!raw) given = cushion::material::read_material_file(opt->files.front());
    Campaign campaign = read_campaign(campaign_path);
    if (raw) cushion::io::prepare_output_folder(opt->out);  // the fit writes into OUT/fit
    const std::string material_path = raw ? fit_base(campaign, opt->out.dir) : opt->files.front();
    auto def = raw ? cushion::material::read_material_file(material_path) : *given;
    if (raw && o.search_protocol) fit_base_and_protocol(campaign, opt->out.dir, o, def);
    Diagnosis d = diagnose(def.spec, campaign, o, std::cout);
    if (raw)
      d.warnings.insert(d.warnings.begin(), "base material calibrated from this campaign by `cushion fit` (" +
                                                material_path + "); every candidate fitted jointly with the base moduli");
    for (const auto& w : specimen_warnings(def.spec.density, campaign)) d.warnings.insert(d.warnings.begin(), w);
    if (!raw) cushion::io::prepare_output_folder(opt->out);
    write_diagnosis_outputs(d, opt->out.dir, cushion::tools::gnuplot_path());
    std::cout << "\n" << diagnosis_markdown(d) << "\ndiagnose: " << d.seconds << " s; written to " << opt->out.dir.string() << "\n";
  });
}};

}  // namespace
