#include "tools/fit_job.hpp"

#include <filesystem>
#include <iostream>

#include "calibration/campaign.hpp"
#include "calibration/fit_output.hpp"
#include "io/output_folder.hpp"
#include "tools/gnuplot.hpp"

namespace cushion::tools {

void check_fit_output_folder(const std::filesystem::path& out, bool overwrite, const std::filesystem::path& manifest) {
  io::check_output_folder(calibration::fit_output_folder(out, overwrite, manifest));
}

calibration::FitResult run_fit_job(const calibration::Campaign& campaign, const calibration::FitOptions& options,
                                   const std::filesystem::path& out) {
  using namespace calibration;
  std::cout << "fit: " << campaign.manifest.string() << ": " << campaign.quasi_static.size() << " quasi-static and "
            << campaign.dynamic.size() << " dynamic test(s)\n";
  FitResult result = fit_pipeline(campaign, options, std::cout);
  const auto plots = write_fit_outputs(result, campaign, out, gnuplot_path(), std::cout);
  std::cout << "fit: default material (" << (result.default_choice == DefaultMaterial::refit ? "refit" : "paper")
            << "): " << result.default_reason << "\n";
  std::cout << "fit: outputs in " << out.string() << "/ :";
  for (const char* f : {"material.json", "material_paper.json", "material_refit.json", "abaqus_paper.inp",
                        "abaqus_refit.inp", "report.md", "report.json"})
    if (std::filesystem::exists(out / f)) std::cout << " " << f;
  std::size_t drawn = 0;
  for (const auto& p : plots) drawn += p.drawn;
  std::cout << ", " << plots.size() << " plots (" << drawn << " PNG drawn)\n";
  return result;
}

}  // namespace cushion::tools
