// `cushion fit CAMPAIGN.json -o DIR`: the paper's identification method from test files to a material
// (steps 1-6), the Prony conversion for the solver (7) and the consistency refit (8), with a report.
#include <sstream>

#include "calibration/fit_output.hpp"
#include "calibration/fit_pipeline.hpp"
#include "calibration/hyperfoam_modes_output.hpp"
#include "io/input_error.hpp"
#include "io/output_folder.hpp"
#include "tools/command.hpp"
#include "tools/fit_job.hpp"
#include "tools/gnuplot.hpp"

namespace {

struct FitCliOptions {
  std::string campaign;
  cushion::io::OutputFolder out;
  int terms = 3;
  std::string nu = "0";
  std::vector<double> tau;
  bool no_refit = false;
  std::string default_material = "refit";
  std::string normalisation = "tangent";
  std::string refit_on = "calibration";
  std::string refit_weights = "peak";
  bool free_tau = false;
  int extra_terms = 1;
  int cycles = 20, fit_cycles = 10;
  double preload_rate = 30.0;
  bool relaxed_preload = false;
};

/// A hyperfoam-only campaign ("hyperfoam_tests"): --terms and --nu (a value fixes a common nu) apply, the
/// options of the Prony path do not.
void fit_hyperfoam_campaign(const FitCliOptions& opt, const CLI::App& sub) {
  using namespace cushion::calibration;
  cushion::tools::check_fit_output_folder(opt.out.dir, opt.out.overwrite, opt.campaign);
  std::cout << "fit: reading " << opt.campaign << " (hyperfoam-only campaign)\n";
  HyperfoamCampaign campaign = read_hyperfoam_campaign(opt.campaign);
  if (sub.count("--terms") > 0) campaign.settings.terms = opt.terms;
  for (const char* o : {"--tau", "--no-refit", "--extra-terms", "--default", "--normalisation", "--refit-on", "--refit-weights", "--free-tau", "--dynamic-cycles",
                        "--fit-cycles", "--preload-rate", "--relaxed-preload", "--nu"})
    if (sub.count(o) > 0) std::cout << "fit: note: " << o << " does not apply to a hyperfoam-only campaign (ignored)\n";
  std::cout << "fit: " << campaign.tests.size() << " test(s), " << campaign.settings.terms << " term(s), nu "
            << (campaign.settings.per_term_nu ? "per term" : "common") << "\n";
  const HyperfoamModesFit fit = fit_hyperfoam_modes(campaign.tests, campaign.settings);
  log_hyperfoam_fit(fit, campaign, std::cout);
  const auto plots = write_hyperfoam_outputs(fit, campaign, opt.out.dir, cushion::tools::gnuplot_path(), std::cout);
  std::size_t drawn = 0;
  for (const auto& p : plots) drawn += p.drawn;
  std::cout << "fit: outputs in " << opt.out.dir.string() << "/ : material.json abaqus_hyperfoam.inp report.md report.json, "
            << plots.size() << " plots (" << drawn << " PNG drawn)\n";
}

const cushion::tools::Registrar reg{"fit", [](CLI::App& app) {
  auto opt = std::make_shared<FitCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "fit", "Identify a visco-hyperfoam material from a test campaign (paper sections 2-3) and write a report");
  sub->add_option("campaign", opt->campaign, "campaign manifest (JSON) naming the test CSV files")->required();
  cushion::tools::add_output_folder_options(sub, opt->out, "output folder (material files, ABAQUS cards, report, plots)");
  sub->add_option("--terms", opt->terms, "hyperfoam terms N (1..6)")->check(CLI::Range(1, 6));
  sub->add_option("--nu", opt->nu, "Poisson ratio of the hyperfoam: a value in [0, 0.45] or 'fit'");
  sub->add_option("--tau", opt->tau, "Prony relaxation times [s] (default 0.01 0.1 1 10 100)")->delimiter(',');
  sub->add_flag("--no-refit", opt->no_refit, "skip the consistency refit (step 8)");
  sub->add_option("--default", opt->default_material, "material.json: 'refit' (if accepted) or 'paper'")
      ->check(CLI::IsMember({"paper", "refit"}));
  sub->add_option("--normalisation", opt->normalisation,
                  "relative Prony moduli of the paper's material: 'tangent' (a_i = E_i/K_v) or 'paper' (g_i = E_i/E_0)")
      ->check(CLI::IsMember({"paper", "tangent"}));
  sub->add_option("--refit-on", opt->refit_on,
                  "tests of the refit: 'calibration' (every quasi-static and dynamic test marked calibration; several "
                  "rates separate the long-term curve from the slow Prony terms) or 'all' (also the validation ones)")
      ->check(CLI::IsMember({"calibration", "all"}));
  sub->add_option("--refit-weights", opt->refit_weights,
                  "residuals of the refit: 'peak' (relative to each test's peak stress and to E', E'') or 'noise' (over "
                  "each sample's noise estimate, chi2, as compare and diagnose weigh them; diagnose's base fit)")
      ->check(CLI::IsMember({"peak", "noise"}));
  sub->add_flag("--free-tau", opt->free_tau,
                "the refit also moves each Prony time within a factor 3.16 of --tau's (default: the times are kept)");
  sub->add_option("--extra-terms", opt->extra_terms,
                  "the refit also tries N + 1 .. N + this hyperfoam terms, each kept when it halves the joint cost "
                  "(default 1; 0: N only)")
      ->check(CLI::Range(0, 2));
  sub->add_option("--dynamic-cycles", opt->cycles, "dynamic test: cycles run per frequency (paper: 20)")->check(CLI::PositiveNumber);
  sub->add_option("--fit-cycles", opt->fit_cycles, "dynamic test: last cycles measured per frequency (10)")->check(CLI::PositiveNumber);
  sub->add_option("--preload-rate", opt->preload_rate, "dynamic test: preload ramp speed [mm/min] (paper: 30)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--relaxed-preload", opt->relaxed_preload, "model the dynamic test about a fully relaxed preload");
  sub->callback([opt, sub] {
    using namespace cushion::calibration;
    if (is_hyperfoam_campaign(opt->campaign)) return fit_hyperfoam_campaign(*opt, *sub);
    FitOptions o;
    o.terms = opt->terms;
    if (opt->nu == "fit") {
      o.nu.reset();
    } else {
      std::istringstream in(opt->nu);
      double v = -1.0;
      in >> v;
      if (!in || !in.eof() || !(v >= 0.0 && v <= 0.45))
        throw cushion::InputError("--nu " + opt->nu + ": must be a number in [0, 0.45] or 'fit'");
      o.nu = v;
    }
    if (!opt->tau.empty()) {
      for (double t : opt->tau)
        if (!(t > 0.0)) throw cushion::InputError("--tau: relaxation times must be > 0");
      o.tau = opt->tau;
    }
    o.refit = !opt->no_refit;
    o.refit_on_all_tests = opt->refit_on == "all";
    o.noise_weighted_refit = opt->refit_weights == "noise";
    if (opt->free_tau) o.refit_options.times_range = free_times_range;
    o.extra_refit_terms = opt->extra_terms;
    if (opt->fit_cycles > opt->cycles) throw cushion::InputError("--fit-cycles: must not exceed --dynamic-cycles");
    o.dynamic_schedule.cycles = opt->cycles;
    o.dynamic_schedule.fit_cycles = opt->fit_cycles;
    o.dynamic_schedule.preload_rate_mm_min = opt->preload_rate;
    o.relaxed_preload = opt->relaxed_preload;
    o.default_material = opt->default_material == "paper" ? DefaultMaterial::paper : DefaultMaterial::refit;
    o.normalisation = opt->normalisation == "paper" ? PronyNormalisation::paper : PronyNormalisation::tangent;

    cushion::tools::check_fit_output_folder(opt->out.dir, opt->out.overwrite, opt->campaign);
    cushion::tools::run_fit_job(read_campaign(opt->campaign), o, opt->out.dir);
  });
}};

}  // namespace
