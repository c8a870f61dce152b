// natnet:// client ↔ NatNet emulator over real sockets on 127.0.0.1: unicast in every bitstream
// version the emulator serves, multicast on the loopback interface, model changes (a body
// appearing), server restart (no stale pose), keep-alive timeout, and the emulator's settings.
// Readiness is awaited on conditions, never by sleeping; nothing asserts on timing.
#include <gtest/gtest.h>

#include "natnet_test_support.hpp"

namespace mocaplink::sources {
namespace {

using test::Collector;
using test::Event;

std::vector<core::MocapFrame> frames_of(const std::vector<Event>& events) {
  std::vector<core::MocapFrame> out;
  for (const auto& e : events) {
    if (e.is_frame) out.push_back(e.frame);
  }
  return out;
}

void expect_stream(const std::vector<core::MocapFrame>& frames, bool y_up) {
  std::size_t occluded = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    test::expect_natnet_matches(frames[i], 0.0, y_up);
    occluded += frames[i].bodies[1].tracked ? 0u : 1u;
    if (i > 0) {
      EXPECT_GT(frames[i].frame_number, frames[i - 1].frame_number);
    }
  }
  EXPECT_GT(occluded, 0u);  // Body2's tracking-valid bit clear every 5th frame
}

class NatnetVersions : public ::testing::TestWithParam<wire::natnet::Version> {};

TEST_P(NatnetVersions, UnicastNamesPosesTrackingLatencyCaptureTime) {
  auto so = test::unicast_server();
  so.version = GetParam();
  auto server = test::start_natnet_server(so);
  NatnetSource client(test::natnet_client(server->port()), "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(30));
  client.stop();
  server->stop();
  const auto frames = frames_of(got.events());
  expect_stream(frames, true);
  ASSERT_TRUE(frames.back().frame_rate_hz.has_value());
  EXPECT_NEAR(*frames.back().frame_rate_hz, test::kRateHz, 1e-6);
  EXPECT_EQ(client.counters().malformed.load(), 0u);
  EXPECT_GT(client.natnet_counters().keep_alives.load(), 0u);
  const auto events = got.events();
  const auto connected = std::find_if(events.begin(), events.end(), [](const Event& e) {
    return !e.is_frame && e.state == SourceState::connected;
  });
  ASSERT_NE(connected, events.end());
  EXPECT_NE(connected->detail.find("NatNet " + GetParam().to_string()), std::string::npos);
  EXPECT_NE(connected->detail.find("unicast"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(AllServed, NatnetVersions,
                         ::testing::Values(wire::natnet::Version{3, 0}, wire::natnet::Version{3, 1},
                                           wire::natnet::Version{4, 0}, wire::natnet::Version{4, 1},
                                           wire::natnet::Version{4, 2}));

TEST(NatnetLoopback, MulticastOnTheLoopbackInterfaceZUpKept) {
  NatnetServerOptions so;
  so.listen_host = "127.0.0.1";
  so.port = 0;
  so.multicast = true;
  so.group = "239.255.42.199";
  so.data_port = test::free_udp_port();
  so.interface = "127.0.0.1";
  so.y_up = false;
  auto server = test::start_natnet_server(so);
  NatnetSource client(test::natnet_client(server->port()), "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(30)) << client.last_error();
  client.stop();
  server->stop();
  expect_stream(frames_of(got.events()), false);
  EXPECT_EQ(client.natnet_counters().keep_alives.load(), 0u);  // multicast needs none
}

TEST(NatnetLoopback, ABodyAppearingIsNamedAfterTheModelReload) {
  auto so = test::unicast_server();
  so.rate_hz = test::kRateHz;
  auto server = std::make_unique<NatnetServer>(so);
  ASSERT_FALSE(server->start([](std::uint64_t tick) {
    core::MocapFrame f = test::natnet_frame(tick + 1, 0.0);
    if (tick >= 40) {
      core::BodySample b3;
      b3.name = "Body3";
      b3.tracked = true;
      b3.p_world_m = {1, 2, 3};
      f.bodies.push_back(b3);
    }
    return std::optional<core::MocapFrame>(f);
  }));
  NatnetSource client(test::natnet_client(server->port()), "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    for (const auto& e : events) {
      if (e.is_frame && e.frame.bodies.size() == 3) return true;
    }
    return false;
  }));
  client.stop();
  server->stop();
  for (const auto& f : frames_of(got.events())) {
    ASSERT_GE(f.bodies.size(), 2u);
    if (f.bodies.size() == 3) {
      EXPECT_EQ(f.bodies[2].name, "Body3");
      EXPECT_TRUE(f.bodies[2].p_world_m.isApprox(Eigen::Vector3d(1, 3, -2), 1e-6));  // Y-up
    }
  }
  EXPECT_GE(client.natnet_counters().model_reloads.load(), 2u);
}

TEST(NatnetLoopback, ServerRestartNeverDeliversAStalePose) {
  auto server = test::start_natnet_server(test::unicast_server(), 0.0, 1);
  const std::uint16_t port = server->port();
  NatnetSource client(test::natnet_client(port), "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10));
  server->stop();
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    return std::any_of(events.begin(), events.end(), [](const Event& e) {
      return !e.is_frame && e.state == SourceState::disconnected;
    });
  }));
  // A different Motive on the same port: other positions, frame numbers starting again low.
  server = test::start_natnet_server(test::unicast_server(port), 100.0, 1);
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    bool after = false;
    std::size_t n = 0;
    for (const auto& e : events) {
      if (!e.is_frame && e.state == SourceState::disconnected) after = true;
      if (after && e.is_frame) ++n;
    }
    return n >= 10;
  }));
  client.stop();
  server->stop();
  bool after = false;
  for (const auto& e : got.events()) {
    if (!e.is_frame) {
      after = after || e.state == SourceState::disconnected;
      continue;
    }

    test::expect_natnet_matches(e.frame, after ? 100.0 : 0.0, true);
  }
  EXPECT_GE(client.counters().reconnects.load(), 1u);
  EXPECT_GE(client.natnet_counters().timeouts.load(), 1u);
}

