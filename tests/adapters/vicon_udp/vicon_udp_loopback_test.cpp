// vicon-udp:// receiver ↔ the `serve --protocol vicon-udp` sender over real UDP on 127.0.0.1, and
// hand-made datagrams from a raw socket: poses in m with the configured rotation, frame steps,
// split frames, Tracker's zero-padded blocks of every size (and the exact size), malformed and
// foreign datagrams counted with their reason, silence → every body lost once.
// Readiness is awaited on conditions, never by sleeping; nothing asserts on timing.
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include <gtest/gtest.h>
#include <asio.hpp>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/vicon_udp_sender.hpp"
#include "mocaplink/sources/vicon_udp_source.hpp"
#include "mocaplink/wire/vicon_udp.hpp"

namespace mocaplink::sources {
namespace {

using test::Collector;
using test::Event;
namespace vu = wire::vicon_udp;

ViconUdpOptions receiver_options() {
  ViconUdpOptions o;
  o.bind_host = "127.0.0.1";
  o.port = 0;  // any free port (the URL parser never gives 0)
  return o;
}

std::vector<core::MocapFrame> frames_of(const std::vector<Event>& events) {
  std::vector<core::MocapFrame> out;
  for (const auto& e : events) {
    if (e.is_frame) out.push_back(e.frame);
  }
  return out;
}

std::unique_ptr<ViconUdpSender> start_sender(std::uint16_t to_port,
                                             std::vector<std::pair<std::string, std::string>> set) {
  EmulatorOptions e;
  e.to_host = "127.0.0.1";
  e.to_port = to_port;
  e.rate_hz = 200.0;
  e.settings = std::move(set);
  auto options = vicon_udp_sender_options(e);
  EXPECT_TRUE(options) << options.error();
  auto sender = std::make_unique<ViconUdpSender>(options.value());
  const auto err = sender->start([](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(test::test_frame(tick + 1));
  });
  EXPECT_FALSE(err.has_value()) << *err;
  return sender;
}

/// `block_size`: the emulator's setting, or "" for its default (1024).
void loopback(vu::EulerOrder order, const char* rotation, const std::string& block_size = "") {
  auto options = receiver_options();
  options.rotation = order;
  ViconUdpSource source(options, "vicon-udp://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  ASSERT_NE(source.bound_port(), 0);
  std::vector<std::pair<std::string, std::string>> set{{"rotation", rotation}, {"frame_step", "2"}};
  if (!block_size.empty()) set.emplace_back("block_size", block_size);
  auto sender = start_sender(source.bound_port(), set);
  ASSERT_TRUE(got.wait_frames(40));
  sender->stop();
  source.stop();
  const auto frames = frames_of(got.events());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    if (i > 0) {
      EXPECT_GT(f.capture_time, frames[i - 1].capture_time);
      EXPECT_EQ(f.frame_step, 2u);
    }
    // The sender numbers tick k as 1 + 2k; test_frame(k + 1) is what it sent.
    const auto k = (f.frame_number - 1) / 2;
    const auto want = test::test_frame(k + 1);
    std::size_t w = 0;
    for (const auto& b : f.bodies) {
      while (w < want.bodies.size() && want.bodies[w].name != b.name) ++w;
      ASSERT_LT(w, want.bodies.size()) << b.name;
      EXPECT_TRUE(want.bodies[w].tracked) << "an occluded body was sent";
      EXPECT_LT((b.p_world_m - want.bodies[w].p_world_m).norm(), 1e-9);
      EXPECT_NEAR(std::abs(b.q_world_body.dot(want.bodies[w].q_world_body)), 1.0, 1e-9);
    }
  }
  EXPECT_EQ(source.counters().malformed, 0u);
  EXPECT_EQ(source.counters().last_rejection.get(), "");
  // Every datagram padded to the block, but with block_size=0 (exactly the items).
  const auto& c = source.udp_counters();
  if (block_size == "0") {
    EXPECT_EQ(c.padded, 0u);
  } else {
    EXPECT_GT(c.padded, 0u);
    EXPECT_EQ(c.padded, c.datagrams);
  }
}

TEST(ViconUdpLoopback, PosesFramesAndStepsXyz) {
  loopback(vu::EulerOrder::xyz, "xyz");
}

// Tracker's block sizes, and no padding at all: the same poses.
TEST(ViconUdpLoopback, BlockSize256) {
  loopback(vu::EulerOrder::xyz, "xyz", "256");
}
TEST(ViconUdpLoopback, BlockSize512) {
  loopback(vu::EulerOrder::xyz, "xyz", "512");
}
TEST(ViconUdpLoopback, BlockSize1024) {
  loopback(vu::EulerOrder::xyz, "xyz", "1024");
}
TEST(ViconUdpLoopback, ExactSizeWithoutPadding) {
  loopback(vu::EulerOrder::xyz, "xyz", "0");
}

// Two bodies in 80-byte blocks (one object each): split over two datagrams with one frame
// number, merged back into one frame.
TEST(ViconUdpLoopback, BlockTooSmallForEveryObjectSplitsTheFrame) {
  ViconUdpSource source(receiver_options(), "vicon-udp://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  auto sender = start_sender(source.bound_port(), {{"block_size", "80"}});
  ASSERT_TRUE(got.wait_frames(40));
  sender->stop();
  source.stop();
  EXPECT_GT(source.udp_counters().split_frames, 0u);
  EXPECT_EQ(source.udp_counters().padded, 0u);  // one object fills 80 bytes exactly
  EXPECT_EQ(source.counters().malformed, 0u);
  bool merged = false;
  for (const auto& f : frames_of(got.events())) merged = merged || f.bodies.size() == 2;
  EXPECT_TRUE(merged);
}

TEST(ViconUdpLoopback, PosesFramesAndStepsZyx) {
  loopback(vu::EulerOrder::zyx, "zyx");
}

TEST(ViconUdpLoopback, SplitDatagramsAndZerosForOccluded) {
  ViconUdpSource source(receiver_options(), "vicon-udp://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  auto sender = start_sender(source.bound_port(), {{"per_datagram", "1"}, {"occluded", "zeros"}});
  ASSERT_TRUE(got.wait_frames(40));
  sender->stop();
  source.stop();
  EXPECT_GT(source.udp_counters().split_frames, 0u);
  bool merged = false;
  bool zero_untracked = false;
  for (const auto& f : frames_of(got.events())) {
    merged = merged || f.bodies.size() == 2;
    for (const auto& b : f.bodies) {
      if (b.name == "Body2" && f.frame_number % 5 == 0) {
        EXPECT_FALSE(b.tracked);
        zero_untracked = true;
      }
    }
  }
  EXPECT_TRUE(merged);
  EXPECT_TRUE(zero_untracked);
}

/// Polls `done` (another thread's counters) for up to 5 s.
template <typename F>
bool wait_until(F done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

TEST(ViconUdpHostile, TrailingGarbageRefusedWithItsReason) {
  ViconUdpSource source(receiver_options(), "vicon-udp://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  const asio::ip::udp::endpoint to(asio::ip::make_address("127.0.0.1"), source.bound_port());
  asio::io_context io;
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  std::vector<vu::Object> three(3);
  for (std::size_t i = 0; i < three.size(); ++i) three[i].name = "Body" + std::to_string(i + 1);
  auto bytes = vu::encode_datagram(7, three, 1024);
  bytes[1000] = std::byte{0xFF};
  socket.send_to(asio::buffer(bytes), to);
  ASSERT_TRUE(wait_until([&] { return source.counters().malformed == 1; }));
  EXPECT_EQ(source.counters().last_rejection.get(),
            "malformed datagram at byte 1000: trailing non-zero bytes after 3 items (0xff in a "
            "1024-byte datagram)");
  EXPECT_EQ(source.counters().frames, 0u);
  source.stop();
}

TEST(ViconUdpHostile, MalformedAndForeignDatagramsCountedSilenceLosesBodies) {
  auto options = receiver_options();
  options.from = "127.0.0.1";
  options.lost = std::chrono::milliseconds(50);
  ViconUdpSource source(options, "vicon-udp://test");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  const asio::ip::udp::endpoint to(asio::ip::make_address("127.0.0.1"), source.bound_port());
  asio::io_context io;
  asio::ip::udp::socket good(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  asio::ip::udp::socket other(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.2"), 0));

  // Malformed: too short, a non-zero byte in the padding, a NaN.
  good.send_to(asio::buffer(std::string("\x01\x02\x03")), to);
  vu::Object a;
  a.name = "Drone1";
  a.t_mm = {1000, -500, 250};
  auto trailing = vu::encode_datagram(1, std::span(&a, 1), 256);
  trailing[200] = std::byte{0x41};
  good.send_to(asio::buffer(trailing), to);
  vu::Object nan = a;
  nan.rot_rad.x() = std::nan("");
  good.send_to(asio::buffer(vu::encode_datagram(2, std::span(&nan, 1))), to);
  ASSERT_TRUE(wait_until([&] { return source.counters().malformed == 3; }));
  EXPECT_EQ(source.counters().last_rejection.get(),
            "malformed datagram at byte 56: non-finite number in object Drone1");
  // From another address: dropped before parsing.
  other.send_to(asio::buffer(vu::encode_datagram(3, std::span(&a, 1))), to);
  ASSERT_TRUE(wait_until([&] { return source.counters().refused == 1; }));
  EXPECT_EQ(source.counters().last_rejection.get(),
            "datagram from 127.0.0.2, not 127.0.0.1 (from=)");
  EXPECT_EQ(source.counters().rejected(), 4u);
  // A good one, padded to 1024 bytes: the only frame.
  good.send_to(asio::buffer(vu::encode_datagram(4, std::span(&a, 1), 1024)), to);
  ASSERT_TRUE(got.wait_frames(1));
  // Then silence: one frame with Drone1 untracked.
  ASSERT_TRUE(got.wait_frames(2));
  source.stop();
  const auto frames = frames_of(got.events());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].frame_number, 4u);
  EXPECT_EQ(frames[0].bodies[0].p_world_m, Eigen::Vector3d(1.0, -0.5, 0.25));
  EXPECT_TRUE(frames[0].bodies[0].tracked);
  ASSERT_EQ(frames[1].bodies.size(), 1u);
  EXPECT_FALSE(frames[1].bodies[0].tracked);
  EXPECT_EQ(source.counters().malformed, 3u);
  EXPECT_EQ(source.udp_counters().foreign, 1u);
  const auto events = got.events();
  EXPECT_TRUE(std::any_of(events.begin(), events.end(), [](const Event& e) {
    return !e.is_frame && e.state == SourceState::disconnected;
  }));
}

}  // namespace
}  // namespace mocaplink::sources
