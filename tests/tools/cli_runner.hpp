#pragma once
// Runs the built `cushion` program (path in CUSHION_BINARY) for the command-line tests.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

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

/// An empty folder <tmp>/<prefix><name of the running test>, fresh for each test.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cli_test
