#pragma once
// Campaigns of the independent generator (tests/foreign), run as its own program (FOREIGN_CAMPAIGNS_BINARY), and
// the exact cushion material of a campaign's base foam. Nothing of tests/foreign is compiled into the tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "material/io/material_file.hpp"

namespace cushion::foreign_program {

/// `count` campaigns of `foreign_campaigns --seed seed --pairs pairs --controls controls [options]` in a fresh folder
/// under the temporary directory named `tag` and the process id.
inline std::filesystem::path generate(const std::string& tag, int count, unsigned long long seed, int pairs, int controls,
                                      const std::string& options = "") {
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("cushion_test_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  const std::string command = std::string("\"") + FOREIGN_CAMPAIGNS_BINARY + "\" --out \"" + d.string() + "\" --count " +
                              std::to_string(count) + " --seed " + std::to_string(seed) + " --pairs " +
                              std::to_string(pairs) + " --controls " + std::to_string(controls) + " " + options +
                              " > /dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return d;
}

/// report.json of `cushion diagnose DIR/campaign.json OPTIONS -o DIR/OUTPUT` (from raw data: the fit included); the verdict
/// is printed for the record.
inline nlohmann::json diagnose_raw(const std::filesystem::path& campaign_dir, const std::string& options,
                                   const std::string& output = "diag") {
  const std::string command = std::string("\"") + CUSHION_BINARY + "\" diagnose \"" +
                              (campaign_dir / "campaign.json").string() + "\" -o \"" +
                              (campaign_dir / output).string() + "\" " + options + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(campaign_dir / output / "report.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  std::cout << campaign_dir.filename().string() << ": " << r.at("verdict").get<std::string>() << "\n";
  return r;
}

/// The truth's base foam (truth.json "base") as a cushion material file: hyperfoam with nu = 0 (the foreign
/// machine's F = diag(l, 1, 1)) and the same relative Prony moduli (both FEBio-form decorators).
inline material::MaterialDefinition exact_material(const std::filesystem::path& campaign_dir) {
  std::ifstream in(campaign_dir / "truth.json");
  const nlohmann::json base = nlohmann::json::parse(in).at("base");
  nlohmann::json m{{"name", "foreign_truth"}, {"density_kg_m3", base.at("density_kg_m3")}};
  for (const auto& t : base.at("hyperfoam"))
    m["hyperfoam"]["terms"].push_back({{"mu_kPa", t.at("mu_kPa")}, {"alpha", t.at("alpha")}, {"nu", 0}});
  m["viscoelastic"]["moduli"] = "long_term";
  for (const auto& p : base.at("prony")) m["viscoelastic"]["prony"].push_back({{"g", p.at("g")}, {"tau_s", p.at("tau_s")}});
  std::ofstream(campaign_dir / "exact_material.json") << m.dump(1);
  return material::read_material_file(campaign_dir / "exact_material.json");
}

}  // namespace cushion::foreign_program
