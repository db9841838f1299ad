// `cushion diagnose MATERIAL.json CAMPAIGN.json -o DIR`: which effect of the catalogue is missing from a
// calibrated material (ranked candidates, evidence, material-file fragment), calibration/diagnose.hpp.
#include <filesystem>
#include <iostream>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "calibration/diagnose.hpp"
#include "calibration/diagnose_output.hpp"
#include "calibration/plot.hpp"
#include "io/input_error.hpp"
#include "material/io/material_file.hpp"
#include "tools/command.hpp"
#include "tools/forward_model_cli.hpp"
#include "tools/gnuplot.hpp"

namespace {

struct DiagnoseCli {
  std::string material, campaign, out;
  std::vector<std::string> candidates;
  cushion::calibration::DiagnoseOptions options;
};

const cushion::tools::Registrar reg{"diagnose", [](CLI::App& app) {
  auto opt = std::make_shared<DiagnoseCli>();
  CLI::App* sub = app.add_subcommand(
      "diagnose", "Name the physical effect missing from a calibrated material: refit each catalogue effect, rank by BIC");
  sub->add_option("material", opt->material, "calibrated baseline material file (JSON)")->required();
  sub->add_option("campaign", opt->campaign, "campaign manifest (JSON)")->required();
  sub->add_option("-o,--output", opt->out, "output folder (diagnosis.md, report.json, fragment.json, plots)")->required();
  sub->add_option("--candidates", opt->candidates, "only these effect kinds (default: the whole catalogue)")->delimiter(',');
  sub->add_flag("--joint-base", opt->options.joint_base,
                "fit each effect together with the base moduli (for a baseline calibrated on data that contain it)");
  sub->add_option("--threads", opt->options.threads, "candidates fitted in parallel (default 2)")->check(CLI::Range(1, 2));
  sub->add_option("--max-iterations", opt->options.max_iterations,
                  "Levenberg-Marquardt iterations per candidate (default " +
                      std::to_string(cushion::calibration::DiagnoseOptions{}.max_iterations) +
                      "; a candidate stopped by the limit is ranked with a warning)")
      ->check(CLI::Range(1, 1000));
  cushion::tools::add_forward_model_options(sub, opt->options.compare);
  sub->callback([opt] {
    using namespace cushion::calibration;
    const auto def = cushion::material::read_material_file(opt->material);
    const Campaign campaign = read_campaign(opt->campaign);
    DiagnoseOptions o = opt->options;
    o.candidates = opt->candidates;
    for (const auto& k : o.candidates)
      if (!cushion::material::find_effect(k)) throw cushion::InputError("--candidates: unknown effect kind '" + k + "'");
    Diagnosis d = diagnose(def.spec, campaign, o, std::cout);
    for (const auto& w : specimen_warnings(def.spec.density, campaign)) d.warnings.insert(d.warnings.begin(), w);
    write_diagnosis_outputs(d, opt->out, cushion::tools::gnuplot_path());
    std::cout << "\n" << diagnosis_markdown(d) << "\ndiagnose: " << d.seconds << " s; written to " << opt->out << "\n";
  });
}};

}  // namespace
