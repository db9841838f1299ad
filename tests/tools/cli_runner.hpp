#pragma once
// Runs the built `cushion` program (path in CUSHION_BINARY) for the command-line tests.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace cli_test {

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

/// The path in double quotes, for the shell.
inline std::string quoted(const std::filesystem::path& path) { return "\"" + path.string() + "\""; }

/// Runs `cushion ARGUMENTS` with stderr merged into stdout.
inline CommandRun run_cushion(const std::string& arguments) {
  const std::string command = quoted(CUSHION_BINARY) + " " + arguments + " 2>&1";
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) run.output += buffer;
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace cli_test
