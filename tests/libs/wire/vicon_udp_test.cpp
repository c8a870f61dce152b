// Vicon Tracker UDP datagrams (wire/vicon_udp*.hpp) against the worked example and the further
// vectors of /work/shared/protocols/vicon-tracker-udp.md §6, hand-built from its layout.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mocaplink/wire/vicon_udp.hpp"
#include "mocaplink/wire/vicon_udp_stream.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vicon_udp {
namespace {

using vicon::test::hex;

constexpr const char* kDrone1Hex =
    "d20400000100480044726f6e65310000000000000000000000000000000000000000000000408f400000000000"
    "407fc00000000000406f4000000000000000000000000000000000182d4454fb21f93f";

// Object item bytes (3 + 72) for `name` at (x, y, z) mm with angles (a, b, c).
std::vector<std::byte> object_item(std::string_view name, std::array<double, 6> v) {
  Object o;
  o.name = std::string(name);
  o.t_mm = {v[0], v[1], v[2]};
  o.rot_rad = {v[3], v[4], v[5]};
  auto d = encode_datagram(0, std::span(&o, 1));
  return {d.begin() + kHeaderBytes, d.end()};
}

std::vector<std::byte> datagram(std::uint32_t frame, std::uint8_t count,
                                std::initializer_list<std::vector<std::byte>> items) {
  std::vector<std::byte> out{static_cast<std::byte>(frame & 0xFF),
                             static_cast<std::byte>((frame >> 8) & 0xFF),
                             static_cast<std::byte>((frame >> 16) & 0xFF),
                             static_cast<std::byte>(frame >> 24), static_cast<std::byte>(count)};
  for (const auto& i : items) out.insert(out.end(), i.begin(), i.end());
  return out;
}

TEST(ViconUdp, WorkedExample) {
  const auto bytes = hex(kDrone1Hex);
  ASSERT_EQ(bytes.size(), 80u);
  auto d = parse_datagram(bytes);
  ASSERT_TRUE(d) << d.error().reason;
  EXPECT_EQ(d.value().frame, 1234u);
  ASSERT_EQ(d.value().objects.size(), 1u);
  const Object& o = d.value().objects[0];
  EXPECT_EQ(o.name, "Drone1");
  EXPECT_EQ(o.t_mm, Eigen::Vector3d(1000, -500, 250));
  EXPECT_EQ(o.rot_rad, Eigen::Vector3d(0, 0, std::numbers::pi / 2));
  const auto q = to_quaternion(o.rot_rad, EulerOrder::xyz);
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.x(), 0.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.0, 1e-12);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-12);
  // Our encoder writes the same bytes.
  EXPECT_EQ(encode_datagram(1234, d.value().objects), bytes);
}

