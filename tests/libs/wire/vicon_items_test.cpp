// Golden byte tests of the DataStream items, from the worked examples and layouts of
// /work/shared/protocols/vicon-datastream.md (§8, §11). The expected bytes are transcribed by hand
// from the spec (captured from / replayed to the real SDK), never produced by our encoder.
#include <gtest/gtest.h>

#include "mocaplink/wire/vicon_items.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vicon {
namespace {

using test::body_of;
using test::hex;

// §11 example 1, H: the server's greeting offering 1, 2, 5, 9, 100004.
const char* const kGreeting =
    "01 00 2b 1a 20 00 00 00 a1 86 01 00 18 00 00 00 05 00 00 00 01 00 00 00 02 00 00 00"
    "05 00 00 00 09 00 00 00 a4 86 01 00";

template <Item T>
std::vector<std::byte> packet_of(const T& item) {
  PacketBuilder b;
  b.add(item);
  return b.finish();
}

template <Item T>
T parse_single(const std::vector<std::byte>& packet) {
  auto len = parse_packet_header(packet);
  EXPECT_TRUE(len.ok());
  const auto body = body_of(packet);
  auto items = split_items(body);
  EXPECT_TRUE(items.ok());
  EXPECT_EQ(items.value().size(), 1u);
  EXPECT_EQ(items.value()[0].type, to_u32(T::kType));
  auto parsed = parse_item<T>(items.value()[0].payload);
  EXPECT_TRUE(parsed.ok()) << (parsed.ok() ? "" : parsed.error().reason);
  return parsed.value();
}

TEST(ViconItems, GreetingObjectEnumsBothWays) {
  const auto bytes = hex(kGreeting);
  const auto parsed = parse_single<ObjectEnums>(bytes);
  EXPECT_EQ(parsed.types, (std::vector<std::uint32_t>{1, 2, 5, 9, 100004}));
  EXPECT_EQ(packet_of(ObjectEnums{{1, 2, 5, 9, 100004}}), bytes);
}

TEST(ViconItems, ClientPacketsCapturedFromTheSdk) {
  // §11 example 1: ObjectEnums {1, 2, 5, 100004}; RequestFrame(1); RequestNextFrame(1); Ping 1;
  // StopMulticastSender (empty item, same shape as KeepAlive).
  EXPECT_EQ(packet_of(ObjectEnums{{1, 2, 5, 100004}}),
            hex("01 00 2b 1a 1c 00 00 00 a1 86 01 00 14 00 00 00 04 00 00 00 01 00 00 00"
                "02 00 00 00 05 00 00 00 a4 86 01 00"));
  EXPECT_EQ(packet_of(RequestFrame{true}),
            hex("01 00 2b 1a 09 00 00 00 a2 86 01 00 01 00 00 00 01"));
  EXPECT_EQ(packet_of(RequestNextFrame{1}),
            hex("01 00 2b 1a 0c 00 00 00 a8 86 01 00 04 00 00 00 01 00 00 00"));
  EXPECT_EQ(packet_of(Ping{1}), hex("01 00 2b 1a 10 00 00 00 2a 00 00 00 08 00 00 00"
                                    "01 00 00 00 00 00 00 00"));
  // KeepAlive: type 100003 = a3 86 01 00, empty payload.
  EXPECT_EQ(packet_of(KeepAlive{}), hex("01 00 2b 1a 08 00 00 00 a3 86 01 00 00 00 00 00"));
  EXPECT_EQ(parse_single<RequestFrame>(hex("01 00 2b 1a 09 00 00 00 a2 86 01 00 01 00 00 00 00"))
                .streaming,
            false);
  EXPECT_EQ(parse_single<Ping>(hex("01 00 2b 1a 10 00 00 00 2a 00 00 00 08 00 00 00"
                                   "3b 00 00 00 00 00 00 00"))
                .ping_id,
            59u);
}

TEST(ViconItems, FilterAndPingInOnePacket) {
  // §11 example 1: Filter {8:{2}, 9:{2}, 40:{2}, 901:{2}} followed by Ping id 1.
  const auto bytes =
      hex("01 00 2b 1a 4c 00 00 00 a7 86 01 00 34 00 00 00 04 00 00 00 08 00 00 00 01 00 00 00"
          "02 00 00 00 09 00 00 00 01 00 00 00 02 00 00 00 28 00 00 00 01 00 00 00 02 00 00 00"
          "85 03 00 00 01 00 00 00 02 00 00 00 2a 00 00 00 08 00 00 00 01 00 00 00 00 00 00 00");
  const auto body = body_of(bytes);
  auto items = split_items(body);
  ASSERT_TRUE(items.ok());
  ASSERT_EQ(items.value().size(), 2u);
  auto filter = parse_item<Filter>(items.value()[0].payload);
  ASSERT_TRUE(filter.ok());
  using Entry = std::pair<std::uint32_t, std::vector<std::uint32_t>>;
  EXPECT_EQ(filter.value().filter, (std::vector<Entry>{{8, {2}}, {9, {2}}, {40, {2}}, {901, {2}}}));
  auto ping = parse_item<Ping>(items.value()[1].payload);
  ASSERT_TRUE(ping.ok());
  EXPECT_EQ(ping.value().ping_id, 1u);
  PacketBuilder b;
  b.add(filter.value()).add(Ping{1});
  EXPECT_EQ(b.finish(), bytes);
}

TEST(ViconItems, StreamInfoAndFrameInfo) {
  // §8.9: 100 Hz → 1 350 000 ticks = 0x149970; §11 example 2 bytes.
  EXPECT_EQ(packet_of(StreamInfo{1'350'000}),
            hex("01 00 2b 1a 10 00 00 00 01 00 00 00 08 00 00 00 70 99 14 00 00 00 00 00"));
  EXPECT_EQ(packet_of(FrameInfo{41}),
            hex("01 00 2b 1a 0c 00 00 00 05 00 00 00 04 00 00 00 29 00 00 00"));
}

TEST(ViconItems, TimecodeLayout) {
  // §8.17, built by hand: 10:20:30:12, subframes 1 of 2, NTSC (1), user bits 0xAABBCCDD, field 1.
  const auto bytes =
      hex("01 00 2b 1a 19 00 00 00 17 00 00 00 11 00 00 00 0a 14 1e 0c 01 00 02 00 01 00 00 00"
          "dd cc bb aa 01");
  const Timecode tc = parse_single<Timecode>(bytes);
  EXPECT_EQ(tc.hours, 10);
  EXPECT_EQ(tc.minutes, 20);
  EXPECT_EQ(tc.seconds, 30);
  EXPECT_EQ(tc.frames, 12);
  EXPECT_EQ(tc.subframes, 1);
  EXPECT_EQ(tc.subframes_per_frame, 2);
  EXPECT_EQ(tc.standard, 1u);
  EXPECT_EQ(tc.user_bits, 0xAABBCCDDu);
  EXPECT_EQ(tc.field_flag, 1);
  EXPECT_EQ(packet_of(tc), bytes);
}

TEST(ViconItems, LatencyInfoLayout) {
  // §8.18, by hand: 2 samples: "A" 0.5 s (3fe0…), "BC" 0.25 s (3fd0…).
  const auto bytes =
      hex("01 00 2b 1a 27 00 00 00 1a 00 00 00 1f 00 00 00 02 00 00 00"
          "01 00 00 00 41 00 00 00 00 00 00 e0 3f"
          "02 00 00 00 42 43 00 00 00 00 00 00 d0 3f");
  const LatencyInfo info = parse_single<LatencyInfo>(bytes);
  ASSERT_EQ(info.samples.size(), 2u);
  EXPECT_EQ(info.samples[0].name, "A");
  EXPECT_EQ(info.samples[0].seconds, 0.5);
  EXPECT_EQ(info.samples[1].name, "BC");
  EXPECT_EQ(info.samples[1].seconds, 0.25);
  EXPECT_EQ(packet_of(info), bytes);
}

TEST(ViconItems, FrameRateInfoAndApplicationInfoLayout) {
  // §8.19: map<string, f64> {"R": 100.0 (0x4059000000000000)}; §8.10: u8 1 = Y-up.
  const auto rates =
      hex("01 00 2b 1a 19 00 00 00 27 00 00 00 11 00 00 00 01 00 00 00 01 00 00 00 52"
          "00 00 00 00 00 00 59 40");
  const FrameRateInfo info = parse_single<FrameRateInfo>(rates);
  ASSERT_EQ(info.rates_hz.size(), 1u);
  EXPECT_EQ(info.rates_hz[0].first, "R");
  EXPECT_EQ(info.rates_hz[0].second, 100.0);
  EXPECT_EQ(packet_of(info), rates);
  const auto app = hex("01 00 2b 1a 09 00 00 00 25 00 00 00 01 00 00 00 01");
  EXPECT_EQ(parse_single<ApplicationInfo>(app).axis_orientation, 1);
  EXPECT_EQ(packet_of(ApplicationInfo{1}), app);
}

TEST(ViconItems, ObjectQualityLayout) {
  // §8.14: subject 3, quality 1.0 (0x3ff0000000000000).
  const auto bytes =
      hex("01 00 2b 1a 14 00 00 00 28 00 00 00 0c 00 00 00 03 00 00 00 00 00 00 00 00 00 f0 3f");
  const ObjectQuality q = parse_single<ObjectQuality>(bytes);
  EXPECT_EQ(q.subject_id, 3u);
  EXPECT_EQ(q.quality, 1.0);
  EXPECT_EQ(packet_of(q), bytes);
}

TEST(ViconItems, TrailingBytesInAnItemAreIgnored) {
  // §3: the reader jumps to the end of the item after parsing its fields.
  const auto payload = hex("29 00 00 00 ff ee");
  auto parsed = parse_item<FrameInfo>(payload);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed.value().frame_id, 41u);
}

