// PX4's VehicleOdometry and VehicleStatus as DDS samples, against the offsets PX4's generated
// ucdr code uses (ros2-dds.md §4's table, px4_msgs' .msg field order), not against the encoder.
// The link that carries them over DDS: tests/adapters/ros2/px4_link_test.cpp.
#include "mocaplink/wire/px4_messages.hpp"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

namespace mocaplink::wire {
namespace {

template <typename T>
T at(const std::vector<std::uint8_t>& v, std::size_t payload_offset) {
  T out{};
  std::memcpy(&out, v.data() + 4 + payload_offset, sizeof(T));  // little-endian hosts only
  return out;
}

Px4VehicleOdometry sample_odometry() {
  Px4VehicleOdometry m;
  m.timestamp = 0x0102030405060708ULL;
  m.timestamp_sample = 1'700'000'000'123'456ULL;
  m.pose_frame = Px4VehicleOdometry::kFrameFrd;
  m.position = {1.5F, -2.25F, -0.75F};
  m.q = {0.5F, 0.5F, -0.5F, 0.5F};
  m.velocity_frame = Px4VehicleOdometry::kVelocityFrameBodyFrd;
  m.velocity = {0.1F, 0.2F, 0.3F};
  m.angular_velocity = {-0.1F, -0.2F, -0.3F};
  m.position_variance = {1e-6F, 2e-6F, 3e-6F};
  m.orientation_variance = {4e-4F, 5e-4F, 6e-4F};
  m.velocity_variance = {7e-3F, 8e-3F, 9e-3F};
  m.reset_counter = 7;
  m.quality = -1;
  return m;
}

TEST(Px4Messages, VehicleOdometryAtPx4sOffsets) {
  std::vector<std::uint8_t> out;
  encode_px4_vehicle_odometry(sample_odometry(), out);
  ASSERT_EQ(out.size(), 4U + 114U);
  EXPECT_EQ(out[0], 0x00);
  EXPECT_EQ(out[1], 0x01);  // CDR_LE: the Agent forwards bytes, PX4 reads them little endian
  EXPECT_EQ(out[2], 0x00);
  EXPECT_EQ(out[3], 0x00);
  EXPECT_EQ(at<std::uint64_t>(out, 0), 0x0102030405060708ULL);
  EXPECT_EQ(at<std::uint64_t>(out, 8), 1'700'000'000'123'456ULL);
  EXPECT_EQ(at<std::uint8_t>(out, 16), 2);
  EXPECT_EQ(at<std::uint8_t>(out, 17), 0);  // padding to position's alignment
  EXPECT_EQ(at<float>(out, 20), 1.5F);
  EXPECT_EQ(at<float>(out, 28), -0.75F);
  EXPECT_EQ(at<float>(out, 32), 0.5F);  // q[0] is w
  EXPECT_EQ(at<float>(out, 40), -0.5F);
  EXPECT_EQ(at<std::uint8_t>(out, 48), 3);
  EXPECT_EQ(at<float>(out, 52), 0.1F);
  EXPECT_EQ(at<float>(out, 64), -0.1F);
  EXPECT_EQ(at<float>(out, 76), 1e-6F);
  EXPECT_EQ(at<float>(out, 88), 4e-4F);
  EXPECT_EQ(at<float>(out, 100), 7e-3F);
  EXPECT_EQ(at<float>(out, 108), 9e-3F);
  EXPECT_EQ(at<std::uint8_t>(out, 112), 7);
  EXPECT_EQ(at<std::int8_t>(out, 113), -1);
}

TEST(Px4Messages, VehicleOdometryDecodesWhatPx4Sends) {
  std::vector<std::uint8_t> out;
  encode_px4_vehicle_odometry(sample_odometry(), out);
  const auto back = decode_px4_vehicle_odometry(out);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, sample_odometry());
  // Short, or not CDR: refused.
  out.pop_back();
  EXPECT_FALSE(decode_px4_vehicle_odometry(out).has_value());
  out.push_back(0);
  out[0] = 0x01;  // not an encapsulation kind CDR has
  EXPECT_FALSE(decode_px4_vehicle_odometry(out).has_value());
}

TEST(Px4Messages, VehicleOdometryBigEndianDecodes) {
  std::vector<std::uint8_t> sample(4 + 114, 0);
  sample[1] = 0x00;  // CDR_BE
  const std::uint64_t t = 123456789;
  for (std::size_t i = 0; i < 8; ++i)
    sample[4 + 8 + i] = static_cast<std::uint8_t>(t >> (56 - 8 * i));
  sample[4 + 112] = 9;
  const auto m = decode_px4_vehicle_odometry(sample);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->timestamp_sample, t);
  EXPECT_EQ(m->reset_counter, 9);
}

TEST(Px4Messages, VehicleStatusLeadingFields) {
  // v1.14's layout up to nav_state, written by hand: timestamp, armed_time, takeoff_time (u64),
  // arming_state, latest_arming_reason, latest_disarming_reason (u8), pad, nav_state_timestamp
  // (u64 at 32), nav_state_user_intention (u8 at 40), nav_state (u8 at 41), then more fields.
  std::vector<std::uint8_t> s(4 + 80, 0);
  s[1] = 0x01;
  const std::uint64_t ts = 61'500'000;
  std::memcpy(s.data() + 4, &ts, 8);
  s[4 + 24] = 2;   // ARMING_STATE_ARMED
  s[4 + 40] = 17;  // user intention: takeoff
  s[4 + 41] = 4;   // nav_state: AUTO_LOITER
  const auto v = decode_px4_vehicle_status(s);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->timestamp, ts);
  EXPECT_TRUE(v->armed());
  EXPECT_EQ(v->nav_state, 4);
  s[4 + 24] = 1;  // STANDBY (v1.14) / DISARMED (v1.15+)
  EXPECT_FALSE(decode_px4_vehicle_status(s)->armed());
  s.resize(4 + 41);
  EXPECT_FALSE(decode_px4_vehicle_status(s).has_value());
}

