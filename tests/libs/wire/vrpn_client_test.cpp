// VRPN id tables and frame assembly (wire/vrpn_client.hpp) with injected host time: messages are
// the document's vectors (vrpn.md §9) or built from its layout.
#include <gtest/gtest.h>
#include <cstddef>

#include "mocaplink/wire/vrpn_client.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vrpn {
namespace {

using std::chrono::milliseconds;
using vicon::test::hex;

struct Split {
  Header header;
  std::vector<std::byte> payload;
};

Split split(const std::vector<std::byte>& message) {
  auto h = parse_header(std::span(message).first(kHeaderBytes));
  EXPECT_TRUE(h);
  const auto begin = message.begin() + kHeaderBytes;
  return {h.value(), {begin, begin + static_cast<std::ptrdiff_t>(h.value().payload_bytes())}};
}

Result<MessageOutcome> feed(ClientTables& t, const std::vector<std::byte>& message) {
  const Split s = split(message);
  return t.apply(s.header, s.payload);
}

TEST(VrpnClientTables, DocumentVectorsGiveANamedReport) {
  ClientTables t;
  // Pos_Quat before the descriptions: ids unknown, ignored.
  const auto pos_quat = hex(
      "000000586553f1000007a12000000000000000030000000200000000000000003ff0000000000000bfe00000"
      "000000003fd0000000000000000000000000000000000000000000003fe6a09e667f3bcd3fe6a09e667f3bcd");
  auto early = feed(t, pos_quat);
  ASSERT_TRUE(early);
  EXPECT_TRUE(early.value().unknown_id);
  EXPECT_FALSE(early.value().report);

  auto sender = feed(t, hex("000000236553f1000003d09000000000ffffffff00000000000000074472"
                            "6f6e6531000000000000"));
  ASSERT_TRUE(sender);
  EXPECT_EQ(sender.value().new_sender, "Drone1");
  ASSERT_TRUE(feed(t, hex("000000326553f1000003d09000000003fffffffe00000001000000167672706e5f"
                          "547261636b657220506f735f5175617400000000000000")));
  auto report = feed(t, pos_quat);
  ASSERT_TRUE(report);
  ASSERT_TRUE(report.value().report);
  EXPECT_EQ(report.value().report->tracker, "Drone1");
  EXPECT_EQ(report.value().report->pose.p_m, Eigen::Vector3d(1.0, -0.5, 0.25));
  EXPECT_EQ(report.value().report->time, (Timeval{1'700'000'000u, 500'000u}));
  EXPECT_EQ(t.senders(), std::vector<std::string>{"Drone1"});
}

TEST(VrpnClientTables, OtherTypesAndSystemMessagesIgnoredMalformedRefused) {
  ClientTables t;
  ASSERT_TRUE(feed(t, encode_description({}, kSenderDescription, 4, "Quad")));
  ASSERT_TRUE(feed(t, encode_description({}, kTypeDescription, 9, kVelocityType)));
  const std::array<std::byte, 72> velocity{};
  auto other = feed(t, encode_message({}, 4, 9, velocity));
  ASSERT_TRUE(other);
  EXPECT_FALSE(other.value().report);
  EXPECT_FALSE(other.value().unknown_id);
  const std::array<std::byte, 10> udp_description{};
  EXPECT_TRUE(feed(t, encode_message({}, 3883, kUdpDescription, udp_description)));
  // A bad description is an error (the connection is dropped by the caller).
  const std::array<std::byte, 3> short_description{};
  EXPECT_FALSE(feed(t, encode_message({}, 1, kSenderDescription, short_description)));
}

TEST(VrpnClientTables, TablesAreBounded) {
  ClientTables t;
  for (std::size_t i = 0; i < kMaxIds; ++i) {
    ASSERT_TRUE(feed(t, encode_description({}, kTypeDescription, static_cast<std::int32_t>(i),
                                           "t" + std::to_string(i))));
  }
  auto over = feed(t, encode_description({}, kTypeDescription, -7 + 100000, "more"));
  ASSERT_TRUE(over);
  EXPECT_TRUE(over.value().over_limit);
  // Redescribing a known id still works.
  auto again = feed(t, encode_description({}, kTypeDescription, 0, "t0b"));
  ASSERT_TRUE(again);
  EXPECT_TRUE(again.value().described);
}

Report report(const std::string& name, double x, std::int32_t sensor = 0) {
  Report r;
  r.tracker = name;
  r.pose.sensor = sensor;
  r.pose.p_m = Eigen::Vector3d(x, 0, 0);
  return r;
}

core::HostTime at_ms(std::int64_t ms) {
  return core::host_time_from_ns(ms * 1'000'000);
}

TEST(VrpnFrameAssembler, RoundsCloseOnRepeatOrWhenCompleteOnDrain) {
  FrameAssembler a;
  EXPECT_FALSE(a.on_report(report("A", 1), at_ms(0)));
  EXPECT_FALSE(a.on_report(report("B", 2, 1), at_ms(1)));
  // First round: nothing expected yet, so a drained socket closes it.
  auto f1 = a.on_drained();
  ASSERT_TRUE(f1);
  EXPECT_EQ(f1->frame.frame_number, 1u);
  EXPECT_EQ(f1->frame.frame_step, 0u);
  EXPECT_EQ(f1->frame.capture_time, core::source_time_from_ns(0));
  ASSERT_EQ(f1->frame.bodies.size(), 2u);
  EXPECT_EQ(f1->frame.bodies[0].name, "A");
  EXPECT_EQ(f1->frame.bodies[1].name, "B:1");
  EXPECT_TRUE(f1->frame.bodies[0].tracked);
  // Second round: A alone is incomplete on drain; B completes it.
  EXPECT_FALSE(a.on_report(report("A", 1.1), at_ms(10)));
  EXPECT_FALSE(a.on_drained());
  EXPECT_FALSE(a.on_report(report("B", 2.1, 1), at_ms(11)));
  auto f2 = a.on_drained();
  ASSERT_TRUE(f2);
  EXPECT_EQ(f2->frame.frame_number, 2u);
  EXPECT_EQ(f2->frame.capture_time, core::source_time_from_ns(10'000'000));
  // B gone: A repeating closes the round without B.
  EXPECT_FALSE(a.on_report(report("A", 1.2), at_ms(20)));
  EXPECT_FALSE(a.on_drained());
  auto f3 = a.on_report(report("A", 1.3), at_ms(30));
  ASSERT_TRUE(f3);
  ASSERT_EQ(f3->frame.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(f3->frame.bodies[0].p_world_m.x(), 1.2);
  // From now on A alone is a complete round.
  auto f4 = a.on_drained();
  ASSERT_TRUE(f4);
  EXPECT_DOUBLE_EQ(f4->frame.bodies[0].p_world_m.x(), 1.3);
}

// Trackers at unequal rates (A at 100 Hz, B at 50 Hz), each update one read that drains the
// socket, on_idle asked at every idle_deadline before the next update, as the source's timer
// does: every round is delivered at most settle_after after its last report, never held back
// until the next update; and `received` is that last report's arrival.
TEST(VrpnFrameAssembler, IncompleteRoundSettlesInsteadOfWaitingForTheNextUpdate) {
  FrameAssembler a;                                               // settle_after 2 ms
  std::vector<std::pair<std::size_t, core::Duration>> delivered;  // (bodies, late by)
  core::HostTime last{};
  const auto take = [&](std::optional<AssembledFrame> f, core::HostTime now) {
    if (!f) return;
    EXPECT_EQ(f->received, last);
    delivered.emplace_back(f->frame.bodies.size(), now - last);
  };
  for (int n = 0; n < 20; ++n) {
    const auto t = at_ms(10 * n);
    last = t;
    take(a.on_report(report("A", n), t), t);
    if (n % 2 == 0) take(a.on_report(report("B", n, 1), t), t);
    take(a.on_drained(), t);
    while (const auto d = a.idle_deadline()) {
      if (*d >= at_ms(10 * (n + 1))) break;
      take(a.on_idle(*d), *d);
    }
  }
  ASSERT_EQ(delivered.size(), 20u);
  for (std::size_t i = 0; i < delivered.size(); ++i) {
    EXPECT_EQ(delivered[i].first, i % 2 == 0 ? 2u : 1u) << i;
    EXPECT_LE(delivered[i].second, milliseconds(2)) << i;
  }
}

// The server stalls right after an incomplete round: the round goes out after settle_after with
// `received` at its report's arrival (honest, so an age check downstream can judge it), and the
// loss frame follows after lost_after.
TEST(VrpnFrameAssembler, StallMidRoundDeliversTheRoundWithItsArrivalTime) {
  AssemblerConfig c;
  c.lost_after = milliseconds(500);
  FrameAssembler a(c);
  (void)a.on_report(report("A", 1), at_ms(0));
  (void)a.on_report(report("B", 1), at_ms(0));
  ASSERT_TRUE(a.on_drained());
  (void)a.on_report(report("A", 2), at_ms(10));
  EXPECT_FALSE(a.on_drained());  // B missing: settles
  ASSERT_TRUE(a.idle_deadline());
  EXPECT_EQ(*a.idle_deadline(), at_ms(12));
  EXPECT_FALSE(a.on_idle(at_ms(11)));
  // However late the timer gets to it, the round says when its data arrived.
  auto round = a.on_idle(at_ms(300));
  ASSERT_TRUE(round);
  EXPECT_EQ(round->received, at_ms(10));
  ASSERT_EQ(round->frame.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(round->frame.bodies[0].p_world_m.x(), 2.0);
  ASSERT_TRUE(a.idle_deadline());
  EXPECT_EQ(*a.idle_deadline(), at_ms(510));
  auto lost = a.on_idle(at_ms(510));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->received, at_ms(510));
  EXPECT_FALSE(lost->frame.bodies[0].tracked);
}

TEST(VrpnFrameAssembler, CaptureTimesStrictlyIncrease) {
  FrameAssembler a;
  (void)a.on_report(report("A", 1), at_ms(5));
  auto f1 = a.on_report(report("A", 2), at_ms(5));  // two rounds in one read
  auto f2 = a.flush();
  ASSERT_TRUE(f1 && f2);
  EXPECT_GT(f2->frame.capture_time, f1->frame.capture_time);
}

TEST(VrpnFrameAssembler, SilenceGivesOneLossFrame) {
  AssemblerConfig c;
  c.lost_after = milliseconds(100);
  FrameAssembler a(c);
  EXPECT_FALSE(a.idle_deadline());
  (void)a.on_report(report("A", 1), at_ms(0));
  ASSERT_TRUE(a.idle_deadline());  // armed by the report itself, before any frame went out
  ASSERT_TRUE(a.on_drained());
  ASSERT_TRUE(a.idle_deadline());
  EXPECT_EQ(*a.idle_deadline(), at_ms(100));
  EXPECT_FALSE(a.on_idle(at_ms(99)));
  auto lost = a.on_idle(at_ms(100));
  ASSERT_TRUE(lost);
  ASSERT_EQ(lost->frame.bodies.size(), 1u);
  EXPECT_FALSE(lost->frame.bodies[0].tracked);
  EXPECT_FALSE(a.on_idle(at_ms(500)));
  EXPECT_FALSE(a.idle_deadline());
}

TEST(VrpnFrameAssembler, FrozenPoseBecomesUntracked) {
  AssemblerConfig c;
  c.frozen_after = milliseconds(50);
  FrameAssembler a(c);
  for (int i = 0; i <= 10; ++i) {
    auto f = a.on_report(report("A", 1.0), at_ms(i * 10));
    if (f) {
      EXPECT_EQ(f->frame.bodies[0].tracked, i <= 5) << i;  // frame i−1 closed by report i
    }
  }
  EXPECT_GT(a.frozen_samples(), 0u);
  auto moved = a.on_report(report("A", 1.5), at_ms(200));
  ASSERT_TRUE(moved);
  EXPECT_FALSE(moved->frame.bodies[0].tracked);
  auto next = a.flush();
  ASSERT_TRUE(next);
  EXPECT_TRUE(next->frame.bodies[0].tracked);
}

TEST(VrpnFrameAssembler, ResetForgetsTheRoundAndBodiesBounded) {
  AssemblerConfig c;
  c.max_bodies = 2;
  FrameAssembler a(c);
  (void)a.on_report(report("A", 1), at_ms(0));
  (void)a.on_report(report("B", 1), at_ms(0));
  (void)a.on_report(report("C", 1), at_ms(0));
  EXPECT_EQ(a.ignored_bodies(), 1u);
  a.reset();
  EXPECT_FALSE(a.flush());  // the old connection's round never becomes a frame
  EXPECT_FALSE(a.idle_deadline());
  (void)a.on_report(report("C", 1), at_ms(10));
  auto f = a.flush();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame.bodies[0].name, "C");
}

}  // namespace
}  // namespace mocaplink::wire::vrpn
