#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/temp_dir.hpp"

namespace slamkit::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout (and stderr, for RunCli)
};

// The slamkit binary: $SLAMKIT_CLI if set (to run the tests against another build), else the
// one built with the tests.
inline std::string CliPath() {
  const char* env = std::getenv("SLAMKIT_CLI");
  return env && *env ? env : SLAMKIT_CLI;
}

// Runs `prefix` (e.g. "taskset -c 0 "), the slamkit binary and `command_after_cli` through the
// shell and captures stdout only: the command redirects stderr as it likes.
inline CliResult RunShell(const std::string& command_after_cli, const std::string& prefix = "") {
  const std::string command = prefix + CliPath() + " " + command_after_cli;
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// Runs the slamkit binary with `args` through the shell and captures its output.
inline CliResult RunCli(const std::string& args) { return RunShell(args + " 2>&1"); }

// A fresh directory under the system temp directory, named after the running test.
inline std::filesystem::path FreshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("slamkit_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The short simulated scenario the command-line tests run (configs/short.yaml).
inline const std::string kShortScenario =
    std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml";

}  // namespace slamkit::testing
