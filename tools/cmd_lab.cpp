// `cushion lab TRUTH.json -o DIR`: the virtual test lab (synthetic campaigns from a known material).
#include <iostream>

#include "calibration/lab.hpp"
#include "tools/command.hpp"

namespace {

struct LabOptions {
  std::string truth;
  std::string out;
};

const cushion::tools::Registrar reg{"lab", [](CLI::App& app) {
  auto opt = std::make_shared<LabOptions>();
  CLI::App* sub = app.add_subcommand(
      "lab", "Generate a SYNTHETIC test campaign (quasi-static and dynamic tests) from a truth file");
  sub->add_option("truth", opt->truth, "truth file (JSON): material, specimen, protocols, noise")->required();
  sub->add_option("-o,--output", opt->out, "output folder for campaign.json and the CSV files")->required();
  sub->callback([opt] {
    const auto truth = cushion::calibration::read_lab_truth(opt->truth);
    cushion::calibration::run_lab(truth, opt->out, std::cout);
    std::cout << "lab: campaign written to " << opt->out << "/campaign.json\n";
  });
}};

}  // namespace
