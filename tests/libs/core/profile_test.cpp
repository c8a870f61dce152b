// Profiles → message sets (DESIGN.md table, autopilots.md §12) and the name spellings.
#include "mocaplink/core/profile.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

TEST(ProfileNames, RoundTripAndRejectOthers) {
  for (Profile p : {Profile::px4, Profile::ardupilot, Profile::px4_gps, Profile::ardupilot_gps,
                    Profile::classic, Profile::custom}) {
    EXPECT_EQ(parse_profile(to_string(p)), p);
  }
  EXPECT_EQ(to_string(Profile::px4_gps), "px4-gps");
  EXPECT_EQ(to_string(Profile::ardupilot_gps), "ardupilot-gps");
  EXPECT_FALSE(parse_profile("PX4"));
  EXPECT_FALSE(parse_profile("px4_gps"));
  EXPECT_FALSE(parse_profile(""));
  for (const char* name : {"odometry", "vision_position_estimate", "vision_speed_estimate",
                           "att_pos_mocap", "hil_gps", "gps_input", "local_position_ned"}) {
    const auto kind = parse_message_kind(name);
    ASSERT_TRUE(kind) << name;
    EXPECT_EQ(to_string(*kind), name);
  }
  EXPECT_FALSE(parse_message_kind("ODOMETRY"));
}

TEST(ProfileSets, DesignTable) {
  EXPECT_EQ(messages_for(Profile::px4), MessageSet{MessageKind::odometry});
  EXPECT_EQ(messages_for(Profile::ardupilot), MessageSet{MessageKind::odometry});
  EXPECT_EQ(messages_for(Profile::px4_gps), MessageSet{MessageKind::hil_gps});
  EXPECT_EQ(messages_for(Profile::ardupilot_gps), MessageSet{MessageKind::gps_input});
  EXPECT_EQ(to_string(messages_for(Profile::classic)), "att_pos_mocap,hil_gps,local_position_ned");
  const std::vector<MessageKind> custom{MessageKind::vision_speed_estimate,
                                        MessageKind::vision_position_estimate,
                                        MessageKind::vision_speed_estimate};
  const MessageSet set = messages_for(Profile::custom, custom);
  EXPECT_EQ(set.size(), 2U);
  EXPECT_EQ(to_string(set), "vision_position_estimate,vision_speed_estimate");
  EXPECT_TRUE(messages_for(Profile::px4, custom) == MessageSet{MessageKind::odometry});
}

TEST(ProfileSets, OriginAndGpsClassification) {
  EXPECT_TRUE(sends_origin(Profile::px4, messages_for(Profile::px4)));
  EXPECT_TRUE(sends_origin(Profile::ardupilot, messages_for(Profile::ardupilot)));
  EXPECT_FALSE(sends_origin(Profile::px4_gps, messages_for(Profile::px4_gps)));
  EXPECT_FALSE(sends_origin(Profile::ardupilot_gps, messages_for(Profile::ardupilot_gps)));
  EXPECT_FALSE(sends_origin(Profile::classic, messages_for(Profile::classic)));
  EXPECT_TRUE(sends_origin(Profile::custom, MessageSet{MessageKind::att_pos_mocap}));
  EXPECT_FALSE(sends_origin(Profile::custom, MessageSet{MessageKind::local_position_ned}));
  EXPECT_TRUE(messages_for(Profile::classic).needs_origin());
  EXPECT_FALSE(messages_for(Profile::px4).needs_origin());
  EXPECT_TRUE(is_gps(MessageKind::hil_gps));
  EXPECT_TRUE(is_gps(MessageKind::gps_input));
  EXPECT_FALSE(is_gps(MessageKind::odometry));
  MessageSet s;
  EXPECT_TRUE(s.empty());
  s.insert(MessageKind::hil_gps);
  s.erase(MessageKind::hil_gps);
  EXPECT_TRUE(s.empty());
  EXPECT_EQ(to_string(s), "");
}

TEST(MessageTable, FrameSizesFollowTheMavlinkLengths) {
  // common.xml payload lengths with every extension field, + 10 header + 2 CRC (+ 13 signature).
  EXPECT_EQ(max_frame_bytes(MessageKind::odometry), 10U + 233U + 2U);
  EXPECT_EQ(max_frame_bytes(MessageKind::odometry, true), 10U + 233U + 2U + 13U);
  EXPECT_EQ(max_frame_bytes(MessageKind::hil_gps), 10U + 39U + 2U);
  EXPECT_EQ(max_frame_bytes(MessageKind::local_position_ned), 10U + 28U + 2U);
  // classic at 10 Hz: (HIL_GPS 51 + LOCAL_POSITION_NED 40 + ATT_POS_MOCAP 132) × 10, plus
  // HEARTBEAT 21, TIMESYNC 30 twice and SET_GPS_GLOBAL_ORIGIN 33 at 1 Hz, plus the vehicle's
  // ATTITUDE 40 and LOCAL_POSITION_NED 40 at 5 Hz (the agreement check's request) and
  // ESTIMATOR_STATUS 54 (the larger of it and EKF_STATUS_REPORT 38) at 1 Hz (the set-up list's).
  EXPECT_DOUBLE_EQ(
      link_bytes_per_second(Profile::classic, messages_for(Profile::classic), 10.0, false),
      (51.0 + 40.0 + 132.0) * 10.0 + 21.0 + 30.0 + 30.0 + 33.0 + (40.0 + 40.0) * 5.0 + 75.0 * 2.0 +
          54.0);
  // Signed: every frame 13 bytes longer, the vehicle's too.
  EXPECT_DOUBLE_EQ(
      link_bytes_per_second(Profile::classic, messages_for(Profile::classic), 10.0, true) -
          link_bytes_per_second(Profile::classic, messages_for(Profile::classic), 10.0, false),
      13.0 * (3 * 10 + 4 + 2 * 5 + 2 + 1));
  EXPECT_FALSE(serial_bandwidth_warning(Profile::classic, messages_for(Profile::classic), 10.0,
                                        false, 57600));
  EXPECT_EQ(serial_bandwidth_warning(Profile::px4, messages_for(Profile::px4), 100.0, false, 9600),
            "profile px4 at 100 Hz needs up to 25218 bytes/s (with the vehicle's ATTITUDE and "
            "LOCAL_POSITION_NED at 5 Hz, its HIGHRES_IMU at 2 Hz and its estimator status at 1 "
            "Hz) but 9600 baud carries 960: frames will be dropped; lower rate_hz or raise the "
            "baud rate");
}

TEST(MessageTable, NamesListEveryKindInEnumOrder) {
  ASSERT_EQ(message_kinds().size(), message_kind_names().size());
  for (std::size_t i = 0; i < message_kinds().size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(message_kinds()[i]), i);
    EXPECT_EQ(to_string(message_kinds()[i]), message_kind_names()[i]);
  }
  EXPECT_EQ(profile_names().size(), 7U);
  EXPECT_TRUE(is_vision(MessageKind::att_pos_mocap));
  EXPECT_FALSE(is_vision(MessageKind::local_position_ned));
  EXPECT_FALSE(is_vision(MessageKind::hil_gps));
}

}  // namespace
}  // namespace mocaplink::core
