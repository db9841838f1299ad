#pragma once
/// The `cushion fit` job from a campaign file to its output folder (material files, ABAQUS cards, report,
/// plots), with the console lines a user follows. Shared by `cushion fit` and by `cushion diagnose CAMPAIGN`,
/// which calibrates the base itself before naming a missing effect.
#include <filesystem>
#include <string>

#include "calibration/fit_pipeline.hpp"

namespace cushion::tools {

/// Checks the output folder `out` (calibration::fit_output_folder: an earlier fit output is replaced only with
/// `overwrite`), reads the campaign, runs calibration::fit_pipeline with `options` and writes the outputs to
/// `out`. Returns the pipeline's result (its default_material is what `out`/material.json holds, when written).
calibration::FitResult run_fit_job(const std::string& campaign_path, const calibration::FitOptions& options,
                                   const std::filesystem::path& out, bool overwrite);

}  // namespace cushion::tools
