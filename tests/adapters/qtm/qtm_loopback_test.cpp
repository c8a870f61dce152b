// qtm:// client against the QTM RT emulator on 127.0.0.1: every 6DOF component over TCP and UDP,
// version negotiation down to the ≤ 1.20 XML, body list changes (event 11 → parameters re-read),
// a server restart (never a stale pose), the client limit. Waits are on conditions, never timed.
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <asio.hpp>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/qtm_server.hpp"
#include "mocaplink/sources/qtm_source.hpp"

namespace mocaplink::sources {
namespace {

using test::Collector;
using test::Event;
namespace wq = wire::qtm;

// Frame n: Body1 always tracked and yawing, Body2 untracked when n % 5 == 0; `offset_m` in x tells
// two servers apart; `bodies` = how many of the two are listed at all.
core::MocapFrame frame(std::uint64_t n, double offset_m = 0.0, std::size_t bodies = 2) {
  core::MocapFrame f;
  f.frame_number = n;
  f.capture_time = core::SourceTime{std::chrono::microseconds(5000 * n)};
  core::BodySample b1;
  b1.name = "Body1";
  b1.tracked = true;
  b1.p_world_m = {offset_m + 0.001 * static_cast<double>(n), -0.5, 1.25};
  const double yaw = 0.01 * static_cast<double>(n);
  b1.q_world_body = Eigen::Quaterniond(std::cos(yaw / 2), 0.1, 0.0, std::sin(yaw / 2)).normalized();
  core::BodySample b2;
  b2.name = "Body2";
  b2.tracked = n % 5 != 0;
  b2.p_world_m = {offset_m - 1.234567, 2.5, 0.75};
  b2.q_world_body = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
  f.bodies = {b1, b2};
  f.bodies.resize(bodies);
  return f;
}

// Every delivered frame equals frame(frame_number, offset_m, its body count) (float precision).
void expect_frames_match(const std::vector<Event>& events, double offset_m) {
  for (const auto& e : events) {
    if (!e.is_frame) continue;
    const auto& got = e.frame;
    const auto want = frame(got.frame_number, offset_m, got.bodies.size());
    ASSERT_GE(got.bodies.size(), 1u);
    EXPECT_EQ(got.capture_time, want.capture_time);
    for (std::size_t i = 0; i < got.bodies.size(); ++i) {
      const auto& g = got.bodies[i];
      const auto& w = want.bodies[i];
      EXPECT_EQ(g.name, w.name);
      ASSERT_EQ(g.tracked, w.tracked) << "frame " << got.frame_number << " " << w.name;
      if (!w.tracked) continue;
      EXPECT_LT((g.p_world_m - w.p_world_m).norm(), 1e-5) << "frame " << got.frame_number;
      EXPECT_NEAR(std::abs(g.q_world_body.dot(w.q_world_body)), 1.0, 1e-6);
    }
  }
}

std::unique_ptr<QtmServer> start_server(QtmServerOptions options, double offset_m = 0.0,
                                        std::uint16_t port = 0) {
  options.listen_host = "127.0.0.1";
  options.port = port;
  options.rate_hz = 200.0;
  auto server = std::make_unique<QtmServer>(options);
  const auto err = server->start([offset_m](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(frame(tick + 1, offset_m));
  });
  EXPECT_FALSE(err) << *err;
  return server;
}

QtmSourceOptions client_options(std::uint16_t port) {
  QtmSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.port = port;
  o.retry = core::RetryPolicy{std::chrono::milliseconds(20), std::chrono::milliseconds(20),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(100)};
  return o;
}

std::string connected_detail(const std::vector<Event>& events) {
  for (const auto& e : events) {
    if (!e.is_frame && e.state == SourceState::connected) return e.detail;
  }
  return {};
}

TEST(QtmLoopback, EveryComponentOverTcpAndUdpMatchesTheServedFrames) {
  const auto server = start_server({});
  for (const auto component : {wq::Component::six_d, wq::Component::six_d_residual,
                               wq::Component::six_d_euler, wq::Component::six_d_euler_residual}) {
    for (const bool udp : {false, true}) {
      SCOPED_TRACE(std::string(wq::to_string(component)) + (udp ? " UDP" : " TCP"));
      auto o = client_options(server->port());
      o.target.component = component;
      if (udp) o.target.udp_port = 0;
      QtmSource source(o, "qtm://test");
      Collector got;
      source.start(got.frame_sink(), got.state_sink());
      ASSERT_TRUE(got.wait_frames(30));
      source.stop();
      const auto events = got.events();
      expect_frames_match(events, 0.0);
      EXPECT_NE(connected_detail(events).find(udp ? "over UDP" : "over TCP"), std::string::npos);
      EXPECT_NE(connected_detail(events).find("protocol 1.28"), std::string::npos);
      EXPECT_EQ(source.counters().malformed, 0u);
      for (const auto& e : events) {
        if (e.is_frame) {
          EXPECT_EQ(e.frame.frame_rate_hz, 200.0);  // General <Frequency>
        }
      }
    }
  }
}

TEST(QtmLoopback, NegotiatesDownToTheServersVersionAndReadsTheOldXml) {
  QtmServerOptions options;
  options.session.max_minor = 19;
  const auto server = start_server(options);
  QtmSource source(client_options(server->port()), "qtm://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10));
  source.stop();
  EXPECT_NE(connected_detail(got.events()).find("protocol 1.19"), std::string::npos);
  expect_frames_match(got.events(), 0.0);
}

TEST(QtmLoopback, ABodyListChangeIsAnEventAndTheNamesAreReadAgain) {
  QtmServerOptions options;
  options.listen_host = "127.0.0.1";
  options.port = 0;
  QtmServer server(options);
  ASSERT_FALSE(server.start({}));
  QtmSource source(client_options(server.port()), "qtm://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  // A publisher at ~200 Hz listing `listed` bodies; frame numbers from `n`.
  std::atomic<std::size_t> listed{2};
  std::atomic<std::uint64_t> n{1};
  std::atomic<bool> done{false};
  std::thread publisher([&] {
    while (!done) {
      server.publish(frame(n++, 0.0, listed));
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  // Switches to `bodies` and waits for a frame published after the switch with that many.
  const auto serve_until_seen = [&](std::size_t bodies) {
    listed = bodies;
    const std::uint64_t from = n;
    return got.wait([&](const std::vector<Event>& events) {
      for (const auto& e : events) {
        if (e.is_frame && e.frame.frame_number > from && e.frame.bodies.size() == bodies) {
          return true;
        }
      }
      return false;
    });
  };
  const bool seen = serve_until_seen(2) && serve_until_seen(1) && serve_until_seen(2);
  done = true;
  publisher.join();
  ASSERT_TRUE(seen);
  source.stop();
  server.stop();
  expect_frames_match(got.events(), 0.0);
  EXPECT_GE(source.qtm_counters().parameter_reads, 3u);
  EXPECT_GE(source.qtm_counters().events, 2u);
  EXPECT_GE(server.counters().body_list_changes, 2u);
}

// Before the first frame there is no body list, and the official client reads the list once, at
// connect: a connection waits unwelcomed until the first frame, however many ticks pass.
TEST(QtmLoopback, AConnectionIsWelcomedOnlyFromTheFirstFrameOn) {
  QtmServerOptions options;
  options.listen_host = "127.0.0.1";
  options.port = 0;
  options.rate_hz = 200.0;
  std::atomic<bool> frames{false};
  std::atomic<std::uint64_t> ticks{0};
  QtmServer server(options);  // after what its provider reads: stopped before they go
  ASSERT_FALSE(server.start([&](std::uint64_t tick) {
    ++ticks;
    return frames ? std::optional<core::MocapFrame>(frame(tick + 1)) : std::nullopt;
  }));
  asio::io_context io;
  asio::ip::tcp::socket client(io);
  client.connect({asio::ip::make_address("127.0.0.1"), server.port()});
  // The connection is in the backlog now; the server's loop runs a few more ticks, which it would
  // not do without taking up a ready connection first if it were accepting.
  const auto wait_ticks = [&](std::uint64_t n) {
    const auto until = std::chrono::steady_clock::now() + test::kWaitCap;
    while (ticks < n && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return ticks >= n;
  };
  ASSERT_TRUE(wait_ticks(ticks + 3));
  EXPECT_EQ(server.counters().clients_accepted, 0u);
  frames = true;
  const auto welcome = wq::ServerSession::welcome();
  std::vector<std::byte> got(welcome.size());
  asio::read(client, asio::buffer(got));
  EXPECT_EQ(got, welcome);
  EXPECT_EQ(server.counters().clients_accepted, 1u);
  EXPECT_GE(server.counters().frames, 1u);
  server.stop();
}

TEST(QtmLoopback, ReconnectsAfterARestartAndNeverDeliversAStalePose) {
  auto first = start_server({}, 0.0);
  const std::uint16_t port = first->port();
  QtmSource source(client_options(port), "qtm://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10));
  first->stop();
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    for (const auto& e : events) {
      if (!e.is_frame && e.state == SourceState::disconnected) return true;
    }
    return false;
  }));
  const std::size_t before = Collector::frame_count(got.events());
  const auto second = start_server({}, 100.0, port);
  ASSERT_TRUE(got.wait_frames(before + 10));
  source.stop();
  const auto events = got.events();
  bool after_disconnect = false;
  std::vector<Event> old_frames;
  std::vector<Event> new_frames;
  for (const auto& e : events) {
    if (!e.is_frame && e.state == SourceState::disconnected) after_disconnect = true;
    if (e.is_frame) (after_disconnect ? new_frames : old_frames).push_back(e);
  }
  expect_frames_match(old_frames, 0.0);
  expect_frames_match(new_frames, 100.0);  // nothing from the first server after it went away
  EXPECT_GE(source.counters().reconnects, 1u);
}

TEST(QtmLoopback, DuplicateNamesAreUntrackedAndSaidInTheConnectedState) {
  QtmServerOptions options;
  options.listen_host = "127.0.0.1";
  options.port = 0;
  options.rate_hz = 200.0;
  QtmServer server(options);
  ASSERT_FALSE(server.start([](std::uint64_t tick) {
    auto f = frame(tick + 1);
    f.bodies[1].name = "Body1";
    f.bodies[1].tracked = true;
    return std::optional<core::MocapFrame>(f);
  }));
  QtmSource source(client_options(server.port()), "qtm://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(5));
  source.stop();
  EXPECT_NE(connected_detail(got.events()).find("duplicate body name Body1"), std::string::npos)
      << connected_detail(got.events());
  for (const auto& e : got.events()) {
    if (!e.is_frame) continue;
    ASSERT_EQ(e.frame.bodies.size(), 2u);
    EXPECT_FALSE(e.frame.bodies[0].tracked);
    EXPECT_FALSE(e.frame.bodies[1].tracked);
  }
}

TEST(QtmLoopback, TheClientBeyondTheLimitGetsQtmsRefusal) {
  QtmServerOptions options;
  options.max_clients = 1;
  const auto server = start_server(options);
  QtmSource first(client_options(server->port()), "qtm://a");
  Collector a;
  first.start(a.frame_sink(), a.state_sink());
  ASSERT_TRUE(a.wait_frames(1));
  QtmSource second(client_options(server->port()), "qtm://b");
  Collector b;
  second.start(b.frame_sink(), b.state_sink());
  ASSERT_TRUE(b.wait([](const std::vector<Event>& events) {
    for (const auto& e : events) {
      if (!e.is_frame && e.detail.find("Max number of clients") != std::string::npos) return true;
    }
    return false;
  }));
  second.stop();
  first.stop();
  EXPECT_EQ(Collector::frame_count(b.events()), 0u);
  EXPECT_GE(server->counters().clients_rejected, 1u);
}

}  // namespace
}  // namespace mocaplink::sources