TEST(ViconItems, TruncatedPayloadIsAnErrorWithOffset) {
  const auto payload = hex("70 99 14 00 00 00 00");  // StreamInfo needs 8 bytes
  auto parsed = parse_item<StreamInfo>(payload, 16);
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().offset, 16u);
  EXPECT_NE(parsed.error().reason.find("StreamInfo"), std::string::npos);
}

TEST(ViconItems, AbsurdCountsAreRejectedBeforeAllocating) {
  // SubjectInfo: id 1, name length 0xFFFFFFF0 with 2 bytes behind it.
  const auto name = hex("01 00 00 00 f0 ff ff ff 41 42");
  auto a = parse_item<SubjectInfo>(name);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().reason.find("exceeds"), std::string::npos);
  // GlobalSegments: subject 1, 0x7FFFFFFF segments, none present.
  const auto segs = hex("01 00 00 00 ff ff ff 7f");
  auto b = parse_item<GlobalSegments>(segs);
  ASSERT_FALSE(b.ok());
  // A plausible count (2) with only one 100-byte pose behind it: truncated.
  std::vector<std::byte> two = hex("01 00 00 00 02 00 00 00");
  two.resize(two.size() + 100 + 50);
  auto c = parse_item<GlobalSegments>(two);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().reason.find("truncated"), std::string::npos);
}

