#pragma once
/// Output folder of `cushion fit`: material_paper.json, material_refit.json, material.json (the default),
/// abaqus_paper.inp, abaqus_refit.inp, report.json, report.md and the plots (CSV + gnuplot script + PNG).
/// Everything is written to DIR.partial and renamed to DIR at the end: a failure leaves no partial output.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibration/fit_pipeline.hpp"
#include "calibration/plot.hpp"
#include "io/output_folder.hpp"

namespace cushion::calibration {

/// The report's plots (paper Fig. 8, Fig. 7, Fig. 4, the Table 2 protocol curve, model vs test).
std::vector<Plot> fit_plots(const FitResult& result, const Campaign& campaign);

/// The output-folder policy of `cushion fit` (io/output_folder.hpp): an earlier fit output holds report.md,
/// the campaign manifest is an input, the outputs are staged in DIR.partial.
io::OutputFolder fit_output_folder(const std::filesystem::path& dir, bool overwrite, const std::filesystem::path& manifest);

/// The common end of a fit output staged in `staging` (DIR.partial): draws `plots` there, writes report.json
/// (`report`) and report.md (`markdown` of the drawn plot files), replaces `dir` by the staging folder, and returns
/// the plot files at their final place. Notes on undrawn plots go to `log`.
std::vector<PlotFiles> finish_staged_fit_output(const std::vector<Plot>& plots, const std::filesystem::path& staging,
                                                const std::filesystem::path& dir, const std::string& gnuplot,
                                                std::ostream& log, const nlohmann::json& report,
                                                const std::function<std::string(const std::vector<PlotFiles>&)>& markdown);

/// Writes every output; `gnuplot` is the executable (empty: scripts and CSV only). Replaces an earlier fit
/// output in `dir`; refuses any other non-empty `dir` (InputError, fit_output_folder with overwrite).
/// Returns the plot files.
std::vector<PlotFiles> write_fit_outputs(const FitResult& result, const Campaign& campaign,
                                         const std::filesystem::path& dir, const std::string& gnuplot, std::ostream& log);

}  // namespace cushion::calibration
