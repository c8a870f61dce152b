// VRPN codec against the worked hex examples of /work/shared/protocols/vrpn.md §9 (built from the
// document, not from our encoder), plus the refusals of §3 and §8.
#include <cmath>

#include <gtest/gtest.h>

#include "mocaplink/wire/vrpn_protocol.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::vrpn {
namespace {

using vicon::test::hex;

constexpr const char* kCookieHex = "7672706e3a207665722e2030372e33382020300000000000";
constexpr const char* kSenderHex =
    "000000236553f1000003d09000000000ffffffff000000000000000744726f6e6531000000000000";
constexpr const char* kTypeHex =
    "000000326553f1000003d09000000003fffffffe00000001000000167672706e5f547261636b657220506f735f"
    "5175617400000000000000";
constexpr const char* kPosQuatHex =
    "000000586553f1000007a12000000000000000030000000200000000000000003ff0000000000000bfe0000000"
    "0000003fd0000000000000000000000000000000000000000000003fe6a09e667f3bcd3fe6a09e667f3bcd";

std::span<const std::byte> payload_of(const std::vector<std::byte>& message, const Header& h) {
  return std::span<const std::byte>(message).subspan(kHeaderBytes, h.payload_bytes());
}

TEST(VrpnCookie, MatchesTheDocumentAndParses) {
  const auto ours = make_cookie('0');
  EXPECT_EQ(std::vector<std::byte>(ours.begin(), ours.end()), hex(kCookieHex));
  auto parsed = parse_cookie(hex(kCookieHex));
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed.value().magic, "vrpn: ver. 07.38");
  EXPECT_EQ(parsed.value().log_mode, '0');
}

TEST(VrpnCookie, OtherMinorAcceptedOtherMajorAndBadLogModeRefused) {
  auto minor = hex(kCookieHex);
  minor[15] = std::byte{'5'};  // 07.35, a distribution package
  EXPECT_TRUE(parse_cookie(minor));
  auto major = hex(kCookieHex);
  major[12] = std::byte{'6'};  // 06.38
  EXPECT_FALSE(parse_cookie(major));
  auto mode = hex(kCookieHex);
  mode[18] = std::byte{'4'};
  EXPECT_FALSE(parse_cookie(mode));
  const auto cookie = hex(kCookieHex);
  EXPECT_FALSE(parse_cookie(std::span(cookie).first(23)));
}

TEST(VrpnMessage, SenderDescriptionVector) {
  const auto bytes = hex(kSenderHex);
  ASSERT_EQ(bytes.size(), 40u);
  auto h = parse_header(std::span(bytes).first(kHeaderBytes));
  ASSERT_TRUE(h);
  EXPECT_EQ(h.value().length, 35u);
  EXPECT_EQ(h.value().padded_payload_bytes(), 16u);
  EXPECT_EQ(h.value().time, (Timeval{1'700'000'000u, 250'000u}));
  EXPECT_EQ(h.value().sender, 0);
  EXPECT_EQ(h.value().type, kSenderDescription);
  auto name = parse_description(payload_of(bytes, h.value()));
  ASSERT_TRUE(name) << name.error().reason;
  EXPECT_EQ(name.value(), "Drone1");
  EXPECT_EQ(encode_description({1'700'000'000u, 250'000u}, kSenderDescription, 0, "Drone1"), bytes);
}

TEST(VrpnMessage, TypeDescriptionVector) {
  const auto bytes = hex(kTypeHex);
  ASSERT_EQ(bytes.size(), 56u);
  auto h = parse_header(std::span(bytes).first(kHeaderBytes));
  ASSERT_TRUE(h);
  EXPECT_EQ(h.value().sender, 3);
  EXPECT_EQ(h.value().type, kTypeDescription);
  auto name = parse_description(payload_of(bytes, h.value()));
  ASSERT_TRUE(name);
  EXPECT_EQ(name.value(), kPosQuatType);
  EXPECT_EQ(encode_description({1'700'000'000u, 250'000u}, kTypeDescription, 3, kPosQuatType, 1),
            bytes);
}

