// cushion: nonlinear FE solver and material calibration toolkit for polyurethane seat foam.
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "io/input_error.hpp"
#include "tools/command.hpp"
#include "tools/mpi_launch.hpp"

namespace cushion::tools {
std::vector<std::pair<std::string, Setup>>& registry() {
  static std::vector<std::pair<std::string, Setup>> commands;
  return commands;
}
}  // namespace cushion::tools

int main(int argc, char** argv) {
  // Progress lines reach a log file or a pipe (`cushion diagnose ... | tee log`) as they are written, not at exit:
  // stdout (which std::cout writes through) is line-buffered even when it is not a terminal.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"cushion: visco-hyperelastic foam calibration and finite-element analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cushion 0.1.0");
  // Argument errors on one line, like every other input error.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("cushion: argument error: ") + e.what() + " (see cushion --help)\n";
  });
  for (auto& [name, setup] : cushion::tools::registry()) setup(app);
  // Under mpirun -np N every process runs this; one message is enough (errors of a distributed run
  // are met by every process alike, see tools/cmd_run.cpp).
  static std::ostream silent(nullptr);
  const bool first = cushion::tools::launched_rank() == 0;
  std::ostream& err = first ? std::cerr : silent;
  // Only process 0 returns the error's exit code (mpirun's code then): a process leaving with a non-zero code
  // makes mpirun end the others, which under load ended process 0 before its message was out (seen in ctest).
  auto failure = [first](int code) { return first ? code : 0; };
  if (cushion::tools::launched_processes() > 1 && !(argc > 1 && std::string(argv[1]) == "run")) {
    err << "cushion: input error: started by mpirun on " << cushion::tools::launched_processes()
        << " processes: only `cushion run` runs distributed (start the other commands without mpirun)\n";
    return failure(2);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every argument error exits 2 like any other input error.
    return app.exit(e, first ? std::cout : silent, err) == 0 ? 0 : failure(2);
  } catch (const cushion::InputError& e) {
    err << "cushion: input error: " << e.what() << "\n";
    return failure(2);
  } catch (const std::exception& e) {
    err << "cushion: error: " << e.what() << "\n";
    return failure(1);
  }
  return 0;
}
