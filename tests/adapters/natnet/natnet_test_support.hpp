// Shared by the natnet socket tests: the emulator serving test::test_frame (with a capture time),
// client options with short back-offs, and the check of a received frame against the frame the
// server was given (float precision on the wire; Motive's Y-up world when the server converts).
#pragma once

#include <asio.hpp>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/natnet_server.hpp"
#include "mocaplink/sources/natnet_source.hpp"

namespace mocaplink::sources::test {

inline constexpr double kRateHz = 200.0;

/// test_frame(n) with capture time n × 5 ms (200 Hz) and an x offset.
inline core::MocapFrame natnet_frame(std::uint64_t n, double offset_m) {
  core::MocapFrame f = test_frame(n, offset_m);
  f.capture_time = core::source_time_from_ns(static_cast<std::int64_t>(n) * 5'000'000);
  return f;
}

inline std::unique_ptr<NatnetServer> start_natnet_server(NatnetServerOptions o,
                                                         double offset_m = 0.0,
                                                         std::uint64_t first_frame = 1) {
  o.rate_hz = kRateHz;
  auto server = std::make_unique<NatnetServer>(o);
  const auto err = server->start([offset_m, first_frame](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(natnet_frame(first_frame + tick, offset_m));
  });
  EXPECT_FALSE(err.has_value()) << *err;
  return server;
}

inline NatnetServerOptions unicast_server(std::uint16_t port = 0) {
  NatnetServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = port;
  o.multicast = false;
  o.data_port = 0;  // frames leave from a free port (Motive: 1511), announced in the server info
  return o;
}

inline NatnetSourceOptions natnet_client(std::uint16_t port) {
  NatnetSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.command_port = port;
  o.target.local = "127.0.0.1";
  o.connect_retry = std::chrono::milliseconds(50);
  o.silence_timeout = std::chrono::milliseconds(500);
  o.retry = core::RetryPolicy{std::chrono::milliseconds(20), std::chrono::milliseconds(20),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(200)};
  o.model_retry = std::chrono::milliseconds(20);
  return o;
}

/// A UDP port free right now on 127.0.0.1 (for a multicast data port the test chooses).
inline std::uint16_t free_udp_port() {
  asio::io_context io;
  asio::ip::udp::socket s(io, asio::ip::udp::endpoint(asio::ip::address_v4::loopback(), 0));
  return s.local_endpoint().port();
}

/// The received frame equals natnet_frame(frame_number, offset_m), turned Y-up when `y_up`:
/// (x, y, z) → (x, z, −y) for positions, the same axis change for rotations.
inline void expect_natnet_matches(const core::MocapFrame& got, double offset_m, bool y_up) {
  const core::MocapFrame want = natnet_frame(got.frame_number, offset_m);
  ASSERT_EQ(got.bodies.size(), 2u);
  const Eigen::Matrix3d to_y = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& g = got.bodies[i];
    const auto& w = want.bodies[i];
    EXPECT_EQ(g.name, w.name);
    EXPECT_EQ(g.tracked, w.tracked) << "frame " << got.frame_number << " body " << w.name;
    if (!w.tracked) continue;
    const Eigen::Vector3d p = y_up ? Eigen::Vector3d(to_y * w.p_world_m) : w.p_world_m;
    const Eigen::Matrix3d r =
        y_up ? Eigen::Matrix3d(to_y * w.q_world_body.toRotationMatrix() * to_y.transpose())
             : w.q_world_body.toRotationMatrix();
    EXPECT_LT((g.p_world_m - p).norm(), 1e-6 + 1e-7 * p.norm())
        << "frame " << got.frame_number;  // f32
    EXPECT_LT((g.q_world_body.toRotationMatrix() - r).norm(), 1e-6) << "frame " << got.frame_number;
  }
  ASSERT_TRUE(got.source_latency.has_value());
  EXPECT_EQ(got.source_latency->count() / 100, want.source_latency->count() / 100);  // 10 MHz
  EXPECT_EQ(got.capture_time, want.capture_time);
}

}  // namespace mocaplink::sources::test