TEST(NatnetLoopback, AClientWithoutKeepAliveIsDroppedAndComesBack) {
  auto so = test::unicast_server();
  so.keepalive_timeout = std::chrono::milliseconds(100);
  auto server = test::start_natnet_server(so);
  auto co = test::natnet_client(server->port());
  co.keep_alive = std::chrono::hours(1);  // our client "forgets" its keep-alives
  NatnetSource client(co, "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait([&](const std::vector<Event>&) {
    return client.counters().reconnects.load() >= 1 &&
           server->counters().clients_timed_out.load() >= 1;
  }));
  const std::size_t before = Collector::frame_count(got.events());
  ASSERT_TRUE(got.wait_frames(before + 5));  // served again after reconnecting
  client.stop();
  server->stop();
  // Told so by the server (NAT_DISCONNECTBYTIMEOUT), as Motive does, not left to notice silence.
  EXPECT_GE(client.natnet_counters().disconnects_by_server.load(), 1u);
  EXPECT_EQ(client.natnet_counters().timeouts.load(), 0u);
}

TEST(NatnetLoopback, DisconnectOnStopEndsUnicastStreaming) {
  auto server = test::start_natnet_server(test::unicast_server());
  {
    NatnetSource client(test::natnet_client(server->port()), "natnet://test");
    Collector got;
    client.start(got.frame_sink(), got.state_sink());
    ASSERT_TRUE(got.wait_frames(5));
    EXPECT_EQ(server->counters().clients_now.load(), 1u);
  }
  // The NAT_DISCONNECT sent on stop() removes the client at the next frame.
  Collector never;
  ASSERT_TRUE(never.wait(
      [&](const std::vector<Event>&) { return server->counters().clients_now.load() == 0; }));
  server->stop();
}

TEST(NatnetEmulatorSettings, OneLineErrors) {
  auto error_of = [](std::vector<std::pair<std::string, std::string>> settings) {
    EmulatorOptions o;
    o.settings = std::move(settings);
    auto r = natnet_server_options(o);
    if (auto* e = std::get_if<std::string>(&r)) return *e;
    return std::string("(accepted)");
  };
  EXPECT_EQ(error_of({{"version", "5.0"}}),
            "version must be 3.0, 3.1, 4.0, 4.1 or 4.2, got \"5.0\"");
  EXPECT_EQ(error_of({{"transport", "tcp"}}),
            "transport must be multicast or unicast, got \"tcp\"");
  EXPECT_EQ(error_of({{"group", "10.0.0.1"}}),
            "group must be an IPv4 multicast address, got \"10.0.0.1\"");
  EXPECT_EQ(error_of({{"up", "x"}}), "up must be y or z, got \"x\"");
  EXPECT_NE(error_of({{"keepalive_timeout_s", "0"}}).find("keepalive_timeout_s must be"),
            std::string::npos);
  EXPECT_NE(error_of({{"data_port", "70000"}}).find("data_port must be"), std::string::npos);
  EXPECT_EQ(error_of({{"interface", "eth0"}}), "interface must be an IPv4 address, got \"eth0\"");
  EmulatorOptions o;
  o.settings = {{"transport", "unicast"},     {"version", "4.2"},     {"up", "z"},
                {"keepalive_timeout_s", "2"}, {"group", "239.1.2.3"}, {"data_port", "1600"},
                {"interface", "127.0.0.1"}};
  const auto ok = std::get<NatnetServerOptions>(natnet_server_options(o));
  EXPECT_FALSE(ok.multicast);
  EXPECT_EQ(ok.version, (wire::natnet::Version{4, 2}));
  EXPECT_FALSE(ok.y_up);
  EXPECT_EQ(ok.keepalive_timeout, std::chrono::milliseconds(2000));
  EXPECT_EQ(ok.group, "239.1.2.3");
  EXPECT_EQ(ok.data_port, 1600);
  EXPECT_EQ(ok.interface, "127.0.0.1");
}

}  // namespace
}  // namespace mocaplink::sources
