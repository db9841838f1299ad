// cushion: nonlinear FE solver and material calibration toolkit for polyurethane seat foam.
#include <cstdio>
#include <exception>
#include <iostream>

#include "io/input_error.hpp"
#include "tools/command.hpp"

namespace cushion::tools {
std::vector<std::pair<std::string, Setup>>& registry() {
  static std::vector<std::pair<std::string, Setup>> commands;
  return commands;
}
}  // namespace cushion::tools

int main(int argc, char** argv) {
  CLI::App app{"cushion: visco-hyperelastic foam calibration and finite-element analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cushion 0.1.0");
  // Argument errors on one line, like every other input error.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("cushion: argument error: ") + e.what() + " (see cushion --help)\n";
  });
  for (auto& [name, setup] : cushion::tools::registry()) setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every argument error exits 2 like any other input error.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const cushion::InputError& e) {
    std::cerr << "cushion: input error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cushion: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
