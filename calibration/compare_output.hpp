#pragma once
/// Outputs of `cushion compare`: report.json (every figure of CompareResult, for scripts), summary.md
/// (the per-test table), and per test a two-panel plot (model and measurement overlaid, residual below
/// with the +-1 noise band): compare_<test>.csv (columns with units), .gp, and the PNG when gnuplot runs.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibration/compare.hpp"

namespace cushion::calibration {

/// Every figure of `result` as JSON (stresses and moduli in kPa, forces in N, stiffnesses in N/mm, phases in degrees).
nlohmann::json compare_json(const CompareResult& result, const std::string& label);

/// The per-test table (markdown): test, kind, use, NRMSE, RMS error and noise in physical units,
/// error/noise, and the worst region.
std::string compare_table(const CompareResult& result);

/// Writes report.json, summary.md and the plots into `dir` (created); draws them with `gnuplot`
/// (empty: scripts only). Returns the PNG paths that were drawn.
std::vector<std::filesystem::path> write_compare_outputs(const CompareResult& result, const std::string& label,
                                                         const std::filesystem::path& dir, const std::string& gnuplot);

}  // namespace cushion::calibration
