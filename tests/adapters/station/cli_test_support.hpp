// Runs the real `mocaplink` binary (MOCAPLINK_BINARY, set by CMake) for the station tests
// (station_cli_test, vicon_serve_test): exit code, stdout and stderr of one command.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace mocaplink::test {

struct ProcessResult {
  int exit_code = -1;  ///< -1 when the process did not exit normally (signal) or did not start
  std::string out;
  std::string err;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs the binary with `args` (shell-quoted by the caller) and waits for it to exit.
inline ProcessResult run_mocaplink(const std::string& args) {
  // One file per test process: ctest -j runs these tests' processes side by side.
  const std::string err_path =
      testing::TempDir() + "/station_cli_stderr_" + std::to_string(getpid()) + ".txt";
  const std::string command = std::string(MOCAPLINK_BINARY) + " " + args + " 2>" + err_path;
  ProcessResult run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) run.out.append(buffer, n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.err = read_file(err_path);
  return run;
}

}  // namespace mocaplink::test