TEST(ViconUdp, ZeroItemsAndTwoObjects) {
  auto empty = parse_datagram(hex("0100000000"));
  ASSERT_TRUE(empty);
  EXPECT_TRUE(empty.value().objects.empty());
  auto two = parse_datagram(datagram(
      7, 2, {object_item("A", {1, 2, 3, 0, 0, 0}), object_item("B", {4, 5, 6, 0.1, 0.2, 0.3})}));
  ASSERT_TRUE(two);
  ASSERT_EQ(two.value().objects.size(), 2u);
  EXPECT_EQ(two.value().objects[1].name, "B");
  EXPECT_EQ(two.value().objects[1].rot_rad, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(datagram(7, 2, {object_item("A", {}), object_item("B", {})}).size(), 5u + 2 * 75u);
}

TEST(ViconUdp, UnknownItemSkippedBySizeThenObject) {
  auto d = parse_datagram(
      datagram(9, 2, {hex("07 0500 0102030405"), object_item("Drone1", {1, 1, 1, 0, 0, 0})}));
  ASSERT_TRUE(d) << d.error().reason;
  EXPECT_EQ(d.value().unknown_items, 1u);
  ASSERT_EQ(d.value().objects.size(), 1u);
  EXPECT_EQ(d.value().objects[0].name, "Drone1");
}

TEST(ViconUdp, ObjectItemLongerThan72HasItsExtraSkipped) {
  auto item = object_item("A", {1, 2, 3, 0, 0, 0});
  item[1] = std::byte{74};
  item.push_back(std::byte{0xAA});
  item.push_back(std::byte{0xBB});
  auto d = parse_datagram(datagram(1, 1, {item}));
  ASSERT_TRUE(d) << d.error().reason;
  EXPECT_EQ(d.value().objects[0].t_mm, Eigen::Vector3d(1, 2, 3));
}

TEST(ViconUdp, Refusals) {
  EXPECT_FALSE(parse_datagram(hex("01000000")));  // < 5 bytes
  auto truncated = hex(kDrone1Hex);
  truncated.pop_back();
  EXPECT_FALSE(parse_datagram(truncated));  // item shorter than its size
  auto oversize = hex(kDrone1Hex);
  oversize[6] = std::byte{0x49};  // ItemDataSize 73 > what remains
  EXPECT_FALSE(parse_datagram(oversize));
  auto small = datagram(1, 1, {hex("00 0400 41424344")});  // object item of 4 bytes
  EXPECT_FALSE(parse_datagram(small));
  auto trailing = hex(kDrone1Hex);
  trailing.push_back(std::byte{1});
  EXPECT_FALSE(parse_datagram(trailing));  // a non-zero byte after the last item
  auto count = hex(kDrone1Hex);
  count[4] = std::byte{2};  // says two items, holds one
  EXPECT_FALSE(parse_datagram(count));
  auto header_cut = datagram(1, 1, {hex("0048")});
  EXPECT_FALSE(parse_datagram(header_cut));
  EXPECT_FALSE(parse_datagram(datagram(1, 1, {object_item("A\x01", {})})));  // control char
  EXPECT_FALSE(parse_datagram(datagram(1, 1, {object_item("", {})})));       // no name
  EXPECT_FALSE(parse_datagram(datagram(1, 1, {object_item("A", {NAN, 0, 0, 0, 0, 0})})));
  EXPECT_FALSE(parse_datagram(datagram(1, 1, {object_item("A", {0, 0, 0, 0, INFINITY, 0})})));
  EXPECT_FALSE(parse_datagram(datagram(1, 1, {object_item("A", {2e6, 0, 0, 0, 0, 0})}), 1e6));
}

// Tracker's blocks (its "Data Block Size"): the items, then zero bytes to 256, 512 or 1024.
std::vector<std::byte> padded(std::vector<std::byte> bytes, std::size_t block) {
  bytes.resize(block, std::byte{0});
  return bytes;
}

TEST(ViconUdp, WorkedExamplePaddedToEveryBlockSizeAndExact) {
  for (const std::size_t block : {80u, 256u, 512u, 1024u}) {
    SCOPED_TRACE(block);
    const auto bytes = padded(hex(kDrone1Hex), block);
    auto d = parse_datagram(bytes);
    ASSERT_TRUE(d) << d.error().reason;
    EXPECT_EQ(d.value().frame, 1234u);
    ASSERT_EQ(d.value().objects.size(), 1u);
    EXPECT_EQ(d.value().objects[0].name, "Drone1");
    EXPECT_EQ(d.value().objects[0].t_mm, Eigen::Vector3d(1000, -500, 250));
    EXPECT_EQ(d.value().objects[0].rot_rad, Eigen::Vector3d(0, 0, std::numbers::pi / 2));
    EXPECT_EQ(d.value().padding_bytes, block - 80u);
    // The encoder pads the same way (0: the exact 80 bytes).
    EXPECT_EQ(encode_datagram(1234, d.value().objects, block == 80u ? 0u : block), bytes);
  }
  // Zero items in a block: a frame without objects.
  auto empty = parse_datagram(padded(hex("0100000000"), 256));
  ASSERT_TRUE(empty);
  EXPECT_TRUE(empty.value().objects.empty());
  EXPECT_EQ(empty.value().padding_bytes, 251u);
}

TEST(ViconUdp, NonZeroTrailingBytesRefusedWithTheReason) {
  // Three objects (230 bytes) in a 1024-byte block, with one stray byte anywhere in the padding.
  const auto three =
      datagram(5, 3,
               {object_item("A", {1, 2, 3, 0, 0, 0}), object_item("B", {4, 5, 6, 0, 0, 0}),
                object_item("C", {7, 8, 9, 0, 0, 0})});
  ASSERT_EQ(three.size(), 230u);
  ASSERT_TRUE(parse_datagram(padded(three, 1024)));
  for (const std::size_t at : {230u, 500u, 1023u}) {
    SCOPED_TRACE(at);
    auto bytes = padded(three, 1024);
    bytes[at] = std::byte{0x41};
    auto d = parse_datagram(bytes);
    ASSERT_FALSE(d);
    EXPECT_EQ(d.error().offset, at);
    EXPECT_EQ(d.error().reason,
              "trailing non-zero bytes after 3 items (0x41 in a 1024-byte datagram)");
  }
  // A count that leaves an object out: the object is in the "padding", so the datagram is refused
  // rather than delivered without it.
  auto undercount = padded(three, 512);
  undercount[4] = std::byte{2};
  auto d = parse_datagram(undercount);
  ASSERT_FALSE(d);
  EXPECT_EQ(d.error().offset, 156u);  // C's id is 0; its size (72) is the first non-zero byte
  EXPECT_EQ(d.error().reason,
            "trailing non-zero bytes after 2 items (0x48 in a 512-byte datagram)");
}

TEST(ViconUdp, CountBeyondTheItemsReadsPaddingAsAnEmptyItemAndRefuses) {
  auto over = padded(hex(kDrone1Hex), 256);
  over[4] = std::byte{2};  // says two items: the second header is the padding's zeros
  auto d = parse_datagram(over);
  ASSERT_FALSE(d);
  EXPECT_EQ(d.error().reason, "object item of 0 bytes, expected 72");
}

TEST(ViconUdp, ObjectsPerBlock) {
  EXPECT_EQ(objects_per_block(256), 3u);
  EXPECT_EQ(objects_per_block(512), 6u);
  EXPECT_EQ(objects_per_block(1024), 13u);
  EXPECT_EQ(objects_per_block(80), 1u);
  EXPECT_EQ(objects_per_block(79), 0u);
  EXPECT_EQ(objects_per_block(0), 255u);
  EXPECT_EQ(objects_per_block(kMaxDatagramBytes), 255u);
  // 13 objects fill 980 of 1024 bytes.
  std::vector<Object> objects(13);
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i].name = "Body" + std::to_string(i + 1);
  const auto bytes = encode_datagram(1, objects, 1024);
  ASSERT_EQ(bytes.size(), 1024u);
  auto d = parse_datagram(bytes);
  ASSERT_TRUE(d) << d.error().reason;
  EXPECT_EQ(d.value().objects.size(), 13u);
  EXPECT_EQ(d.value().padding_bytes, 1024u - 980u);
}