TEST(VrpnMessage, PosQuatVector) {
  const auto bytes = hex(kPosQuatHex);
  ASSERT_EQ(bytes.size(), 88u);
  auto h = parse_header(std::span(bytes).first(kHeaderBytes));
  ASSERT_TRUE(h);
  EXPECT_EQ(h.value().time, (Timeval{1'700'000'000u, 500'000u}));
  EXPECT_EQ(h.value().sender, 0);
  EXPECT_EQ(h.value().type, 3);
  auto pose = parse_pos_quat(payload_of(bytes, h.value()));
  ASSERT_TRUE(pose) << pose.error().reason;
  EXPECT_EQ(pose.value().sensor, 0);
  EXPECT_EQ(pose.value().p_m, Eigen::Vector3d(1.0, -0.5, 0.25));
  const auto& q = pose.value().q_world_sensor;
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.x(), 0.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.0, 1e-12);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-12);
  // 90° about z: body x → world y.
  EXPECT_TRUE((q * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(VrpnMessage, HeaderRefusals) {
  auto bytes = hex(kPosQuatHex);
  bytes[3] = std::byte{23};  // length 23 < 24
  EXPECT_FALSE(parse_header(std::span(bytes).first(kHeaderBytes)));
  bytes[3] = std::byte{0};
  bytes[1] = std::byte{0x10};  // 1 MiB payload, above the cap
  EXPECT_FALSE(parse_header(std::span(bytes).first(kHeaderBytes)));
  EXPECT_FALSE(parse_header(std::span(bytes).first(20)));
  auto usec = hex(kPosQuatHex);
  usec[8] = std::byte{0x7f};  // microseconds way above 999999
  EXPECT_FALSE(parse_header(std::span(usec).first(kHeaderBytes)));
}

TEST(VrpnMessage, DescriptionRefusals) {
  const auto good = hex("000000074472 6f6e653100");
  EXPECT_TRUE(parse_description(good));
  EXPECT_FALSE(parse_description(hex("0000000844726f6e653100")));    // L says 8, 7 follow
  EXPECT_FALSE(parse_description(hex("0000000744726f6e65310000")));  // an extra byte
  EXPECT_FALSE(parse_description(hex("0000000744726f00653100")));    // NUL inside the name
  EXPECT_FALSE(parse_description(hex("0000000744726f6e653141")));    // no NUL at the end
  EXPECT_FALSE(parse_description(hex("0000000744720a6e653100")));    // control character
  EXPECT_FALSE(parse_description(hex("0000000100")));                // empty name
  EXPECT_FALSE(parse_description(hex("000000")));                    // no length
  std::vector<std::byte> long_name = hex("00000065");                // L = 101 > 100
  long_name.resize(4 + 101, std::byte{'a'});
  long_name.back() = std::byte{0};
  EXPECT_FALSE(parse_description(long_name));
}

TEST(VrpnMessage, PosQuatRefusals) {
  const auto bytes = hex(kPosQuatHex);
  const auto payload = std::vector<std::byte>(bytes.begin() + 24, bytes.end());
  EXPECT_FALSE(parse_pos_quat(std::span(payload).first(63)));  // too short
  auto nan = payload;
  nan[8] = std::byte{0x7f};
  nan[9] = std::byte{0xf8};  // x = NaN
  EXPECT_FALSE(parse_pos_quat(nan));
  auto zero_q = payload;
  std::fill(zero_q.begin() + 32, zero_q.end(), std::byte{0});
  EXPECT_FALSE(parse_pos_quat(zero_q));  // |q| = 0
  auto negative = payload;
  negative[0] = std::byte{0xff};
  EXPECT_FALSE(parse_pos_quat(negative));
  auto longer = payload;
  longer.resize(72, std::byte{0});  // extra bytes are ignored
  EXPECT_TRUE(parse_pos_quat(longer));
}

TEST(VrpnMessage, EncodedPosQuatRoundTripsAndPads) {
  PosQuat r{2, Eigen::Vector3d(0.1, 0.2, 0.3),
            Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()))};
  const auto message = encode_message({5, 6}, 7, 8, encode_pos_quat(r), 9);
  EXPECT_EQ(message.size(), 88u);
  auto h = parse_header(std::span(message).first(kHeaderBytes));
  ASSERT_TRUE(h);
  auto back = parse_pos_quat(payload_of(message, h.value()));
  ASSERT_TRUE(back);
  EXPECT_EQ(back.value().sensor, 2);
  EXPECT_TRUE(back.value().p_m.isApprox(r.p_m));
  EXPECT_TRUE(back.value().q_world_sensor.isApprox(r.q_world_sensor));
  // A 5-byte payload is padded to 8; length excludes the padding.
  const std::array<std::byte, 5> five{};
  const auto padded = encode_message({}, 0, 0, five);
  EXPECT_EQ(padded.size(), 32u);
  EXPECT_EQ(padded[3], std::byte{29});
}

}  // namespace
}  // namespace mocaplink::wire::vrpn
