// vicon:// client ↔ DataStream emulator over real sockets on 127.0.0.1 (port 0), in all three
// stream modes; server restart mid-stream. Readiness is awaited on conditions, never by sleeping;
// nothing asserts on timing.
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "mocaplink/sources/vicon_server.hpp"
#include "mocaplink/sources/vicon_source.hpp"
#include "vicon_test_support.hpp"

namespace mocaplink::sources {
namespace {

using test::Collector;
using test::Event;
using wire::vicon::StreamMode;

constexpr double kRateHz = 200.0;

std::unique_ptr<ViconServer> start_server(std::uint16_t port, double offset_m,
                                          std::uint64_t first_frame) {
  ViconServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = port;
  o.rate_hz = kRateHz;
  auto server = std::make_unique<ViconServer>(o);
  const auto err = server->start([offset_m, first_frame](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(test::test_frame(first_frame + tick, offset_m));
  });
  EXPECT_FALSE(err.has_value()) << *err;
  return server;
}

ViconSourceOptions client_options(std::uint16_t port, StreamMode mode) {
  ViconSourceOptions o;
  o.target = ViconUrl{"127.0.0.1", port, mode};
  o.backoff_initial = std::chrono::milliseconds(20);
  o.backoff_max = std::chrono::milliseconds(200);
  return o;
}

std::vector<core::MocapFrame> frames_of(const std::vector<Event>& events) {
  std::vector<core::MocapFrame> out;
  for (const auto& e : events) {
    if (e.is_frame) out.push_back(e.frame);
  }
  return out;
}

class ViconLoopback : public ::testing::TestWithParam<StreamMode> {};

TEST_P(ViconLoopback, NamesPosesOcclusionFrameNumbersRateLatency) {
  auto server = start_server(0, 0.0, 1);
  ViconSource client(client_options(server->port(), GetParam()), "vicon://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  // 40 frames at 200 Hz cover eight Body2 occlusions (every 5th frame).
  ASSERT_TRUE(got.wait_frames(40));
  client.stop();
  server->stop();

  const auto frames = frames_of(got.events());
  ASSERT_GE(frames.size(), 40u);
  std::size_t occluded = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    test::expect_matches(f);
    ASSERT_TRUE(f.frame_rate_hz.has_value());
    EXPECT_DOUBLE_EQ(*f.frame_rate_hz, kRateHz);
    // capture time = frame id × period on the 135 MHz clock (5 ms at 200 Hz).
    EXPECT_EQ(f.capture_time,
              core::source_time_from_ns(static_cast<std::int64_t>(f.frame_number * 5'000'000)));
    occluded += f.bodies[1].tracked ? 0u : 1u;
    // Never a repeat or a step back, in any mode (pull repeats are filtered).
    if (i > 0) {
      EXPECT_GT(f.frame_number, frames[i - 1].frame_number);
    }
  }
  EXPECT_GE(occluded, 1u);
  EXPECT_EQ(client.counters().malformed.load(), 0u);
  EXPECT_EQ(client.vicon_counters().invalid_poses.load(), 0u);
  EXPECT_EQ(client.vicon_counters().connections.load(), 1u);
  EXPECT_EQ(server->counters().malformed_requests.load(), 0u);
  const auto events = got.events();
  ASSERT_FALSE(events.empty());
  EXPECT_FALSE(events.front().is_frame);
  EXPECT_EQ(events.front().state, SourceState::connecting);
}

INSTANTIATE_TEST_SUITE_P(AllModes, ViconLoopback,
                         ::testing::Values(StreamMode::server_push, StreamMode::client_prefetch,
                                           StreamMode::client_pull),
                         [](const auto& param_info) {
                           return std::string(wire::vicon::to_string(param_info.param));
                         });

TEST(ViconLoopbackMany, ClientsInDifferentModesShareOneServer) {
  auto server = start_server(0, 0.0, 1);
  std::vector<std::unique_ptr<ViconSource>> clients;
  std::vector<std::unique_ptr<Collector>> got;
  for (StreamMode m :
       {StreamMode::server_push, StreamMode::client_prefetch, StreamMode::client_pull}) {
    clients.push_back(std::make_unique<ViconSource>(client_options(server->port(), m), "v"));
    got.push_back(std::make_unique<Collector>());
    clients.back()->start(got.back()->frame_sink(), got.back()->state_sink());
  }
  for (auto& g : got) ASSERT_TRUE(g->wait_frames(10));
  EXPECT_EQ(server->counters().clients_accepted.load(), 3u);
  for (auto& c : clients) c->stop();
  server->stop();
  for (auto& g : got) {
    for (const auto& f : frames_of(g->events())) test::expect_matches(f);
  }
}

TEST(ViconLoopbackRestart, ReconnectsAndNeverDeliversAStalePose) {
  auto server = start_server(0, 0.0, 1);
  const std::uint16_t port = server->port();
  ViconSource client(client_options(port, StreamMode::server_push), "vicon://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10));
  server->stop();
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    return std::any_of(events.begin(), events.end(), [](const Event& e) {
      return !e.is_frame && e.state == SourceState::disconnected;
    });
  }));
  // The restarted server serves different poses (x + 100 m) and restarts its frame numbers.
  server = start_server(port, 100.0, 5000);
  const std::size_t before = Collector::frame_count(got.events());
  ASSERT_TRUE(got.wait_frames(before + 10));
  client.stop();
  server->stop();

  bool disconnected = false;
  bool reconnected = false;
  std::size_t after = 0;
  for (const Event& e : got.events()) {
    if (!e.is_frame) {
      if (e.state == SourceState::disconnected) disconnected = true;
      if (disconnected && e.state == SourceState::connected) reconnected = true;
      continue;
    }
    if (!disconnected) {
      test::expect_matches(e.frame, 0.0);
    } else {
      // Every frame after the disconnect comes from the new server: no stale pose.
      EXPECT_TRUE(reconnected);
      EXPECT_GE(e.frame.frame_number, 5000u);
      test::expect_matches(e.frame, 100.0);
      ++after;
    }
  }
  EXPECT_GE(after, 10u);
  EXPECT_GE(client.counters().reconnects.load(), 1u);
  EXPECT_EQ(client.vicon_counters().connections.load(), 2u);
  EXPECT_EQ(client.counters().malformed.load(), 0u);
}

}  // namespace
}  // namespace mocaplink::sources
