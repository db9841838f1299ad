#pragma once
/// The fit report: every figure of `cushion fit` as JSON (units in the keys: kPa, s, 1/s, Hz, deg,
/// relative errors as fractions), and a Markdown summary (parameter tables and errors) for people.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibration/fit_pipeline.hpp"
#include "calibration/plot.hpp"

namespace cushion::calibration {

/// Every intermediate and final figure of the fit.
nlohmann::json report_json(const FitResult& result, const Campaign& campaign);

/// Markdown report; `plots` are listed with their PNG (or, if not drawn, their script).
std::string report_markdown(const FitResult& result, const Campaign& campaign, const std::vector<PlotFiles>& plots);

}  // namespace cushion::calibration
