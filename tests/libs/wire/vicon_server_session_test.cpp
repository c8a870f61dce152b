// The emulator's per-connection logic (§6, §7, §12 "Server emulator"), checked by decoding its
// packets with the item parsers (which the golden tests pin to the spec's bytes) and against the
// spec's frame A bytes (§11 example 2).
#include <gtest/gtest.h>

#include "mocaplink/wire/vicon_client_stream.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "mocaplink/wire/vicon_server_session.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vicon {
namespace {

using test::body_of;
using test::hex;

ServedFrame frame(std::uint64_t seq, std::uint32_t id, bool tracked = true) {
  ServedFrame f;
  f.sequence = seq;
  f.frame_id = id;
  f.frame_period_ticks = 1'350'000;
  f.subjects.push_back(
      ServedSubject{1, "Body1", tracked, {1000, -250.5, 1500.25}, {0, -1, 0, 1, 0, 0, 0, 0, 1}});
  f.subjects.push_back(ServedSubject{2, "Body2", true, {1, 2, 3}, {1, 0, 0, 0, 1, 0, 0, 0, 1}});
  f.latency.push_back(LatencySample{"Emulator Acquisition", 0.004});
  return f;
}

template <Item T>
std::vector<std::byte> body_with(const T& item) {
  PacketBuilder b;
  b.add(item);
  return body_of(b.finish());
}

std::vector<std::uint32_t> item_types(const std::vector<std::byte>& packet) {
  const auto body = body_of(packet);
  auto items = split_items(body);
  EXPECT_TRUE(items.ok());
  std::vector<std::uint32_t> out;
  for (const auto& i : items.value()) out.push_back(i.type);
  return out;
}

TEST(ViconServerSession, EncodesFrameAExactlyForTheSameItems) {
  // The spec's frame A carries segment bounds, which our emulator leaves at 0; built with the same
  // items, the PacketBuilder must reproduce the spec's 274 bytes.
  PacketBuilder b;
  b.add(Contents{{{1, 1}, {2, 1}, {5, 1}, {9, 1}}, {}});
  b.add(StreamInfo{1'350'000});
  b.add(SubjectInfo{1, "Drone", {SegmentInfo{0, 1, {-50, -50, -10, 50, 50, 10}, "Drone"}}, {}, {}});
  b.add(FrameInfo{41});
  b.add(GlobalSegments{1, {SegmentPose{1, {1000, -250.5, 1500.25}, {0, -1, 0, 1, 0, 0, 0, 0, 1}}}});
  const auto a = b.finish();
  ASSERT_EQ(a.size(), 274u);
  EXPECT_EQ(std::vector<std::byte>(a.begin(), a.begin() + 16),
            hex("01 00 2b 1a 0a 01 00 00 a4 86 01 00 28 00 00 00"));
  EXPECT_EQ(std::vector<std::byte>(a.end() - 18, a.end()),
            hex("00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 f0 3f"));
}

TEST(ViconServerSession, GreetingOffersContentsAndSegments) {
  ServerSession s;
  auto offered = parse_greeting(body_of(s.greeting()));
  ASSERT_TRUE(offered.ok());
  const auto& t = offered.value().types;
  EXPECT_NE(std::find(t.begin(), t.end(), 100004u), t.end());
  EXPECT_NE(std::find(t.begin(), t.end(), 9u), t.end());
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
}

TEST(ViconServerSession, PushSendsEveryFrameAndClientDecodesIt) {
  ServerSession s;
  ClientStream c;
  ASSERT_TRUE(
      s.on_client_packet(body_with(client_request(ObjectEnums{server_offered_types()})), nullptr)
          .ok());
  EXPECT_FALSE(s.on_new_frame(frame(1, 10)).has_value());  // not streaming yet
  auto r = s.on_client_packet(body_with(RequestFrame{true}), nullptr);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.value().empty());
  for (std::uint32_t id = 11; id < 14; ++id) {
    auto p = s.on_new_frame(frame(id, id, id != 12));
    ASSERT_TRUE(p.has_value());
    auto out = c.apply(body_of(*p));
    ASSERT_TRUE(out.ok()) << out.error().reason;
    ASSERT_TRUE(out.value().frame.has_value());
    const DecodedFrame& f = *out.value().frame;
    EXPECT_EQ(f.frame_id, id);
    ASSERT_EQ(f.subjects.size(), 2u);
    EXPECT_EQ(f.subjects[0].name, "Body1");
    EXPECT_EQ(f.subjects[0].occluded, id == 12);
    if (id != 12) {
      EXPECT_EQ(f.subjects[0].translation_mm[1], -250.5);
    }
    ASSERT_TRUE(f.latency.has_value());
    EXPECT_EQ(f.latency->samples.at(0).seconds, 0.004);
  }
}

