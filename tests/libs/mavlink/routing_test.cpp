// message_target at the edges the node-mavlink oracle (tests/conformance/mavlink/
// node_mavlink_routing.cjs) does not reach: target bytes removed by MAVLink 2 truncation, MAVLink 1
// frames (no extension fields), payloads shorter or longer than the definition, ids not addressed.
// Frames come from our encoder, whose layout the golden vectors pin (golden_test.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/routing.hpp"

namespace mocaplink::mavlink {
namespace {

constexpr FrameHeader kHeader{.seq = 3, .sysid = 255, .compid = 190};

FrameView parsed(const Frame& frame) {
  const auto r = parse_frame(frame.bytes());
  EXPECT_TRUE(r.ok());
  return *r;
}

TEST(MessageTarget, CommandLongReadsItsTargetFields) {
  CommandLong cmd;
  cmd.command = 400;
  cmd.target_system = 7;
  cmd.target_component = 1;
  const FrameView v2 = parsed(encode(cmd, kHeader));
  EXPECT_EQ(message_target(v2), (Target{.system = 7, .component = 1}));
  // Base fields: MAVLink 1 carries them.
  const FrameView v1 = parsed(encode_v1(cmd, kHeader));
  ASSERT_EQ(v1.version, 1);
  EXPECT_EQ(message_target(v1), (Target{.system = 7, .component = 1}));
}

TEST(MessageTarget, CommandLongWhoseTargetBytesWereTruncatedReadsZero) {
  CommandLong cmd;
  cmd.param7 = 1.0F;
  cmd.command = 400;  // targets 0/0, confirmation 0: the last three bytes are truncated away
  const FrameView all = parsed(encode(cmd, kHeader));
  ASSERT_EQ(all.payload.size(), 30U);
  EXPECT_EQ(message_target(all), (Target{.system = 0, .component = 0}));

  cmd.target_system = 9;  // component and confirmation 0: only those two are truncated
  const FrameView component = parsed(encode(cmd, kHeader));
  ASSERT_EQ(component.payload.size(), 31U);
  EXPECT_EQ(message_target(component), (Target{.system = 9, .component = 0}));

  // All-zero payload: one byte kept (or none, as node-mavlink sends it).
  EXPECT_EQ(message_target(CommandLong::kId, std::array<std::uint8_t, 1>{}, 2), Target{});
  EXPECT_EQ(message_target(CommandLong::kId, {}, 2), Target{});
}

TEST(MessageTarget, CommandAckTargetsAreExtensionsAbsentFromMavlink1) {
  CommandAck ack;
  ack.command = 400;
  ack.result = 4;
  ack.target_system = 3;
  ack.target_component = 4;
  const FrameView v2 = parsed(encode(ack, kHeader));
  ASSERT_EQ(v2.payload.size(), 10U);
  EXPECT_EQ(message_target(v2), (Target{.system = 3, .component = 4}));

  const FrameView v1 = parsed(encode_v1(ack, kHeader));
  ASSERT_EQ(v1.version, 1);
  ASSERT_EQ(v1.payload.size(), 3U);
  EXPECT_EQ(message_target(v1), std::nullopt);
  // MAVLink 1 has no extension fields at all, whatever bytes follow the base fields.
  std::array<std::uint8_t, 10> full{};
  full[8] = 3;
  full[9] = 4;
  EXPECT_EQ(message_target(CommandAck::kId, full, 1), std::nullopt);
  EXPECT_EQ(message_target(CommandAck::kId, full, 2), (Target{.system = 3, .component = 4}));

  // A MAVLink 2 COMMAND_ACK without the extension bytes is addressed to everyone.
  ack.target_system = 0;
  ack.target_component = 0;
  const FrameView truncated = parsed(encode(ack, kHeader));
  ASSERT_EQ(truncated.payload.size(), 3U);
  EXPECT_EQ(message_target(truncated), Target{});
}

TEST(MessageTarget, TimesyncTargetsAreExtensions) {
  Timesync ts;
  ts.tc1 = 0;
  ts.ts1 = 123456789;
  ts.target_system = 1;
  ts.target_component = 197;
  EXPECT_EQ(message_target(parsed(encode(ts, kHeader))), (Target{.system = 1, .component = 197}));
  EXPECT_EQ(message_target(parsed(encode_v1(ts, kHeader))), std::nullopt);
}

TEST(MessageTarget, MessageWithoutTargetComponentReadsComponentZero) {
  SetGpsGlobalOrigin origin;
  origin.latitude = 473977418;
  origin.target_system = 42;
  origin.time_usec = 1;  // an extension after target_system: the next byte is not a component
  std::array<std::uint8_t, SetGpsGlobalOrigin::kMaxLength> payload{};
  origin.pack(payload);
  ASSERT_NE(payload[13], 0);
  EXPECT_EQ(message_target(SetGpsGlobalOrigin::kId, payload, 2),
            (Target{.system = 42, .component = 0}));
}

TEST(MessageTarget, OverLongPayloadIsReadAtTheDefinitionsOffsets) {
  // A newer definition may add extensions: the bytes after the known fields are ignored.
  std::vector<std::uint8_t> payload(40, 0xAA);
  payload[30] = 5;
  payload[31] = 6;
  EXPECT_EQ(message_target(CommandLong::kId, payload, 2), (Target{.system = 5, .component = 6}));
}

TEST(MessageTarget, MessagesWithoutTargetSystemAreNotAddressed) {
  const std::vector<std::uint8_t> payload(255, 0x11);
  for (const std::uint32_t msgid : {0U,            // HEARTBEAT
                                    32U,           // LOCAL_POSITION_NED
                                    69U,           // MANUAL_CONTROL ("target", not target_system)
                                    138U,          // ATT_POS_MOCAP
                                    232U,          // GPS_INPUT
                                    3U,            // no message
                                    0xFFFFFFU}) {  // largest 24-bit id, no message
    EXPECT_EQ(message_target(msgid, payload, 2), std::nullopt) << msgid;
    EXPECT_EQ(message_target(msgid, payload, 1), std::nullopt) << msgid;
  }
}

}  // namespace
}  // namespace mocaplink::mavlink
