// vicon:// client ↔ DataStream emulator over real sockets on 127.0.0.1 (port 0), in all three
// stream modes; server restart mid-stream. Readiness is awaited on conditions, never by sleeping;
// nothing asserts on timing.
#include <asio.hpp>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "mocaplink/sources/vicon_server.hpp"
#include "mocaplink/sources/vicon_source.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "mocaplink/wire/vicon_server_session.hpp"
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
  o.target = ViconOptions{"127.0.0.1", port, mode};
  o.retry = core::RetryPolicy{std::chrono::milliseconds(20), std::chrono::milliseconds(20),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(200)};
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

TEST(ViconLoopbackSlowClient, DropsWholeFramesForAClientThatDoesNotReadAndServesTheOthers) {
  ViconServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = 0;
  auto server = std::make_unique<ViconServer>(o);
  ASSERT_FALSE(server->start({}).has_value());  // frames only from publish()

  // A raw client that asks for everything in push mode and then never reads.
  asio::io_context io;
  asio::ip::tcp::socket stuck(io);
  stuck.connect({asio::ip::make_address("127.0.0.1"), server->port()});
  wire::vicon::PacketBuilder b;
  b.add(wire::vicon::ObjectEnums{wire::vicon::server_offered_types()});
  b.add(wire::vicon::RequestFrame{true});
  asio::write(stuck, asio::buffer(b.finish()));

  ViconSource client(client_options(server->port(), StreamMode::server_push), "vicon://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    return std::any_of(events.begin(), events.end(), [](const Event& e) {
      return !e.is_frame && e.state == SourceState::connected;
    });
  }));
  // Make sure both push requests reached the server: publish until our client sees a frame
  // (a frame published before its RequestFrame(1) arrived is legitimately not sent; republish).
  constexpr auto kRepublish = std::chrono::milliseconds(50);
  std::uint64_t n = 1;
  while (Collector::frame_count(got.events()) == 0 && n < 1000) {
    server->publish(test::test_frame(n++));
    (void)got.wait([&](const std::vector<Event>& e) { return Collector::frame_count(e) > 0; },
                   kRepublish);
  }
  // A burst of large frames (300 bodies, ~70 kB per packet for the greedy client) fills the stuck
  // client's socket buffers and its 8-frame queue.
  for (int i = 0; i < 400; ++i, ++n) {
    core::MocapFrame f = test::test_frame(n);
    for (int k = 0; k < 300; ++k) {
      core::BodySample extra = f.bodies[0];
      extra.name = "Extra" + std::to_string(k);
      f.bodies.push_back(extra);
    }
    server->publish(f);
  }
  // Then frames one at a time until our client has caught up with the last one (a frame that
  // found its queue still full of the burst is dropped for it too: publish the next one).
  std::uint64_t last = 0;
  for (int i = 0; i < 1000; ++i, ++n) {
    server->publish(test::test_frame(n));
    const std::uint64_t want = n;
    const bool caught_up = got.wait(
        [&](const std::vector<Event>& events) {
          for (const auto& e : events) {
            if (e.is_frame) last = std::max(last, e.frame.frame_number);
          }
          return last >= want;
        },
        kRepublish);
    if (caught_up) break;
  }
  ++n;
  client.stop();
  EXPECT_GT(server->counters().frames_dropped.load(), 0u);
  EXPECT_EQ(server->counters().malformed_requests.load(), 0u);
  EXPECT_EQ(client.counters().malformed.load(), 0u);
  EXPECT_EQ(last + 1, n);  // the well-behaved client got the newest frame
  const auto frames = frames_of(got.events());
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_GT(frames[i].frame_number, frames[i - 1].frame_number);
  }
  server->stop();
}

}  // namespace
}  // namespace mocaplink::sources
