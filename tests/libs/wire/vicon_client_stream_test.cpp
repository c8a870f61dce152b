// The client's packet processing (§7) and mapping to MocapFrame (§9), on the spec's worked
// examples 2 and 3 (§11), transcribed by hand; the SDK's decoding of the same bytes is the oracle.
#include <cmath>

#include <gtest/gtest.h>

#include "mocaplink/wire/vicon_client_stream.hpp"
#include "mocaplink/wire/vicon_mocap_frame.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "mocaplink/wire/vicon_pose.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vicon {
namespace {

using test::body_of;
using test::hex;

// §11 example 2, frame A (274 bytes): subject "Drone", frame 41, 100 Hz, t = (1000, −250.5,
// 1500.25) mm, R = +90° about Z.
const char* const kFrameA =
    "01 00 2b 1a 0a 01 00 00 a4 86 01 00 28 00 00 00 04 00 00 00 01 00 00 00 01 00 00 00 02 00 00 "
    "00"
    "01 00 00 00 05 00 00 00 01 00 00 00 09 00 00 00 01 00 00 00 00 00 00 00 01 00 00 00 08 00 00 "
    "00"
    "70 99 14 00 00 00 00 00 02 00 00 00 42 00 00 00 01 00 00 00 05 00 00 00 44 72 6f 6e 65 01 00 "
    "00"
    "00 00 00 00 00 01 00 00 00 00 00 48 c2 00 00 48 c2 00 00 20 c1 00 00 48 42 00 00 48 42 00 00 "
    "20"
    "41 05 00 00 00 44 72 6f 6e 65 00 00 00 00 00 00 00 00 05 00 00 00 04 00 00 00 29 00 00 00 09 "
    "00"
    "00 00 6c 00 00 00 01 00 00 00 01 00 00 00 01 00 00 00 00 00 00 00 00 40 8f 40 00 00 00 00 00 "
    "50"
    "6f c0 00 00 00 00 00 71 97 40 00 00 00 00 00 00 00 00 00 00 00 00 00 00 f0 bf 00 00 00 00 00 "
    "00"
    "00 00 00 00 00 00 00 00 f0 3f 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 "
    "00"
    "00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 f0 3f";

// §11 example 3, frame B (104 bytes): SubjectInfo listed unchanged, subject 1 with 0 segments.
const char* const kFrameB =
    "01 00 2b 1a 60 00 00 00 a4 86 01 00 2c 00 00 00 04 00 00 00 01 00 00 00 01 00 00 00 02 00 00 "
    "00"
    "00 00 00 00 05 00 00 00 01 00 00 00 09 00 00 00 01 00 00 00 01 00 00 00 02 00 00 00 01 00 00 "
    "00"
    "08 00 00 00 70 99 14 00 00 00 00 00 05 00 00 00 04 00 00 00 2a 00 00 00 09 00 00 00 08 00 00 "
    "00"
    "01 00 00 00 00 00 00 00";

// Frame B with an empty unchanged set (the spec's negative control; body 4 bytes shorter).
const char* const kFrameBNoUnchanged =
    "01 00 2b 1a 5c 00 00 00 a4 86 01 00 28 00 00 00 04 00 00 00 01 00 00 00 01 00 00 00 02 00 00 "
    "00"
    "00 00 00 00 05 00 00 00 01 00 00 00 09 00 00 00 01 00 00 00 00 00 00 00"
    "01 00 00 00 08 00 00 00 70 99 14 00 00 00 00 00 05 00 00 00 04 00 00 00 2a 00 00 00"
    "09 00 00 00 08 00 00 00 01 00 00 00 00 00 00 00";

PacketOutcome apply_ok(ClientStream& s, const char* packet_hex) {
  const auto packet = hex(packet_hex);
  EXPECT_TRUE(parse_packet_header(packet).ok());
  const auto body = body_of(packet);
  auto r = s.apply(body);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().reason);
  return r.value();
}

