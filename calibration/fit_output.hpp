#pragma once
/// Output folder of `cushion fit`: material_paper.json, material_refit.json, material.json (the default),
/// abaqus_paper.inp, abaqus_refit.inp, report.json, report.md and the plots (CSV + gnuplot script + PNG).
/// Everything is written to DIR.partial and renamed to DIR at the end: a failure leaves no partial output.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "calibration/fit_pipeline.hpp"
#include "calibration/plot.hpp"

namespace cushion::calibration {

/// The report's plots (paper Fig. 8, Fig. 7, Fig. 4, the Table 2 protocol curve, model vs test).
std::vector<Plot> fit_plots(const FitResult& result, const Campaign& campaign);

/// Writes every output; `gnuplot` is the executable (empty: scripts and CSV only). Refuses an existing
/// `dir` that is not empty and not an earlier fit output (InputError). Returns the plot files.
std::vector<PlotFiles> write_fit_outputs(const FitResult& result, const Campaign& campaign,
                                         const std::filesystem::path& dir, const std::string& gnuplot, std::ostream& log);

}  // namespace cushion::calibration