mavlink::Odometry px4_profile_odometry() {
  mavlink::Odometry m;
  m.time_usec = 42;
  m.x = 1;
  m.y = 2;
  m.z = -3;
  m.q = {0.9F, 0.1F, 0.2F, 0.3F};
  m.vx = 0.4F;
  m.vy = 0.5F;
  m.vz = 0.6F;
  m.rollspeed = 0.01F;
  m.pitchspeed = 0.02F;
  m.yawspeed = 0.03F;
  for (std::size_t i = 0; i < 21; ++i) {
    m.pose_covariance[i] = 100.0F + static_cast<float>(i);
    m.velocity_covariance[i] = 200.0F + static_cast<float>(i);
  }
  m.frame_id = 20;        // MAV_FRAME_LOCAL_FRD
  m.child_frame_id = 12;  // MAV_FRAME_BODY_FRD
  m.reset_counter = 3;
  m.estimator_type = 3;
  m.quality = 87;
  return m;
}

TEST(Px4Messages, OdometryCarriesOverAsPx4sReceiverMapsIt) {
  const Px4VehicleOdometry o = px4_vehicle_odometry_of(px4_profile_odometry(), 1000, 900);
  EXPECT_EQ(o.timestamp, 1000U);
  EXPECT_EQ(o.timestamp_sample, 900U);  // the caller's, never ODOMETRY's time_usec
  EXPECT_EQ(o.pose_frame, Px4VehicleOdometry::kFrameFrd);
  EXPECT_EQ(o.position, (std::array<float, 3>{1, 2, -3}));
  EXPECT_EQ(o.q, (std::array<float, 4>{0.9F, 0.1F, 0.2F, 0.3F}));
  EXPECT_EQ(o.velocity_frame, Px4VehicleOdometry::kVelocityFrameBodyFrd);
  EXPECT_EQ(o.velocity, (std::array<float, 3>{0.4F, 0.5F, 0.6F}));
  EXPECT_EQ(o.angular_velocity, (std::array<float, 3>{0.01F, 0.02F, 0.03F}));
  // The 6×6 upper triangles' diagonals: indices 0, 6, 11 | 15, 18, 20.
  EXPECT_EQ(o.position_variance, (std::array<float, 3>{100, 106, 111}));
  EXPECT_EQ(o.orientation_variance, (std::array<float, 3>{115, 118, 120}));
  EXPECT_EQ(o.velocity_variance, (std::array<float, 3>{200, 206, 211}));
  EXPECT_EQ(o.reset_counter, 3);
  EXPECT_EQ(o.quality, 87);
}

TEST(Px4Messages, OdometryFramesAndUnknownCovariances) {
  mavlink::Odometry m = px4_profile_odometry();
  m.frame_id = 1;        // MAV_FRAME_LOCAL_NED
  m.child_frame_id = 1;  // velocity in NED
  m.pose_covariance[0] = std::nanf("");
  m.velocity_covariance[0] = std::nanf("");
  Px4VehicleOdometry o = px4_vehicle_odometry_of(m, 0, 0);
  EXPECT_EQ(o.pose_frame, Px4VehicleOdometry::kFrameNed);
  EXPECT_EQ(o.velocity_frame, Px4VehicleOdometry::kFrameNed);
  for (const float v : o.position_variance) EXPECT_TRUE(std::isnan(v));
  for (const float v : o.orientation_variance) EXPECT_TRUE(std::isnan(v));
  for (const float v : o.velocity_variance) EXPECT_TRUE(std::isnan(v));
  m.frame_id = 21;  // MAV_FRAME_LOCAL_FLU: nothing PX4 fuses
  m.child_frame_id = 9;
  o = px4_vehicle_odometry_of(m, 0, 0);
  EXPECT_EQ(o.pose_frame, Px4VehicleOdometry::kFrameUnknown);
  EXPECT_TRUE(std::isnan(o.position[0]));
  EXPECT_TRUE(std::isnan(o.q[0]));
  EXPECT_EQ(o.velocity_frame, Px4VehicleOdometry::kFrameUnknown);
  EXPECT_TRUE(std::isnan(o.velocity[0]));
}

}  // namespace
}  // namespace mocaplink::wire