TEST(ViconClientStream, FrameADecodesAsTheSdkDid) {
  ClientStream s;
  const PacketOutcome out = apply_ok(s, kFrameA);
  ASSERT_TRUE(out.frame.has_value());
  const DecodedFrame& f = *out.frame;
  EXPECT_EQ(f.frame_id, 41u);  // the SDK reports 42 (id + 1, §9.5); we report the wire id
  ASSERT_TRUE(f.frame_period_ticks.has_value());
  EXPECT_EQ(*f.frame_period_ticks, 1'350'000);
  ASSERT_EQ(f.subjects.size(), 1u);
  EXPECT_EQ(f.subjects[0].name, "Drone");
  EXPECT_EQ(f.subjects[0].root_segment, "Drone");
  EXPECT_FALSE(f.subjects[0].occluded);

  const MappedFrame m = to_mocap_frame(f);
  EXPECT_EQ(m.invalid_poses, 0u);
  EXPECT_EQ(m.frame.frame_number, 41u);
  ASSERT_TRUE(m.frame.frame_rate_hz.has_value());
  EXPECT_DOUBLE_EQ(*m.frame.frame_rate_hz, 100.0);
  EXPECT_FALSE(m.frame.source_latency.has_value());  // no LatencyInfo in frame A
  EXPECT_EQ(m.frame.capture_time, core::source_time_from_ns(410'000'000));  // 41 × 10 ms
  ASSERT_EQ(m.frame.bodies.size(), 1u);
  const core::BodySample& b = m.frame.bodies[0];
  EXPECT_EQ(b.name, "Drone");
  EXPECT_TRUE(b.tracked);
  EXPECT_DOUBLE_EQ(b.p_world_m.x(), 1.0);
  EXPECT_DOUBLE_EQ(b.p_world_m.y(), -0.2505);
  EXPECT_DOUBLE_EQ(b.p_world_m.z(), 1.50025);
  // SDK: q (x, y, z, w) = (0, 0, 0.707106781187, 0.707106781187).
  EXPECT_NEAR(b.q_world_body.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(b.q_world_body.x(), 0.0, 1e-12);
  EXPECT_NEAR(b.q_world_body.y(), 0.0, 1e-12);
  EXPECT_NEAR(b.q_world_body.z(), std::sqrt(0.5), 1e-12);
}

TEST(ViconClientStream, FrameBKeepsTheSubjectThroughUnchangedAndIsOccluded) {
  ClientStream s;
  (void)apply_ok(s, kFrameA);
  const PacketOutcome out = apply_ok(s, kFrameB);
  ASSERT_TRUE(out.frame.has_value());
  EXPECT_EQ(out.frame->frame_id, 42u);
  ASSERT_EQ(out.frame->subjects.size(), 1u);
  EXPECT_EQ(out.frame->subjects[0].name, "Drone");
  EXPECT_TRUE(out.frame->subjects[0].occluded);
  const MappedFrame m = to_mocap_frame(*out.frame);
  ASSERT_EQ(m.frame.bodies.size(), 1u);
  EXPECT_FALSE(m.frame.bodies[0].tracked);
}

TEST(ViconClientStream, WithoutUnchangedTheSubjectIsForgotten) {
  ClientStream s;
  (void)apply_ok(s, kFrameA);
  const PacketOutcome out = apply_ok(s, kFrameBNoUnchanged);
  ASSERT_TRUE(out.frame.has_value());
  EXPECT_TRUE(out.frame->subjects.empty());  // the SDK reported "subjects": []
}

TEST(ViconClientStream, PacketWithoutStaticItemsKeepsTheStaticSet) {
  // §7 step 4: Contents + FrameInfo + GlobalSegments only: the Drone stays known and tracked.
  ClientStream s;
  (void)apply_ok(s, kFrameA);
  PacketBuilder b;
  GlobalSegments g{1, {SegmentPose{1, {1, 2, 3}, {1, 0, 0, 0, 1, 0, 0, 0, 1}}}};
  b.add(Contents{}).add(FrameInfo{50}).add(g);
  const auto packet = b.finish();
  auto r = s.apply(body_of(packet));
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r.value().frame.has_value());
  ASSERT_EQ(r.value().frame->subjects.size(), 1u);
  EXPECT_FALSE(r.value().frame->subjects[0].occluded);
  EXPECT_EQ(r.value().frame->subjects[0].translation_mm[2], 3.0);
  ASSERT_TRUE(r.value().frame->frame_period_ticks.has_value());  // StreamInfo kept too
}