TEST(ViconServerSession, StaticTypesAreMarkedUnchangedAfterTheFirstFrame) {
  ServerSession s;
  ASSERT_TRUE(s.on_client_packet(body_with(ObjectEnums{{1, 2, 5, 9, 100004}}), nullptr).ok());
  const auto first = s.encode_frame(frame(1, 1));
  const auto second = s.encode_frame(frame(2, 2));
  EXPECT_EQ(item_types(first), (std::vector<std::uint32_t>{100004, 1, 2, 2, 5, 9, 9}));
  EXPECT_EQ(item_types(second), (std::vector<std::uint32_t>{100004, 5, 9, 9}));
  const auto body = body_of(second);
  auto items = split_items(body);
  ASSERT_TRUE(items.ok());
  auto contents = parse_item<Contents>(items.value()[0].payload);
  ASSERT_TRUE(contents.ok());
  EXPECT_EQ(contents.value().unchanged, (std::vector<std::uint32_t>{1, 2}));
  using Entry = std::pair<std::uint32_t, std::uint32_t>;
  EXPECT_EQ(contents.value().table, (std::vector<Entry>{{1, 0}, {2, 0}, {5, 1}, {9, 2}}));
  // A new ObjectEnums (even the same set plus one) forgets what the client holds: sent in full.
  ASSERT_TRUE(s.on_client_packet(body_with(ObjectEnums{{1, 2, 5, 9, 26, 100004}}), nullptr).ok());
  EXPECT_EQ(item_types(s.encode_frame(frame(3, 3))),
            (std::vector<std::uint32_t>{100004, 1, 2, 2, 5, 9, 9, 26}));
}

TEST(ViconServerSession, PullAnswersEveryRequestWithTheLatestFrame) {
  ServerSession s;
  const ServedFrame latest = frame(5, 50);
  auto r1 = s.on_client_packet(body_with(RequestFrame{false}), &latest);
  auto r2 = s.on_client_packet(body_with(RequestFrame{false}), &latest);
  ASSERT_TRUE(r1.ok());
  ASSERT_TRUE(r2.ok());
  ASSERT_EQ(r1.value().size(), 1u);
  ASSERT_EQ(r2.value().size(), 1u);  // a repeat of frame 50 (§6.3)
  EXPECT_FALSE(s.on_new_frame(frame(6, 51)).has_value());
  auto none = s.on_client_packet(body_with(RequestFrame{false}), nullptr);
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none.value().empty());  // nothing produced yet: nothing to send
}

TEST(ViconServerSession, PrefetchNeverRepeatsAFrame) {
  ServerSession s;
  const ServedFrame f1 = frame(1, 100);
  auto r = s.on_client_packet(body_with(RequestNextFrame{1}), &f1);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.value().size(), 1u);  // f1 newer than anything sent: at once
  r = s.on_client_packet(body_with(RequestNextFrame{1}), &f1);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.value().empty());  // f1 already sent: wait for the next one
  EXPECT_EQ(s.pending_next(), 1u);
  EXPECT_TRUE(s.on_new_frame(frame(2, 101)).has_value());
  EXPECT_EQ(s.pending_next(), 0u);
  EXPECT_FALSE(s.on_new_frame(frame(3, 102)).has_value());
  r = s.on_client_packet(body_with(RequestNextFrame{0xFFFFFFFF}), nullptr);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(s.pending_next(), ServerSession::kMaxPendingNext);
}

