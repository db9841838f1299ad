#pragma once
/// `cushion fit` on a hyperfoam-only campaign: the fit's log lines and its output folder (README "cushion fit"):
/// material.json (hyperfoam, per-term nu), abaqus_hyperfoam.inp (*HYPERFOAM, N=.., MODULI=LONG TERM),
/// report.md, report.json, fit_<test>.csv (data and model per point), and the plots (CSV + gnuplot script +
/// PNG) hyperfoam_stress and hyperfoam_lateral_stretch. Written to DIR.partial and renamed: all or nothing.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "calibration/hyperfoam_campaign.hpp"
#include "calibration/hyperfoam_modes_fit.hpp"
#include "calibration/plot.hpp"

namespace cushion::calibration {

/// One line per test: mode, R^2 of the stress, max stress error / peak, max lateral-stretch error.
void log_hyperfoam_fit(const HyperfoamModesFit& fit, const HyperfoamCampaign& campaign, std::ostream& log);

/// The two plots: nominal stress and free-direction stretch, measured (points) vs fitted (lines), every test.
std::vector<Plot> hyperfoam_plots(const HyperfoamModesFit& fit, const HyperfoamCampaign& campaign);

/// Writes every output; `gnuplot` is the executable (empty: scripts and CSV only). Refuses an existing `dir`
/// that is not empty and not an earlier fit output (InputError). Returns the plot files.
std::vector<PlotFiles> write_hyperfoam_outputs(const HyperfoamModesFit& fit, const HyperfoamCampaign& campaign,
                                               const std::filesystem::path& dir, const std::string& gnuplot,
                                               std::ostream& log);

}  // namespace cushion::calibration