TEST(ViconClientStream, PingEchoAloneDeliversNoFrame) {
  ClientStream s;
  (void)apply_ok(s, kFrameA);
  const PacketOutcome out =
      apply_ok(s, "01 00 2b 1a 10 00 00 00 2a 00 00 00 08 00 00 00 3b 00 00 00 00 00 00 00");
  EXPECT_FALSE(out.frame.has_value());
  EXPECT_EQ(out.ping_ids, (std::vector<std::uint64_t>{59}));
}

TEST(ViconClientStream, UnknownItemsAndKeepAliveAreSkipped) {
  // §3 (verified with the SDK): type 12345 and a KeepAlive in front of a frame do not disturb it.
  ClientStream s;
  auto packet = hex(kFrameA);
  const auto a_body = body_of(packet);
  PacketBuilder b;
  const auto junk = hex("de ad be ef");
  b.add_raw(12345, junk).add(KeepAlive{});
  auto prefix = b.finish();
  std::vector<std::byte> body(prefix.begin() + 8, prefix.end());
  body.insert(body.end(), a_body.begin(), a_body.end());
  auto r = s.apply(body);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().unknown_items, 1u);
  EXPECT_EQ(r.value().keep_alives, 1u);
  ASSERT_TRUE(r.value().frame.has_value());
  EXPECT_EQ(r.value().frame->frame_id, 41u);
}

TEST(ViconClientStream, MalformedItemLeavesStateUntouched) {
  ClientStream s;
  (void)apply_ok(s, kFrameA);
  // FrameInfo with a 2-byte payload: the packet is rejected.
  PacketBuilder b;
  b.add(Contents{}).add_raw(5, hex("01 02"));
  const auto packet = b.finish();
  auto r = s.apply(body_of(packet));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().reason.find("FrameInfo"), std::string::npos);
  // The previous state still answers an unchanged-everything packet.
  PacketBuilder c;
  c.add(Contents{{}, {2, 5, 9}}).add(StreamInfo{1'350'000});
  c.add(FrameInfo{43});
  const auto next = c.finish();
  auto ok = s.apply(body_of(next));
  ASSERT_TRUE(ok.ok());
  ASSERT_TRUE(ok.value().frame.has_value());
  ASSERT_EQ(ok.value().frame->subjects.size(), 1u);
  EXPECT_FALSE(ok.value().frame->subjects[0].occluded);  // GlobalSegments copied from frame A
}

TEST(ViconClientStream, DynamicPacketWithoutFrameInfoGivesNoFrame) {
  ClientStream s;
  PacketBuilder b;
  b.add(Contents{}).add(LatencyInfo{{{"x", 0.001}}});
  const auto packet = b.finish();
  auto r = s.apply(body_of(packet));
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.value().frame.has_value());
  EXPECT_FALSE(r.value().frame_dropped_reason.empty());
}

TEST(ViconClientStream, GreetingAndRequest) {
  const auto greeting =
      hex("01 00 2b 1a 20 00 00 00 a1 86 01 00 18 00 00 00 05 00 00 00 01 00 00 00 02 00 00 00"
          "05 00 00 00 09 00 00 00 a4 86 01 00");
  auto offered = parse_greeting(body_of(greeting));
  ASSERT_TRUE(offered.ok());
  EXPECT_EQ(client_request(offered.value()).types,
            (std::vector<std::uint32_t>{1, 2, 5, 9, 100004}));
  EXPECT_EQ(client_request(ObjectEnums{}).types, (std::vector<std::uint32_t>{100004}));
  EXPECT_FALSE(parse_greeting(body_of(hex(kFrameA))).ok());  // no ObjectEnums in it
}

