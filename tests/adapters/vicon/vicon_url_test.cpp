#include "mocaplink/sources/vicon_url.hpp"

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

using wire::vicon::StreamMode;

ViconUrl ok(const char* url) {
  auto r = parse_vicon_url(url);
  EXPECT_TRUE(std::holds_alternative<ViconUrl>(r)) << url;
  return std::holds_alternative<ViconUrl>(r) ? std::get<ViconUrl>(r) : ViconUrl{};
}

std::string error(const char* url) {
  auto r = parse_vicon_url(url);
  EXPECT_TRUE(std::holds_alternative<std::string>(r)) << url;
  return std::holds_alternative<std::string>(r) ? std::get<std::string>(r) : "";
}

TEST(ViconUrl, HostPortAndMode) {
  const ViconUrl a = ok("vicon://192.168.1.3");
  EXPECT_EQ(a.host, "192.168.1.3");
  EXPECT_EQ(a.port, 801);
  EXPECT_EQ(a.mode, StreamMode::server_push);
  const ViconUrl b = ok("vicon://tracker.lab:8801?mode=prefetch");
  EXPECT_EQ(b.host, "tracker.lab");
  EXPECT_EQ(b.port, 8801);
  EXPECT_EQ(b.mode, StreamMode::client_prefetch);
  EXPECT_EQ(ok("vicon://h/?mode=pull").mode, StreamMode::client_pull);
  EXPECT_EQ(ok("vicon://h?mode=push").mode, StreamMode::server_push);
  const ViconUrl v6 = ok("vicon://[::1]:9000");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 9000);
}

TEST(ViconUrl, ErrorsNameTheProblem) {
  EXPECT_NE(error("natnet://h").find("not a vicon://"), std::string::npos);
  EXPECT_NE(error("vicon://").find("missing host"), std::string::npos);
  EXPECT_NE(error("vicon://h:0").find("bad port"), std::string::npos);
  EXPECT_NE(error("vicon://h:70000").find("bad port"), std::string::npos);
  EXPECT_NE(error("vicon://h:80x").find("bad port"), std::string::npos);
  EXPECT_NE(error("vicon://h:").find("empty port"), std::string::npos);
  EXPECT_NE(error("vicon://h?mode=stream").find("bad mode 'stream'"), std::string::npos);
  EXPECT_NE(error("vicon://h?rate=3").find("unknown key 'rate'"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::sources