TEST(ViconUdp, TwentyFourCharacterNameWithoutNul) {
  const std::string name = "ABCDEFGHIJKLMNOPQRSTUVWX";
  auto d = parse_datagram(datagram(1, 1, {object_item(name, {1, 0, 0, 0, 0, 0})}));
  ASSERT_TRUE(d);
  EXPECT_EQ(d.value().objects[0].name, name);
}

TEST(ViconUdp, AllZeroObject) {
  auto d = parse_datagram(datagram(1, 1, {object_item("A", {0, 0, 0, 0, 0, 0})}));
  ASSERT_TRUE(d);
  EXPECT_TRUE(d.value().objects[0].all_zero());
  Stream s;
  auto f = s.on_datagram(datagram(1, 1, {object_item("A", {0, 0, 0, 0, 0, 0})}), {});
  ASSERT_TRUE(f && f.value());
  EXPECT_FALSE(f.value()->bodies[0].tracked);
}

TEST(ViconUdp, EulerOrdersAreTheDocumentsAndInvert) {
  const Eigen::Vector3d a(0.3, -0.2, 1.1);
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d rz = Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(to_quaternion(a, EulerOrder::xyz).toRotationMatrix().isApprox(rx * ry * rz, 1e-12));
  EXPECT_TRUE(to_quaternion(a, EulerOrder::zyx).toRotationMatrix().isApprox(rz * ry * rx, 1e-12));
  // §3: under XYZ, RotY = asin(R[0][2]).
  EXPECT_NEAR(std::asin((rx * ry * rz)(0, 2)), a.y(), 1e-12);
  for (const auto order : {EulerOrder::xyz, EulerOrder::zyx}) {
    EXPECT_TRUE(to_euler(to_quaternion(a, order), order).isApprox(a, 1e-12));
    // Gimbal lock is well defined: finite angles that give the same rotation back.
    const Eigen::Vector3d lock(0.2, std::numbers::pi / 2, 0.4);
    const auto q = to_quaternion(lock, order);
    const auto back = to_euler(q, order);
    EXPECT_TRUE(back.allFinite());
    EXPECT_TRUE(to_quaternion(back, order).toRotationMatrix().isApprox(q.toRotationMatrix(), 1e-6));
  }
}

core::HostTime at_ms(std::int64_t ms) {
  return core::host_time_from_ns(ms * 1'000'000);
}

std::optional<core::MocapFrame> feed(Stream& s, std::uint32_t frame, double x, std::int64_t ms) {
  auto out = s.on_datagram(datagram(frame, 1, {object_item("A", {x, 0, 0, 0, 0, 0})}), at_ms(ms));
  EXPECT_TRUE(out);
  return out ? out.value() : std::nullopt;
}

