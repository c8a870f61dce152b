// `mocaplink serve --protocol vicon --from sim` driven from outside: the real binary on
// 127.0.0.1 port 0 (its first stdout line names the bound port), read by our vicon:// client.
// Also the command's argument errors (exit 1, one clear message).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/sources/vicon_source.hpp"
#include "vicon_test_support.hpp"

extern char** environ;

namespace mocaplink::sources {
namespace {

struct Child {
  pid_t pid = -1;
  int out_fd = -1;  // the child's stdout
  int err_fd = -1;  // the child's stderr
};

Child spawn(const std::vector<std::string>& args) {
  std::array<int, 2> out{};
  std::array<int, 2> err{};
  EXPECT_EQ(pipe(out.data()), 0);
  EXPECT_EQ(pipe(err.data()), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  posix_spawn_file_actions_addclose(&actions, err[0]);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Child c;
  EXPECT_EQ(posix_spawn(&c.pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  close(err[1]);
  c.out_fd = out[0];
  c.err_fd = err[0];
  return c;
}

// One line from fd (blocking read; the child writes it once it listens: this is the readiness).
std::string read_line(int fd) {
  std::string line;
  char ch = 0;
  while (read(fd, &ch, 1) == 1 && ch != '\n') line.push_back(ch);
  return line;
}

std::string read_all(int fd) {
  std::string text;
  std::array<char, 512> buf{};
  ssize_t n = 0;
  while ((n = read(fd, buf.data(), buf.size())) > 0)
    text.append(buf.data(), static_cast<std::size_t>(n));
  return text;
}

// Kills the child if a failed assertion leaves the test early, so no server outlives its test.
struct KillOnExit {
  pid_t& pid;
  ~KillOnExit() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
};

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ViconServeCli, ServesSimBodiesToOurClient) {
  Child c = spawn({MOCAPLINK_BINARY, "serve", "--protocol", "vicon", "--from",
                   "sim://?bodies=2&noise_mm=0", "--listen", "127.0.0.1:0", "--rate", "100"});
  KillOnExit guard{c.pid};
  const std::string line = read_line(c.out_fd);
  // "serving vicon on HOST:PORT from SOURCE at RATE Hz"
  const auto on = line.find(" on ");
  ASSERT_NE(on, std::string::npos) << line;
  const std::string address = line.substr(on + 4, line.find(' ', on + 4) - on - 4);
  const auto port = static_cast<std::uint16_t>(std::stoi(address.substr(address.rfind(':') + 1)));

  ViconSourceOptions o;
  o.target = ViconOptions{"127.0.0.1", port, wire::vicon::StreamMode::server_push};
  ViconSource client(o, "vicon://127.0.0.1");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  const bool enough = got.wait_frames(5);
  client.stop();
  kill(c.pid, SIGTERM);
  EXPECT_EQ(wait_exit(c.pid), 0);
  c.pid = -1;
  const std::string err = read_all(c.err_fd);
  close(c.out_fd);
  close(c.err_fd);
  ASSERT_TRUE(enough) << err;

  for (const auto& e : got.events()) {
    if (!e.is_frame) continue;
    ASSERT_EQ(e.frame.bodies.size(), 2u);
    EXPECT_EQ(e.frame.bodies[0].name, "Body1");
    EXPECT_EQ(e.frame.bodies[1].name, "Body2");
    EXPECT_TRUE(e.frame.bodies[0].tracked);
    ASSERT_TRUE(e.frame.frame_rate_hz.has_value());
    EXPECT_DOUBLE_EQ(*e.frame.frame_rate_hz, 100.0);
    // Body1 hovers about a point 1.0 m up (sim_world.hpp): a sane height, in metres.
    EXPECT_NEAR(e.frame.bodies[0].p_world_m.z(), 1.0, 0.2);
  }
  EXPECT_NE(err.find("stopped"), std::string::npos) << err;
}

TEST(ViconServeCli, ArgumentErrorsExitOne) {
  const std::vector<std::vector<std::string>> cases = {
      {"--protocol", "optitrack", "--from", "sim"},
      {"--protocol", "vicon", "--from", "camera"},
      {"--protocol", "vicon", "--from", "sim", "--listen", "127.0.0.1:99999"},
      {"--protocol", "vicon", "--from", "sim://?bodys=2"},
      {"--protocol", "vicon", "--from", "sim", "--rate", "0"},
      {"--protocol", "vicon", "--from", "sim", "--to", "127.0.0.1:51001"},
      {"--protocol", "vicon", "--from", "sim", "--set", "version=3"},
      {"--protocol", "vicon", "--from", "sim", "--set", "version"},
  };
  const std::vector<std::string> expected = {"not supported yet",
                                             "bad --from",
                                             "bad --listen",
                                             "bodys",
                                             "--rate",
                                             "--to is only for",
                                             "unknown --set key 'version' for vicon",
                                             "bad --set 'version'"};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::vector<std::string> args = {MOCAPLINK_BINARY, "serve"};
    args.insert(args.end(), cases[i].begin(), cases[i].end());
    Child c = spawn(args);
    const std::string err = read_all(c.err_fd);
    (void)read_all(c.out_fd);
    close(c.out_fd);
    close(c.err_fd);
    EXPECT_EQ(wait_exit(c.pid), 1) << err;
    EXPECT_NE(err.find(expected[i]), std::string::npos) << err;
  }
}

}  // namespace
}  // namespace mocaplink::sources