TEST(ViconMocapFrame, LatencyIsTheSumOfSamplesAndYUpIsTurnedZUp) {
  DecodedFrame f;
  f.frame_id = 7;
  f.latency = LatencyInfo{{{"a", 0.002}, {"b", 0.0005}}};
  f.y_up = true;
  SubjectSample s;
  s.name = "Body1";
  s.occluded = false;
  s.translation_mm = {100, 200, 300};
  // +90° about the server's y (up) axis: x → −z.
  s.rotation = {0, 0, 1, 0, 1, 0, -1, 0, 0};
  f.subjects.push_back(s);
  const MappedFrame m = to_mocap_frame(f);
  ASSERT_TRUE(m.frame.source_latency.has_value());
  EXPECT_EQ(*m.frame.source_latency, std::chrono::microseconds(2500));
  EXPECT_FALSE(m.frame.frame_rate_hz.has_value());
  const auto& b = m.frame.bodies.at(0);
  // §9.4: (x, y, z) → (x, −z, y).
  EXPECT_DOUBLE_EQ(b.p_world_m.x(), 0.1);
  EXPECT_DOUBLE_EQ(b.p_world_m.y(), -0.3);
  EXPECT_DOUBLE_EQ(b.p_world_m.z(), 0.2);
  // A rotation about the vertical stays about the vertical: +90° about Z-up.
  EXPECT_NEAR(std::abs(b.q_world_body.z()), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(std::abs(b.q_world_body.w()), std::sqrt(0.5), 1e-12);
  EXPECT_GT(b.q_world_body.z() * b.q_world_body.w(), 0.0);
}

TEST(ViconMocapFrame, BadRotationIsUntrackedAndCounted) {
  DecodedFrame f;
  SubjectSample s;
  s.name = "B";
  s.occluded = false;
  s.rotation = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  f.subjects.push_back(s);
  s.rotation = {1, 0, 0, 0, 1, 0, 0, 0, std::nan("")};
  f.subjects.push_back(s);
  s.rotation = {2, 0, 0, 0, 2, 0, 0, 0, 2};
  f.subjects.push_back(s);
  const MappedFrame m = to_mocap_frame(f);
  EXPECT_EQ(m.invalid_poses, 3u);
  for (const auto& b : m.frame.bodies) {
    EXPECT_FALSE(b.tracked);
    EXPECT_FALSE(b.mirrored);  // none of them orthonormal
  }
}

TEST(ViconMocapFrame, AReflectionIsUntrackedAndNamedMirrored) {
  // An orthonormal matrix with det −1 (z flipped, and the same after a 90° turn about z): a
  // left-handed frame, not a pose; a float-rounded proper rotation stays a pose.
  DecodedFrame f;
  SubjectSample s;
  s.name = "B";
  s.occluded = false;
  s.rotation = {1, 0, 0, 0, 1, 0, 0, 0, -1};
  f.subjects.push_back(s);
  s.rotation = {0, -1, 0, 1, 0, 0, 0, 0, -1};
  f.subjects.push_back(s);
  const float c = static_cast<float>(std::sqrt(0.5));
  s.rotation = {c, -c, 0, c, c, 0, 0, 0, 1};
  f.subjects.push_back(s);
  const MappedFrame m = to_mocap_frame(f);
  EXPECT_EQ(m.invalid_poses, 2u);
  EXPECT_TRUE(m.frame.bodies[0].mirrored);
  EXPECT_TRUE(m.frame.bodies[1].mirrored);
  EXPECT_FALSE(m.frame.bodies[0].tracked);
  EXPECT_TRUE(m.frame.bodies[2].tracked);
  EXPECT_FALSE(m.frame.bodies[2].mirrored);
  EXPECT_TRUE(is_mirrored_rotation({-1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_FALSE(is_mirrored_rotation({1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_FALSE(is_mirrored_rotation({-2, 0, 0, 0, 1, 0, 0, 0, 1}));
}

}  // namespace
}  // namespace mocaplink::wire::vicon
