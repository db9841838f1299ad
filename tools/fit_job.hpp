#pragma once
/// The `cushion fit` job from a campaign file to its output folder (material files, ABAQUS cards, report,
/// plots), with the console lines a user follows. Shared by `cushion fit` and by `cushion diagnose CAMPAIGN`,
/// which calibrates the base itself before naming a missing effect.
#include <filesystem>
#include <string>

#include "calibration/campaign.hpp"
#include "calibration/fit_pipeline.hpp"

namespace cushion::tools {

/// The output folder check of the fit job (calibration::fit_output_folder: an earlier fit output is replaced only
/// with `overwrite`); call it before reading the campaign, so that a refused folder costs nothing.
void check_fit_output_folder(const std::filesystem::path& out, bool overwrite, const std::filesystem::path& manifest);

/// Runs calibration::fit_pipeline on the campaign (read already) with `options` and writes the outputs to `out`.
/// Returns the pipeline's result (its default_material is what `out`/material.json holds, when written).
calibration::FitResult run_fit_job(const calibration::Campaign& campaign, const calibration::FitOptions& options,
                                   const std::filesystem::path& out);

}  // namespace cushion::tools
