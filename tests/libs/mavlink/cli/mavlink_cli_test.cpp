// The real `mocaplink` binary: `mavlink encode` reproduces every golden frame byte for byte,
// `mavlink decode` gives back the golden fields and checks signatures, bad input exits 1, and
// `mavlink listen` prints frames received over UDP and exits 0 on Ctrl-C.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

extern char** environ;

namespace {

using nlohmann::json;

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string temp_path(const std::string& tag) {
  return ::testing::TempDir() + "mavlink_cli_" + std::to_string(getpid()) + "_" + tag;
}

// Runs the binary with `args`, stdin from `input`; stdout/stderr through files (no pipe deadlock).
Result run(std::vector<std::string> args, const std::string& input = "") {
  const std::string in_path = temp_path("in");
  const std::string out_path = temp_path("out");
  const std::string err_path = temp_path("err");
  std::ofstream(in_path) << input;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, in_path.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  args.insert(args.begin(), MOCAPLINK_BIN);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  Result r;
  if (posix_spawn(&pid, MOCAPLINK_BIN, &actions, nullptr, argv.data(), environ) == 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

json golden() {
  std::ifstream in(MAVLINK_GOLDEN);
  return json::parse(in);
}

TEST(MavlinkCli, EncodeReproducesEveryGoldenFrame) {
  const json doc = golden();
  const Result r = run({"mavlink", "encode", MAVLINK_GOLDEN});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), doc["vectors"].size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& v = doc["vectors"][i];
    EXPECT_EQ(lines[i], v["id"].get<std::string>() + " " + v["expected_hex"].get<std::string>());
  }
}

TEST(MavlinkCli, EncodeSingleObjectFromStdin) {
  const Result r = run({"mavlink", "encode", "-"},
                       R"({"id":"hb","msg":"HEARTBEAT","seq":0,"sysid":1,"compid":197,
                           "fields":{"type":18,"autopilot":8,"system_status":4,"mavlink_version":3}})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "hb fd0900000001c50000000000000012080004031ee4\n");
}

// Decoded field equals the golden JSON value (float32-aware; "NaN"; decimal-string int64).
void expect_same(const json& got, const json& want, const std::string& where) {
  if (want.is_array()) {
    ASSERT_TRUE(got.is_array()) << where;
    ASSERT_EQ(got.size(), want.size()) << where;
    for (std::size_t i = 0; i < want.size(); ++i) expect_same(got[i], want[i], where);
  } else if (want.is_string()) {
    EXPECT_EQ(got, want) << where;  // "NaN" or a 64-bit integer
  } else if (want.is_number_float() && want.get<double>() == 0 &&
             std::signbit(want.get<double>())) {
    EXPECT_EQ(got, "-0") << where;
  } else if (want.is_number_float()) {
    ASSERT_TRUE(got.is_number()) << where << " " << got;
    EXPECT_EQ(static_cast<float>(got.get<double>()), static_cast<float>(want.get<double>()))
        << where;
  } else {
    EXPECT_EQ(got.get<std::int64_t>(), want.get<std::int64_t>()) << where;
  }
}

TEST(MavlinkCli, DecodeGivesBackGoldenFieldsAndChecksSignatures) {
  const json doc = golden();
  std::string input;
  for (const auto& v : doc["vectors"]) input += v["expected_hex"].get<std::string>() + "\n";
  const Result r = run({"mavlink", "decode", "--key", doc["key_hex"].get<std::string>()}, input);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), doc["vectors"].size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& v = doc["vectors"][i];
    SCOPED_TRACE(v["id"].get<std::string>());
    const json got = json::parse(lines[i]);
    for (const char* key : {"msgid", "name", "seq", "sysid", "compid", "len", "incompat_flags",
                            "compat_flags", "crc", "fields"}) {
      EXPECT_TRUE(got.contains(key)) << key;
    }
    EXPECT_EQ(got["name"], v["msg"]);
    EXPECT_EQ(got["seq"], v["seq"]);
    EXPECT_EQ(got["sysid"], v["sysid"]);
    EXPECT_EQ(got["compid"], v["compid"]);
    for (const auto& [name, value] : v["fields"].items()) {
      ASSERT_TRUE(got["fields"].contains(name)) << name;
      // The golden file writes integer-valued floats as 0 or 0.0; both mean float 0.
      if (value.is_number_integer() && got["fields"][name].is_number_float()) {
        EXPECT_EQ(got["fields"][name].get<double>(), value.get<double>()) << name;
      } else {
        expect_same(got["fields"][name], value, name);
      }
    }
    if (v.contains("sign")) {
      EXPECT_EQ(got["link_id"], v["sign"]["link_id"]);
      EXPECT_EQ(got["sig_timestamp"], v["sign"]["timestamp"]);
      EXPECT_EQ(got["signature_valid"], true);
      EXPECT_EQ(got["signature"].get<std::string>(),
                v["expected_hex"].get<std::string>().substr(
                    v["expected_hex"].get<std::string>().size() - 12));
    } else {
      EXPECT_FALSE(got.contains("signature_valid"));
    }
  }
}

