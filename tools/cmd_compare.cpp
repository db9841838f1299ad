// `cushion compare [MATERIAL.json] CAMPAIGN.json -o DIR [--run RUN_DIR]... [--label NAME] [--history DIR]`:
// model vs every test of a campaign with error figures per test and region next to the measurement noise,
// plots, report.json, and optionally a history of runs (error per test across model versions).
// Material-level tests run through the material model (MATERIAL); structure-level tests (indentation,
// dynamic_stiffness) are read from the output folders of `cushion run` (--run).
#include <filesystem>
#include <iostream>

#include "calibration/campaign.hpp"
#include "calibration/compare.hpp"
#include "calibration/compare_output.hpp"
#include "calibration/compare_structure.hpp"
#include "calibration/plot.hpp"
#include "calibration/run_history.hpp"
#include "material/io/material_file.hpp"
#include "tools/command.hpp"
#include "tools/forward_model_cli.hpp"
#include "tools/gnuplot.hpp"

namespace {

struct CompareCli {
  std::vector<std::string> files;  // [material] campaign
  std::vector<std::string> runs;
  cushion::io::OutputFolder out;
  std::string label, history;
  cushion::calibration::CompareOptions model = [] {
    cushion::calibration::CompareOptions o;
    o.step_check = true;
    return o;
  }();
};

/// Before any computation: every --run folder exists, the output folder and the history folder can be written.
void check_folders(CompareCli& opt) {
  for (const auto& run : opt.runs) cushion::io::require_input_folder(run, "--run");
  opt.out.inputs.assign(opt.files.begin(), opt.files.end());
  opt.out.inputs.insert(opt.out.inputs.end(), opt.runs.begin(), opt.runs.end());
  if (!opt.history.empty()) opt.out.inputs.emplace_back(opt.history);  // kept across runs: never emptied by --overwrite
  cushion::io::check_output_folder(opt.out);
  if (opt.history.empty()) return;
  cushion::io::OutputFolder history;
  history.dir = opt.history;
  history.option = "--history";
  history.append = true;
  cushion::io::check_output_folder(history);
}

const cushion::tools::Registrar reg{"compare", [](CLI::App& app) {
  auto opt = std::make_shared<CompareCli>();
  CLI::App* sub = app.add_subcommand("compare", "Compare a material and/or FE runs with every test of a campaign (error per "
                                                "test and region vs measurement noise, plots, report.json)");
  sub->add_option("files", opt->files,
                  "MATERIAL.json CAMPAIGN.json, or CAMPAIGN.json alone with --run (structure-level tests only)")
      ->required()
      ->expected(1, 2);
  cushion::tools::add_output_folder_options(sub, opt->out, "output folder (report.json, summary.md, compare_<test>.png/.csv/.gp)");
  opt->out.markers = {"summary.md"};
  sub->add_option("--run", opt->runs,
                  "output folder of a `cushion run` holding the model side of the structure-level tests (repeatable; "
                  "each test uses the first folder that has its file)");
  sub->add_option("--label", opt->label, "model version name for the report and the history (default: material name)");
  sub->add_option("--history", opt->history, "folder of the run history (history.csv and history_plot.png), appended");
  cushion::tools::add_forward_model_options(sub, opt->model);
  sub->add_flag("--no-step-check{false}", opt->model.step_check,
                "skip the run of each dynamic test at half the steps per cycle that estimates the sweep's time-step "
                "error (summary.md, report.json step_error_over_noise; docs/physics.md 9.39)");
  sub->callback([opt] {
    using namespace cushion::calibration;
    const bool with_material = opt->files.size() == 2;
    if (!with_material && opt->runs.empty())
      throw CLI::ValidationError("compare", "give MATERIAL.json CAMPAIGN.json, or CAMPAIGN.json with --run RUN_DIR");
    check_folders(*opt);
    const Campaign campaign = read_campaign(opt->files.back());
    const CompareOptions& o = opt->model;
    CompareResult r;
    std::string label = opt->label;
    if (with_material) {
      const auto def = cushion::material::read_material_file(opt->files.front());
      r = compare_campaign(*def.model, campaign, o);
      for (const auto& w : specimen_warnings(def.spec.density, campaign)) r.warnings.insert(r.warnings.begin(), w);
      if (label.empty()) label = def.spec.name;
    } else {
      if (!campaign.quasi_static.empty() || !campaign.dynamic.empty())
        r.warnings.push_back("no material given: the " + std::to_string(campaign.quasi_static.size() + campaign.dynamic.size()) +
                             " material-level tests are not compared");
      if (label.empty()) label = std::filesystem::path(opt->runs.front()).filename().string();
    }
    for (const auto& w : coverage_warnings(campaign)) r.warnings.push_back(w);
    const std::size_t structure_tests = campaign.indentation.size() + campaign.stiffness.size();
    if (structure_tests > 0 && opt->runs.empty())
      r.warnings.push_back("the campaign has " + std::to_string(structure_tests) +
                           " structure-level tests: give --run RUN_DIR (the output folder of `cushion run`) to compare them");
    else if (structure_tests == 0 && !opt->runs.empty())
      r.warnings.push_back("--run given but the campaign has no structure-level test (kind indentation or dynamic_stiffness)");
    std::vector<std::filesystem::path> runs(opt->runs.begin(), opt->runs.end());
    if (!runs.empty())
      for (auto& t : compare_structure(campaign, runs, r.warnings)) r.tests.push_back(std::move(t));
    const std::string gnuplot = cushion::tools::gnuplot_path();
    cushion::io::prepare_output_folder(opt->out);
    const auto drawn = write_compare_outputs(r, label, opt->out.dir, gnuplot);
    std::cout << "cushion compare: " << label << " vs " << campaign.manifest.string() << " (" << r.tests.size()
              << " tests, " << r.seconds << " s)\n\n"
              << compare_table(r) << "\n";
    for (const auto& w : r.warnings) std::cout << "warning: " << w << "\n";
    std::cout << (r.at_noise_level(o.noise_level_ratio) ? "every test is at the noise level (error <= "
                                                        : "some tests fail beyond noise (error > ")
              << o.noise_level_ratio << " x noise)\n";
    std::cout << "written: " << (opt->out.dir / "report.json").string() << ", " << drawn.size()
              << " plots" << (gnuplot.empty() ? " (gnuplot not found: .gp scripts only)" : "") << "\n";
    if (!opt->history.empty()) {
      const int run = append_history(opt->history, label, r, gnuplot);
      std::cout << "history: run " << run << " appended to " << (std::filesystem::path(opt->history) / "history.csv").string()
                << "\n";
    }
  });
}};

}  // namespace