TEST(ViconServerSession, PingIsEchoedAndFilterLimitsSubjects) {
  ServerSession s;
  PacketBuilder b;
  b.add(Filter{{{9, {2}}, {2, {2}}}}).add(Ping{77}).add(ObjectEnums{{2, 5, 9, 100004}});
  const auto body = body_of(b.finish());
  auto r = s.on_client_packet(body, nullptr);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.value().size(), 1u);
  EXPECT_EQ(r.value()[0], hex("01 00 2b 1a 10 00 00 00 2a 00 00 00 08 00 00 00"
                              "4d 00 00 00 00 00 00 00"));
  EXPECT_EQ(item_types(s.encode_frame(frame(1, 1))),
            (std::vector<std::uint32_t>{100004, 2, 5, 9}));  // only Body2's items
}

TEST(ViconServerSession, MalformedClientPacketIsAnError) {
  ServerSession s;
  PacketBuilder b;
  b.add_raw(100002, {});  // RequestFrame without its bool
  EXPECT_FALSE(s.on_client_packet(body_of(b.finish()), nullptr).ok());
  EXPECT_FALSE(s.on_client_packet(hex("a2 86 01 00 05 00 00 00 01"), nullptr).ok());
  // Unknown types, KeepAlive and ApexHaptics are ignored.
  PacketBuilder c;
  c.add_raw(12345, hex("01 02 03")).add(KeepAlive{}).add_raw(35, hex("00 00 00 00"));
  auto r = s.on_client_packet(body_of(c.finish()), nullptr);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.value().empty());
}

TEST(ViconServedFrame, BuilderKeepsIdsAndServesMissingBodiesOccluded) {
  ServedFrameBuilder builder;
  core::MocapFrame m;
  m.frame_number = 7;
  core::BodySample a;
  a.name = "Body1";
  a.tracked = true;
  a.p_world_m = {1.0, -2.0, 0.5};
  a.q_world_body = Eigen::Quaterniond(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
  core::BodySample b = a;
  b.name = "Body2";
  m.bodies = {a, b};
  m.source_latency = std::chrono::milliseconds(3);
  const ServedFrame f1 = builder.build(m, frame_period_ticks(100.0));
  EXPECT_EQ(f1.frame_period_ticks, 1'350'000);
  ASSERT_EQ(f1.subjects.size(), 2u);
  EXPECT_EQ(f1.subjects[0].subject_id, 1u);
  EXPECT_EQ(f1.subjects[1].subject_id, 2u);
  EXPECT_EQ(f1.subjects[0].translation_mm, (std::array<double, 3>{1000.0, -2000.0, 500.0}));
  const std::array<double, 9> rz90{0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(f1.subjects[0].rotation[i], rz90[i], 1e-15);
  ASSERT_EQ(f1.latency.size(), 1u);
  EXPECT_DOUBLE_EQ(f1.latency[0].seconds, 0.003);
  m.bodies = {b};
  m.frame_number = 0xFFFFFFFF;
  const ServedFrame f2 = builder.build(m, 1);
  ASSERT_EQ(f2.subjects.size(), 2u);
  EXPECT_FALSE(f2.subjects[0].tracked);
  EXPECT_TRUE(f2.subjects[1].tracked);
  EXPECT_EQ(f2.frame_id, 0u);  // never the reserved id
  EXPECT_GT(f2.sequence, f1.sequence);
}

}  // namespace
}  // namespace mocaplink::wire::vicon