TEST(MavlinkCli, DecodeWrongKeyMarksSignatureInvalid) {
  const Result r = run({"mavlink", "decode", "--key", std::string(64, '0')},
                       "fd0901000f01c50000000000000012080004037efe0100b88993b31cbe3a9d792e48\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["signature_valid"], false);
}

TEST(MavlinkCli, DecodeSeveralFramesPerLineWhitespaceTolerantAndSpecials) {
  // Two frames on one line, split by spaces mid-frame; LOCAL_POSITION_NED with vz = -0.0.
  const std::string negzero =
      "fd1c00000d01c5200000000000000000000000000000000000000000000000000000000000803011";
  const Result r =
      run({"mavlink", "decode"}, "  fd0100000b01 c56f000000a847" + negzero.substr(0, 30) + "\t " +
                                     negzero.substr(30) + "  \n\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(json::parse(lines[0])["fields"]["ts1"], "0");
  EXPECT_EQ(json::parse(lines[0])["len"], 1);
  EXPECT_EQ(json::parse(lines[1])["fields"]["vz"], "-0");
}

TEST(MavlinkCli, BadInputExitsOneWithMessage) {
  const Result not_hex = run({"mavlink", "decode"}, "fd09zz\n");
  EXPECT_EQ(not_hex.exit_code, 1);
  EXPECT_NE(not_hex.err.find("line 1"), std::string::npos) << not_hex.err;
  const Result bad_crc = run({"mavlink", "decode"}, "fd0900000001c50000000000000012080004031ee5\n");
  EXPECT_EQ(bad_crc.exit_code, 1);
  EXPECT_NE(bad_crc.err.find("bad_crc"), std::string::npos) << bad_crc.err;
  const Result truncated = run({"mavlink", "decode"}, "fd0900000001c5000000\n");
  EXPECT_EQ(truncated.exit_code, 1);
  EXPECT_NE(truncated.err.find("truncated"), std::string::npos) << truncated.err;
  const Result bad_json = run({"mavlink", "encode"}, "{not json");
  EXPECT_EQ(bad_json.exit_code, 1);
  EXPECT_NE(bad_json.err.find("invalid JSON"), std::string::npos) << bad_json.err;
  const Result bad_field = run({"mavlink", "encode"}, R"({"msg":"HEARTBEAT","fields":{"typo":1}})");
  EXPECT_EQ(bad_field.exit_code, 1);
  EXPECT_NE(bad_field.err.find("no field 'typo'"), std::string::npos) << bad_field.err;
  const Result range = run({"mavlink", "encode"}, R"({"msg":"HEARTBEAT","fields":{"type":256}})");
  EXPECT_EQ(range.exit_code, 1);
  EXPECT_NE(range.err.find("out of range"), std::string::npos) << range.err;
  const Result no_file = run({"mavlink", "decode", "/nonexistent/frames.hex"});
  EXPECT_EQ(no_file.exit_code, 1);
  const Result bad_url = run({"mavlink", "listen", "tcp://127.0.0.1:5"});
  EXPECT_EQ(bad_url.exit_code, 1);
  EXPECT_NE(bad_url.err.find("udp://"), std::string::npos) << bad_url.err;
}

// Reads one line from fd (blocking: readiness comes from the child's own output, no sleeps).
std::string read_line(int fd) {
  std::string line;
  char c = 0;
  while (read(fd, &c, 1) == 1 && c != '\n') line += c;
  return line;
}

TEST(MavlinkCli, ListenPrintsFramesAndExitsZeroOnSigint) {
  int out_pipe[2];
  int err_pipe[2];
  ASSERT_EQ(pipe(out_pipe), 0);
  ASSERT_EQ(pipe(err_pipe), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, err_pipe[0]);
  std::vector<std::string> args = {MOCAPLINK_BIN, "mavlink", "listen", "udp://127.0.0.1:0"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, MOCAPLINK_BIN, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  close(err_pipe[1]);

  const std::string banner = read_line(err_pipe[0]);  // "mocaplink: listening on udp://IP:PORT"
  const auto colon = banner.rfind(':');
  ASSERT_NE(colon, std::string::npos) << banner;
  const int port = std::atoi(banner.c_str() + colon + 1);
  ASSERT_GT(port, 0) << banner;

  // One datagram, two frames (HEARTBEAT + all-zero TIMESYNC golden frames).
  const std::vector<std::uint8_t> datagram = {0xfd, 0x09, 0x00, 0x00, 0x00, 0x01, 0xc5, 0x00, 0x00,
                                              0x00, 0x00, 0x00, 0x00, 0x00, 0x12, 0x08, 0x00, 0x04,
                                              0x03, 0x1e, 0xe4, 0xfd, 0x01, 0x00, 0x00, 0x0b, 0x01,
                                              0xc5, 0x6f, 0x00, 0x00, 0x00, 0xa8, 0x47};
  const int sock = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(sendto(sock, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&to),
                   sizeof(to)),
            static_cast<ssize_t>(datagram.size()));
  close(sock);
  const json first = json::parse(read_line(out_pipe[0]));
  const json second = json::parse(read_line(out_pipe[0]));
  EXPECT_EQ(first["name"], "HEARTBEAT");
  EXPECT_EQ(first["fields"]["type"], 18);
  EXPECT_EQ(second["name"], "TIMESYNC");
  EXPECT_EQ(second["seq"], 11);

  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  close(out_pipe[0]);
  close(err_pipe[0]);
}

}  // namespace
