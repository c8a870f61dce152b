// Runs the real `mocaplink check` binary on good and bad files and checks exit codes and output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace {

struct Run {
  int exit_code = -1;
  std::string stdout_text;
  std::string stderr_text;
};

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Runs `mocaplink check ARG` with stdout and stderr captured in files.
Run run_check(const std::string& arg) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("mocaplink_check_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto out = dir / "stdout";
  const auto err = dir / "stderr";
  const std::string command = std::string("'") + MOCAPLINK_BINARY + "' check '" + arg + "' >'" +
                              out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  Run run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.stdout_text = slurp(out);
  run.stderr_text = slurp(err);
  std::filesystem::remove_all(dir);
  return run;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path =
      std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(CheckCommand, GoodFileExitsZeroWithSummary) {
  const auto run = run_check(std::string(MOCAPLINK_EXAMPLES_DIR) + "/lab.toml");
  EXPECT_EQ(run.exit_code, 0) << run.stderr_text;
  EXPECT_THAT(run.stdout_text,
              testing::StartsWith("ok: 3 vehicles, source vicon://192.168.1.3?mode=push\n"));
  EXPECT_THAT(run.stdout_text, testing::HasSubstr("quad1: body Quad1, udp://192.168.1.21:14540"));
  // lab.toml's px4 and ardupilot vehicles are pointed at profile auto (issue 28).
  EXPECT_THAT(run.stdout_text,
              testing::HasSubstr("  hint: quad1: profile = \"auto\" sends the same and checks the "
                                 "vehicle's set-up by whichever autopilot it runs\n"));
  EXPECT_EQ(run.stderr_text, "");
}

TEST(CheckCommand, BadFileExitsOneWithEveryError) {
  const auto path = write_temp("bad.toml", R"([mocap]
source = "vicon://192.168.1.3"
[[vehicle]]
name = "quad1"
body = "Quad1"
link = "udp://192.168.1.21:14540"
system_id = 300
profile = "px4"
rate = 50
)");
  const auto run = run_check(path);
  std::filesystem::remove(path);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.stdout_text, "");
  EXPECT_EQ(run.stderr_text,
            path + ":7:13: vehicle[1].system_id: must be an integer from 1 to 255, got 300\n" +
                path + ":9:1: vehicle[1].rate: unknown key; did you mean \"rate_hz\"?\n" + path +
                ": 2 errors\n");
}

TEST(CheckCommand, SourceNotBuiltInIsAnError) {
  // A source this binary lacks: `run` refuses it, and so does check, with the same message.
  const auto path = write_temp("optitrack.toml", R"([mocap]
source = "optitrack://mocap-pc"
[[vehicle]]
name = "quad1"
body = "Quad1"
link = "udp://192.168.1.21:14540?bind=:14540"
system_id = 1
profile = "px4"
)");
  const auto run = run_check(path);
  std::filesystem::remove(path);
  EXPECT_EQ(run.exit_code, 1) << run.stderr_text;
  EXPECT_EQ(run.stdout_text, "");
  EXPECT_EQ(run.stderr_text,
            path +
                ":2:10: mocap.source: unknown source scheme \"optitrack\" (one of: "
                "natnet, qtm, replay, sim, vicon, vicon-udp, vrpn)\n" +
                path + ": 1 error\n");
}

TEST(CheckCommand, SyntaxErrorExitsOne) {
  const auto path = write_temp("syntax.toml", "[mocap\nsource = 1\n");
  const auto run = run_check(path);
  std::filesystem::remove(path);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.stderr_text, testing::StartsWith(path + ":1:"));
  EXPECT_THAT(run.stderr_text, testing::HasSubstr("TOML syntax error"));
}

TEST(CheckCommand, UnreadableFileExitsOne) {
  const auto run = run_check("/nonexistent/mocaplink.toml");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(
      run.stderr_text,
      "mocaplink check: cannot read /nonexistent/mocaplink.toml: No such file or directory\n");
  const auto dir = run_check(std::filesystem::temp_directory_path().string());
  EXPECT_EQ(dir.exit_code, 1);
  EXPECT_THAT(dir.stderr_text, testing::HasSubstr("Is a directory"));
}

}  // namespace
