#pragma once
/// Outputs of `cushion diagnose` in DIR: diagnosis.md (verdict, ranked candidates with their error per
/// test, evidence in words, the material-file fragment), report.json (every figure), fragment.json (the
/// "effects" list to put in the material file; absent when no effect is supported), material_extended.json
/// (the baseline plus the winner, ready for `cushion compare`), baseline/ and extended/ compare outputs
/// (compare_output.hpp) with their plots.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "calibration/diagnose.hpp"

namespace cushion::calibration {

nlohmann::json diagnosis_json(const Diagnosis& d);
std::string diagnosis_markdown(const Diagnosis& d);
void write_diagnosis_outputs(const Diagnosis& d, const std::filesystem::path& dir, const std::string& gnuplot);

}  // namespace cushion::calibration
