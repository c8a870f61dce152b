// Issue 4's done-criterion through the real binary: `mocaplink bodies --source vicon://...` shows
// the bodies that `mocaplink serve --protocol vicon --from sim` serves; and an unreachable Vicon
// server is reported as not connected with exit code 2.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_test_support.hpp"

extern char** environ;

namespace {

using mocaplink::test::ProcessResult;
using mocaplink::test::run_mocaplink;

/// `mocaplink serve` as a child process; readiness is its "serving vicon on HOST:PORT" line.
class Server {
 public:
  Server() {
    int fds[2];
    if (pipe(fds) != 0) return;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    std::string binary = MOCAPLINK_BINARY;
    std::string a1 = "serve", a2 = "--protocol", a3 = "vicon", a4 = "--from",
                a5 = "sim://?bodies=3&seed=4", a6 = "--listen", a7 = "127.0.0.1:0", a8 = "--rate",
                a9 = "100";
    char* argv[] = {binary.data(), a1.data(), a2.data(), a3.data(), a4.data(), a5.data(),
                    a6.data(),     a7.data(), a8.data(), a9.data(), nullptr};
    if (posix_spawn(&pid_, binary.c_str(), &actions, nullptr, argv, environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    out_ = fdopen(fds[0], "r");
    char line[256] = {};
    // Blocks until the server has bound its port (or exits, closing the pipe).
    if (out_ != nullptr && fgets(line, sizeof line, out_) != nullptr) {
      const std::string text(line);
      const auto colon = text.find(':', text.find("127.0.0.1"));
      if (text.rfind("serving vicon on 127.0.0.1:", 0) == 0 && colon != std::string::npos) {
        port_ = std::stoi(text.substr(colon + 1));
      }
    }
  }
  ~Server() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      int status = 0;
      waitpid(pid_, &status, 0);
    }
    if (out_ != nullptr) fclose(out_);
  }
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;
  [[nodiscard]] int port() const { return port_; }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
  int port_ = 0;
};

TEST(ViconServe, BodiesShowsWhatServeServes) {
  const Server server;
  ASSERT_GT(server.port(), 0) << "serve did not report its port";
  const ProcessResult run = run_mocaplink(
      "bodies --source vicon://127.0.0.1:" + std::to_string(server.port()) + " --seconds 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j.at("connected"), true);
  EXPECT_GT(j.at("frames").get<int>(), 20);  // ~200 at 100 Hz; only "frames flow" matters
  EXPECT_GT(j.at("frame_rate_hz").get<double>(), 20.0);
  EXPECT_LT(j.at("frame_rate_hz").get<double>(), 200.0);
  const auto& bodies = j.at("bodies");
  ASSERT_EQ(bodies.size(), 3u) << run.out;
  // The simulator's layout (sim_world.hpp): bodies 2.5 m apart along x at heights 1.0, 1.2 and
  // 1.5 m — in metres here, so the emulator's mm and the client's mm → m cancel correctly.
  const double centre_x[] = {-2.5, 0.0, 2.5};
  const double height_z[] = {1.0, 1.2, 1.5};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& b = bodies[i];
    EXPECT_EQ(b.at("name"), "Body" + std::to_string(i + 1));
    EXPECT_EQ(b.at("tracked"), true);
    EXPECT_GT(b.at("frames_tracked").get<int>(), 20);
    EXPECT_NEAR(b.at("p_m")[0].get<double>(), centre_x[i], 1.05);
    EXPECT_NEAR(b.at("p_m")[2].get<double>(), height_z[i], 0.11);
    double norm_sq = 0.0;
    for (const auto& c : b.at("q_wxyz")) norm_sq += c.get<double>() * c.get<double>();
    EXPECT_NEAR(norm_sq, 1.0, 1e-6);
  }
}

TEST(ViconServe, UnreachableServerIsNotConnectedAndExitsTwo) {
  // A port that nobody listens on: bind an ephemeral port, then close it.
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  const int port = ntohs(addr.sin_port);
  close(fd);
  const ProcessResult run = run_mocaplink(
      "bodies --source vicon://127.0.0.1:" + std::to_string(port) + " --seconds 1 --json");
  EXPECT_EQ(run.exit_code, 2);
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j.at("connected"), false);
  EXPECT_EQ(j.at("frames"), 0);
  EXPECT_TRUE(j.at("bodies").empty());
}

}  // namespace
