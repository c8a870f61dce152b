// vrpn:// client ↔ VRPN tracker emulator over real sockets on 127.0.0.1 (port 0): poses, names,
// occlusion as silence, the tracker filter, bodies appearing later, server restart. Readiness is
// awaited on conditions, never by sleeping; nothing asserts on timing.
#include <cmath>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/vrpn_server.hpp"
#include "mocaplink/sources/vrpn_source.hpp"

namespace mocaplink::sources {
namespace {

using test::Collector;
using test::Event;

constexpr double kRateHz = 200.0;

std::unique_ptr<VrpnServer> start_server(std::uint16_t port, double offset_m,
                                         std::uint64_t first = 1) {
  VrpnServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = port;
  o.rate_hz = kRateHz;
  auto server = std::make_unique<VrpnServer>(o);
  const auto err = server->start([offset_m, first](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(test::test_frame(first + tick, offset_m));
  });
  EXPECT_FALSE(err.has_value()) << *err;
  return server;
}

VrpnSourceOptions client_options(std::uint16_t port, std::vector<std::string> trackers = {}) {
  VrpnSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.port = port;
  o.target.trackers = std::move(trackers);
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

/// Checks a received body against what test_frame() sends: Body1 against the tick its x encodes,
/// Body2 (constant, occluded every 5th tick) against its pose. VRPN reports only tracked bodies. A
/// frame may join Body2 of one tick with Body1 of the next: rounds close on what arrived.
void expect_body(const core::BodySample& got, double offset_m) {
  EXPECT_TRUE(got.tracked);
  if (got.name == "Body1") {
    const auto n = static_cast<std::uint64_t>(std::llround((got.p_world_m.x() - offset_m) / 0.001));
    const auto& w = test::test_frame(n, offset_m).bodies[0];
    EXPECT_LT((got.p_world_m - w.p_world_m).norm(), 1e-12);
    EXPECT_NEAR(std::abs(got.q_world_body.dot(w.q_world_body)), 1.0, 1e-12);
    return;
  }
  ASSERT_EQ(got.name, "Body2");
  const auto& w = test::test_frame(1, offset_m).bodies[1];
  EXPECT_EQ(got.p_world_m, w.p_world_m);
  EXPECT_NEAR(std::abs(got.q_world_body.dot(w.q_world_body)), 1.0, 1e-12);
}

/// Publishes `frame` until the client delivered a frame: the first publish may come before the
/// server has the client's cookie (polling with a short wait, not a timing assertion).
bool publish_until_frame(VrpnServer& server, const core::MocapFrame& frame, Collector& got) {
  for (int i = 0; i < 200; ++i) {
    server.publish(frame);
    if (got.wait([](const std::vector<Event>& e) { return Collector::frame_count(e) > 0; },
                 std::chrono::milliseconds(50))) {
      return true;
    }
  }
  return false;
}

TEST(VrpnLoopback, NamesPosesOcclusionHostFrames) {
  auto server = start_server(0, 0.0);
  VrpnSource client(client_options(server->port()), "vrpn://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(60));
  client.stop();
  server->stop();

  const auto frames = frames_of(got.events());
  std::size_t with_body2 = 0;
  std::size_t without_body2 = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    EXPECT_EQ(f.frame_step, 0u);  // numbered by the client: the Station counts no drops
    EXPECT_EQ(f.frame_number, i + 1);
    if (i > 0) {
      EXPECT_GT(f.capture_time, frames[i - 1].capture_time);
    }
    ASSERT_FALSE(f.bodies.empty());
    for (const auto& b : f.bodies) expect_body(b, 0.0);
    (f.bodies.size() == 2 ? with_body2 : without_body2) += 1;
  }
  EXPECT_GT(with_body2, 0u);
  EXPECT_GT(without_body2, 0u);  // every 5th tick Body2 is occluded: not reported
  EXPECT_EQ(client.counters().malformed, 0u);
  EXPECT_EQ(client.vrpn_counters().connections, 1u);
  const auto trackers = client.trackers();
  EXPECT_EQ(trackers, (std::vector<std::string>{"VRPN Control", "Body1", "Body2"}));
}

TEST(VrpnLoopback, OnlyTheTrackersAskedFor) {
  auto server = start_server(0, 0.0);
  VrpnSource client(client_options(server->port(), {"Body2"}), "vrpn://Body2@test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(20));
  client.stop();
  server->stop();
  for (const auto& f : frames_of(got.events())) {
    ASSERT_EQ(f.bodies.size(), 1u);
    EXPECT_EQ(f.bodies[0].name, "Body2");
  }
  EXPECT_GT(client.vrpn_counters().other_trackers, 0u);
}

TEST(VrpnLoopback, ABodyAppearingLaterIsDescribedThenReported) {
  VrpnServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = 0;
  o.rate_hz = kRateHz;
  VrpnServer server(o);
  ASSERT_FALSE(server.start({}).has_value());  // publish() only
  VrpnSource client(client_options(server.port()), "vrpn://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  core::MocapFrame f;
  core::BodySample late;
  late.name = "Late Body";
  late.tracked = true;
  late.p_world_m = {1, 2, 3};
  f.bodies = {late};
  ASSERT_TRUE(publish_until_frame(server, f, got));
  client.stop();
  server.stop();
  const auto frames = frames_of(got.events());
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames[0].bodies[0].name, "Late Body");
  EXPECT_EQ(frames[0].bodies[0].p_world_m, Eigen::Vector3d(1, 2, 3));
}

TEST(VrpnLoopback, ServerRestartReconnectsWithoutAStalePose) {
  auto first = start_server(0, 0.0);
  const std::uint16_t port = first->port();
  VrpnSource client(client_options(port), "vrpn://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10));
  first->stop();
  ASSERT_TRUE(got.wait([](const std::vector<Event>& e) {
    return std::any_of(e.begin(), e.end(), [](const Event& x) {
      return !x.is_frame && x.state == SourceState::disconnected;
    });
  }));
  const std::size_t before = Collector::frame_count(got.events());
  auto second = start_server(port, 100.0);  // poses 100 m away: any old one would show
  ASSERT_TRUE(got.wait_frames(before + 10));
  client.stop();
  second->stop();

  const auto events = got.events();
  bool after_disconnect = false;
  for (const auto& e : events) {
    if (!e.is_frame) {
      if (e.state == SourceState::disconnected) after_disconnect = true;
      continue;
    }
    if (!after_disconnect) continue;
    for (const auto& b : e.frame.bodies) {
      EXPECT_GT(b.p_world_m.x(), 50.0) << "a pose of the old server after the restart";
    }
  }
  EXPECT_GE(client.counters().reconnects, 1u);
  EXPECT_EQ(client.vrpn_counters().connections, 2u);
  EXPECT_EQ(client.counters().malformed, 0u);
}

TEST(VrpnLoopback, SilenceMakesEveryBodyLostOnce) {
  VrpnServerOptions o;
  o.listen_host = "127.0.0.1";
  o.rate_hz = kRateHz;
  VrpnServer server(o);
  ASSERT_FALSE(server.start({}).has_value());
  auto options = client_options(server.port());
  options.target.lost = std::chrono::milliseconds(50);
  VrpnSource client(options, "vrpn://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(publish_until_frame(server, test::test_frame(1), got));
  // No more reports: the next frame is the loss frame, all bodies untracked.
  ASSERT_TRUE(got.wait([](const std::vector<Event>& e) {
    const auto frames = frames_of(e);
    return std::any_of(frames.begin(), frames.end(), [](const core::MocapFrame& f) {
      return !f.bodies.empty() && std::none_of(f.bodies.begin(), f.bodies.end(),
                                               [](const core::BodySample& b) { return b.tracked; });
    });
  }));
  client.stop();
  server.stop();
}

}  // namespace
}  // namespace mocaplink::sources
