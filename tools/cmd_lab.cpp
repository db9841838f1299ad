// `cushion lab TRUTH.json -o DIR`: the virtual test lab (synthetic campaigns from a known material).
#include <iostream>

#include "calibration/lab.hpp"
#include "tools/command.hpp"

namespace {

struct LabOptions {
  std::string truth;
  cushion::io::OutputFolder out;
};

const cushion::tools::Registrar reg{"lab", [](CLI::App& app) {
  auto opt = std::make_shared<LabOptions>();
  CLI::App* sub = app.add_subcommand(
      "lab", "Generate a SYNTHETIC test campaign (quasi-static and dynamic tests) from a truth file");
  sub->add_option("truth", opt->truth, "truth file (JSON): material, specimen, protocols, noise")->required();
  cushion::tools::add_output_folder_options(sub, opt->out, "output folder for campaign.json and the CSV files");
  sub->callback([opt] {
    using namespace cushion::calibration;
    const LabTruth truth = read_lab_truth(opt->truth);
    cushion::io::check_output_folder(lab_output_folder(opt->out.dir, opt->out.overwrite, truth));
    run_lab(truth, opt->out.dir, std::cout);
    std::cout << "lab: campaign written to " << (opt->out.dir / "campaign.json").string() << "\n";
  });
}};

}  // namespace