TEST(ViconPacket, HeaderChecks) {
  EXPECT_EQ(parse_packet_header(hex("01 00 2b 1a 0a 01 00 00")).value(), 266u);
  EXPECT_FALSE(parse_packet_header(hex("01 00 2b 1b 00 00 00 00")).ok());  // bad tag
  EXPECT_FALSE(parse_packet_header(hex("01 00 2b 1a 00")).ok());           // short
  auto big = parse_packet_header(hex("01 00 2b 1a ff ff ff ff"));          // 4 GiB body
  ASSERT_FALSE(big.ok());
  EXPECT_NE(big.error().reason.find("exceeds the cap"), std::string::npos);
  EXPECT_TRUE(parse_packet_header(hex("01 00 2b 1a 00 01 00 00"), 256).ok());
  EXPECT_FALSE(parse_packet_header(hex("01 00 2b 1a 01 01 00 00"), 256).ok());
}

TEST(ViconPacket, SplitItemsRejectsOverlongPayloadAndSkipsNothing) {
  // Unknown type 12345 (0x3039) with 2 bytes, then a KeepAlive: both split out.
  const auto ok = hex("39 30 00 00 02 00 00 00 aa bb a3 86 01 00 00 00 00 00");
  auto items = split_items(ok);
  ASSERT_TRUE(items.ok());
  ASSERT_EQ(items.value().size(), 2u);
  EXPECT_EQ(items.value()[0].type, 12345u);
  EXPECT_EQ(items.value()[0].payload.size(), 2u);
  EXPECT_EQ(items.value()[0].offset, 16u);
  EXPECT_EQ(items.value()[1].type, 100003u);
  const auto overlong = hex("05 00 00 00 ff ff ff 00 29 00 00 00");
  auto bad = split_items(overlong);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().offset, 12u);
  EXPECT_FALSE(split_items(hex("05 00 00 00 04 00")).ok());  // truncated item header
  EXPECT_TRUE(split_items({}).ok());
}

}  // namespace
}  // namespace mocaplink::wire::vicon
