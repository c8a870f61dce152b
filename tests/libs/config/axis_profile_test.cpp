// Axis, north and profile spellings (docs/config.md "[mocap]", "[[vehicle]]").
#include <gtest/gtest.h>

#include "mocaplink/config/axis.hpp"
#include "mocaplink/config/profile.hpp"

namespace mocaplink::config {
namespace {

TEST(Axis, RoundTripsEverySpelling) {
  for (const char* name : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
    const auto axis = parse_axis(name);
    ASSERT_TRUE(axis) << name;
    EXPECT_EQ(core::to_string(axis.value()), name);
  }
  EXPECT_EQ(parse_axis("-y").value(), (core::SignedAxis{1, -1}));
  EXPECT_EQ(parse_axis("+z").value(), (core::SignedAxis{2, 1}));
  EXPECT_TRUE(core::are_perpendicular(core::axis::pos_x, core::axis::neg_z));
  EXPECT_FALSE(core::are_perpendicular(core::axis::pos_x, core::axis::neg_x));
  EXPECT_EQ(parse_axis("x").error(), "expected one of +x, -x, +y, -y, +z, -z, got \"x\"");
  EXPECT_EQ(parse_axis("+X").error(), "expected one of +x, -x, +y, -y, +z, -z, got \"+X\"");
}

TEST(North, AxisOrAngle) {
  EXPECT_EQ(parse_north("-y").value(), core::North{core::axis::neg_y});
  EXPECT_EQ(parse_north("angle:37.5").value(), core::North{core::NorthAngle{37.5}});
  EXPECT_EQ(parse_north("angle:-360").value(), core::North{core::NorthAngle{-360.0}});
  EXPECT_EQ(core::to_string(core::North{core::NorthAngle{37.5}}), "angle:37.5");
  EXPECT_EQ(core::to_string(core::North{core::axis::pos_x}), "+x");
  EXPECT_EQ(parse_north("angle:400").error(),
            "angle must be a number of degrees from -360 to 360, as in \"angle:37.5\", got "
            "\"angle:400\"");
  EXPECT_EQ(parse_north("angle:inf").error(),
            "angle must be a number of degrees from -360 to 360, as in \"angle:37.5\", got "
            "\"angle:inf\"");
  EXPECT_EQ(parse_north("north").error(),
            "expected one of +x, -x, +y, -y, +z, -z or \"angle:DEG\", got \"north\"");
}

TEST(Profile, NamesAndOriginNeeds) {
  for (const char* name :
       {"px4", "ardupilot", "px4-gps", "ardupilot-gps", "classic", "custom", "auto"}) {
    const auto profile = parse_profile(name);
    ASSERT_TRUE(profile) << name;
    EXPECT_EQ(core::to_string(profile.value()), name);
  }
  EXPECT_EQ(parse_profile("px4_gps").error(),
            "unknown profile \"px4_gps\"; did you mean \"px4-gps\"? (one of: px4, ardupilot, "
            "px4-gps, ardupilot-gps, classic, custom, auto)");
  // Spellings are exact (lower case); the suggestion ignores case.
  EXPECT_EQ(parse_profile("PX4").error(),
            "unknown profile \"PX4\"; did you mean \"px4\"? (one of: px4, ardupilot, px4-gps, "
            "ardupilot-gps, classic, custom, auto)");
}

TEST(MessageKind, NamesAndOriginNeeds) {
  for (const char* name : {"odometry", "vision_position_estimate", "vision_speed_estimate",
                           "att_pos_mocap", "hil_gps", "gps_input", "local_position_ned"}) {
    const auto kind = parse_message_kind(name);
    ASSERT_TRUE(kind) << name;
    EXPECT_EQ(core::to_string(kind.value()), name);
  }
  EXPECT_TRUE(core::needs_origin(core::MessageKind::hil_gps));
  EXPECT_TRUE(core::needs_origin(core::MessageKind::gps_input));
  EXPECT_FALSE(core::needs_origin(core::MessageKind::odometry));
  EXPECT_EQ(parse_message_kind("HIL_GPS").error(),
            "unknown message \"HIL_GPS\"; did you mean \"hil_gps\"? (one of: odometry, "
            "vision_position_estimate, vision_speed_estimate, att_pos_mocap, hil_gps, gps_input, "
            "local_position_ned)");
}

}  // namespace
}  // namespace mocaplink::config
