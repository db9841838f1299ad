#pragma once
// Runs the built `cushion` program (path in CUSHION_BINARY) for the command-line tests.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace cli_test {

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

/// The path in double quotes, for the shell.
inline std::string quoted(const std::filesystem::path& path) {
  std::string q(1, '"');  // appended, not "\"" + ...: GCC 12 warns falsely (-Wrestrict) on that form once inlined
  q += path.string();
  q += '"';
  return q;
}

/// Runs a shell command with stderr merged into stdout.
inline CommandRun run_command(const std::string& shell_command) {
  const std::string command = shell_command + " 2>&1";
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) run.output += buffer;
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

/// Runs `cushion ARGUMENTS` with stderr merged into stdout.
inline CommandRun run_cushion(const std::string& arguments) { return run_command(quoted(CUSHION_BINARY) + " " + arguments); }

/// An empty folder <tmp>/<prefix><name of the running test>, fresh for each test.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Number of lines of `text` (a last line without '\n' counts).
inline std::size_t line_count(const std::string& text) {
  const std::size_t n = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  return n + (!text.empty() && text.back() != '\n');
}

/// "path size mtime" of every entry at or below `dir`, sorted; empty if `dir` does not exist. Equal
/// listings before and after a command: the command left the folder untouched.
inline std::vector<std::string> listing(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir, ec)) {
    const auto size = e.is_regular_file() ? e.file_size() : 0;
    out.push_back(fs::relative(e.path(), dir).string() + " " + std::to_string(size) + " " +
                  std::to_string(e.last_write_time().time_since_epoch().count()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The folder's listing on one line, for failure messages.
inline std::string listed(const std::filesystem::path& dir) {
  std::string text = dir.string() + ": [";
  for (const auto& entry : listing(dir)) text += " " + entry;
  return text + " ]";
}

/// Writes `text` to dir/name (a deck or case file of a test) and returns that path.
inline std::filesystem::path write_text(const std::filesystem::path& dir, const std::string& text,
                                        const std::string& name = "model.inp") {
  std::ofstream(dir / name) << text;
  return dir / name;
}

/// Line number (1-based) of the first line of `text` starting with `start`, -1 if none.
inline int line_of(const std::string& text, const std::string& start) {
  int n = 1;
  for (std::size_t at = 0; at < text.size(); at = text.find('\n', at) + 1, ++n)
    if (text.compare(at, start.size(), start) == 0) return n;
  return -1;
}

/// Bad input: exit code 2 and exactly one line, "cushion: input error: " (or "argument error") followed by a
/// message that contains every fragment (the file, the key or line, the problem).
inline void expect_input_error(const CommandRun& run, const std::vector<std::string>& fragments) {
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_EQ(line_count(run.output), 1u) << run.output;
  EXPECT_TRUE(run.output.rfind("cushion: input error: ", 0) == 0 || run.output.rfind("cushion: argument error: ", 0) == 0)
      << run.output;
  for (const std::string& f : fragments) EXPECT_NE(run.output.find(f), std::string::npos) << "'" << f << "' in\n" << run.output;
}

}  // namespace cli_test