TEST(ViconUdpStream, GapsStepLateAndWrap) {
  Stream s;
  auto f = feed(s, 0xFFFFFFFCu, 1, 0);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame_number, 0xFFFFFFFCu);
  EXPECT_DOUBLE_EQ(f->bodies[0].p_world_m.x(), 0.001);  // mm → m
  f = feed(s, 0xFFFFFFFEu, 2, 10);                      // step 2 (stream at half the camera rate)
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame_step, 2u);
  f = feed(s, 0x00000000u, 3, 20);  // wraps
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame_number, 0x100000000u);
  EXPECT_EQ(s.counters().wraps, 1u);
  f = feed(s, 0x00000004u, 4, 30);  // one frame (2 numbers) missing
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame_number, 0x100000004u);
  EXPECT_EQ(s.counters().gaps, 1u);
  EXPECT_FALSE(feed(s, 0x00000002u, 5, 40));  // late: dropped
  EXPECT_EQ(s.counters().late, 1u);
  f = feed(s, 0x00500000u, 6, 50);  // far back? no: far forward is a jump, numbered on
  ASSERT_TRUE(f);
  f = feed(s, 0x00000010u, 7, 60);  // far back: a Tracker restart
  ASSERT_TRUE(f);
  EXPECT_EQ(f->frame_number, 0x10u);
  EXPECT_EQ(s.counters().restarts, 1u);
}

TEST(ViconUdpStream, SplitFrameMergedAtTheFirstCaptureTime) {
  Stream s;
  auto first = s.on_datagram(datagram(5, 1, {object_item("A", {1, 0, 0, 0, 0, 0})}), at_ms(0));
  auto second = s.on_datagram(datagram(5, 1, {object_item("B", {2, 0, 0, 0, 0, 0})}), at_ms(1));
  ASSERT_TRUE(first && first.value() && second && second.value());
  const auto& f = *second.value();
  EXPECT_EQ(f.frame_number, 5u);
  EXPECT_EQ(f.capture_time, first.value()->capture_time);
  ASSERT_EQ(f.bodies.size(), 2u);
  EXPECT_EQ(s.counters().split_frames, 1u);
}

TEST(ViconUdpStream, FrozenObjectUntrackedAndSilenceLosesEveryBody) {
  StreamConfig c;
  c.frozen = 3;
  Stream s(c);
  for (std::uint32_t i = 1; i <= 6; ++i) {
    auto f = feed(s, i, 42.0, i);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->bodies[0].tracked, i <= 4) << i;  // 3 repeats allowed, the 4th is frozen
  }
  auto moved = feed(s, 7, 43.0, 7);
  ASSERT_TRUE(moved);
  EXPECT_TRUE(moved->bodies[0].tracked);
  auto lost = s.on_silence(at_ms(1000));
  ASSERT_TRUE(lost);
  ASSERT_EQ(lost->bodies.size(), 1u);
  EXPECT_FALSE(lost->bodies[0].tracked);
  EXPECT_GT(lost->capture_time, moved->capture_time);
  EXPECT_FALSE(s.on_silence(at_ms(2000)));
  // After the silence the same frame number again is not a split frame of the old one.
  EXPECT_FALSE(feed(s, 7, 43.0, 2001));
  auto resumed = feed(s, 8, 44.0, 2002);
  ASSERT_TRUE(resumed);
  EXPECT_TRUE(resumed->bodies[0].tracked);
}

TEST(ViconUdpStream, MalformedCounted) {
  Stream s;
  EXPECT_FALSE(s.on_datagram(hex("0102"), {}));
  EXPECT_EQ(s.counters().malformed, 1u);
}

TEST(ViconUdpStream, PaddedDatagramsAreFramesAndCounted) {
  Stream s;
  auto f = s.on_datagram(padded(hex(kDrone1Hex), 1024), {});
  ASSERT_TRUE(f && f.value());
  ASSERT_EQ(f.value()->bodies.size(), 1u);
  EXPECT_EQ(f.value()->bodies[0].name, "Drone1");
  EXPECT_TRUE(f.value()->bodies[0].tracked);
  EXPECT_EQ(s.counters().padded, 1u);
  auto bad = padded(hex(kDrone1Hex), 1024);
  bad[1000] = std::byte{0xFF};
  EXPECT_FALSE(s.on_datagram(bad, {}));
  EXPECT_EQ(s.counters().malformed, 1u);
  EXPECT_EQ(s.counters().padded, 1u);
}

}  // namespace
}  // namespace mocaplink::wire::vicon_udp
