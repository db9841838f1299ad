#pragma once
/// Subcommand registry of the `cushion` program. Each tools/cmd_<name>.cpp defines
///   static const cushion::tools::Registrar reg{"name", [](CLI::App& app) { ... app.add_subcommand ... }};
/// so adding a subcommand needs no edit elsewhere. Callbacks throw cushion::InputError for bad
/// input (printed on one line, exit 2) and std::runtime_error for failures (exit 1).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "io/output_folder.hpp"

namespace cushion::tools {

using Setup = std::function<void(CLI::App& app)>;

/// All registered subcommands, in registration order.
std::vector<std::pair<std::string, Setup>>& registry();

struct Registrar {
  Registrar(std::string name, Setup setup) { registry().emplace_back(std::move(name), std::move(setup)); }
};

/// Adds `-o,--output DIR` (required) and `--overwrite` bound to `folder` (the policy in io/output_folder.hpp);
/// the command fills in the rest of `folder`.
inline void add_output_folder_options(CLI::App* sub, io::OutputFolder& folder, const std::string& description) {
  folder.command = "cushion " + sub->get_name();
  sub->add_option("-o,--output", folder.dir, description)->required();
  sub->add_flag("--overwrite", folder.overwrite,
                "replace the content of an existing non-empty output folder (only an earlier output of this command)");
}

}  // namespace cushion::tools
