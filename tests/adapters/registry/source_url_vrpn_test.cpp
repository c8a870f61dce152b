// vrpn:// and vicon-udp:// URL options (adapters/sources/vrpn, adapters/sources/vicon_udp), parsed
// in their folders and reached through the registry (docs/sources.md).
#include <gtest/gtest.h>

#include "mocaplink/sources/registry.hpp"
#include "mocaplink/sources/vicon_udp_options.hpp"
#include "mocaplink/sources/vrpn_options.hpp"
#include "url_test_support.hpp"

namespace mocaplink::sources {
namespace {

using test::parsed;

using test::check_error;

TEST(SourceUrlVrpn, DefaultsTrackersAndOptions) {
  const auto plain = parsed(&parse_vrpn_options, "vrpn://192.168.1.3");
  EXPECT_EQ(plain.host, "192.168.1.3");
  EXPECT_EQ(plain.port, 3883);
  EXPECT_TRUE(plain.trackers.empty());
  EXPECT_EQ(plain.lost, std::chrono::milliseconds(500));
  EXPECT_EQ(plain.frozen, std::chrono::milliseconds(0));
  EXPECT_EQ(plain.timeout, std::chrono::milliseconds(5000));
  const auto one = parsed(&parse_vrpn_options, "vrpn://Tracker0@motive.lab:3884/");
  EXPECT_EQ(one.trackers, std::vector<std::string>{"Tracker0"});
  EXPECT_EQ(one.host, "motive.lab");
  EXPECT_EQ(one.port, 3884);
  const auto many = parsed(&parse_vrpn_options,
                           "vrpn://quad1,quad2@[::1]?lost_ms=200&frozen_ms=300&timeout_ms=900");
  EXPECT_EQ(many.trackers, (std::vector<std::string>{"quad1", "quad2"}));
  EXPECT_EQ(many.host, "::1");
  EXPECT_EQ(many.lost, std::chrono::milliseconds(200));
  EXPECT_EQ(many.frozen, std::chrono::milliseconds(300));
  EXPECT_EQ(many.timeout, std::chrono::milliseconds(900));
  EXPECT_TRUE(parsed(&parse_vrpn_options, "vrpn://*@h").trackers.empty());
}

TEST(SourceUrlVrpn, Refusals) {
  EXPECT_EQ(check_error("vrpn://h?lost=5"),
            "unknown option \"lost\" for vrpn://; did you mean \"lost_ms\"? (options: frozen_ms, "
            "lost_ms, timeout_ms)");
  EXPECT_EQ(check_error("vrpn://a,,b@h"),
            "vrpn:// tracker names must be 1 to 99 characters, got \"\"");
  EXPECT_EQ(check_error("vrpn://h/x"), "vrpn:// takes no path, got \"h/x\"");
  EXPECT_EQ(check_error("vrpn://h:0"), "port must be 1..65535, got \"0\"");
  EXPECT_NE(check_error("vrpn://h?lost_ms=5"), "");
  EXPECT_NE(check_error("vrpn://h?timeout_ms=x"), "");
  EXPECT_EQ(check_error("vrpn://T@h"), "");
}

TEST(SourceUrlViconUdp, DefaultsAndOptions) {
  using wire::vicon_udp::EulerOrder;
  const auto plain = parsed(&parse_vicon_udp_options, "vicon-udp://");
  EXPECT_EQ(plain.bind_host, "0.0.0.0");
  EXPECT_EQ(plain.port, 51001);
  EXPECT_EQ(plain.rotation, EulerOrder::xyz);
  EXPECT_EQ(plain.from, "");
  EXPECT_EQ(plain.frozen, 10u);
  EXPECT_EQ(plain.lost, std::chrono::milliseconds(500));
  EXPECT_EQ(parsed(&parse_vicon_udp_options, "vicon-udp://:51002").port, 51002);
  const auto full = parsed(&parse_vicon_udp_options,
                           "vicon-udp://127.0.0.1:51001?rotation=zyx&from=192.168.1.3&frozen=0&"
                           "lost_ms=250&arena_m=20");
  EXPECT_EQ(full.bind_host, "127.0.0.1");
  EXPECT_EQ(full.rotation, EulerOrder::zyx);
  EXPECT_EQ(full.from, "192.168.1.3");
  EXPECT_EQ(full.frozen, 0u);
  EXPECT_EQ(full.lost, std::chrono::milliseconds(250));
  EXPECT_DOUBLE_EQ(full.arena_m, 20.0);
}

TEST(SourceUrlViconUdp, Refusals) {
  EXPECT_EQ(check_error("vicon-udp://?rotation=xzy"), "rotation must be xyz or zyx, got \"xzy\"");
  EXPECT_EQ(check_error("vicon-udp://?from=tracker-pc"),
            "from must be the Tracker's IP address, got \"tracker-pc\"");
  EXPECT_EQ(check_error("vicon-udp://lab-pc:51001"),
            "vicon-udp:// binds to a local IP address, got \"lab-pc\"");
  EXPECT_EQ(check_error("vicon-udp://:51001/x"), "vicon-udp:// takes no path, got \":51001/x\"");
  EXPECT_NE(check_error("vicon-udp://?rotaton=xyz"), "");
  EXPECT_NE(check_error("vicon-udp://?arena_m=0"), "");
}

}  // namespace
}  // namespace mocaplink::sources
