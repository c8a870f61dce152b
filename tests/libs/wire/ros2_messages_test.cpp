// XCDR1 encodings of the ROS messages, against bytes and sizes worked out from the CDR rules and
// ROS's .msg field lists (ros2-dds.md §2), not from the encoder. The cross-implementation check
// (a Cyclone DDS reader built from IDL) is tests/apps/run/ros2_topics.test.js.
#include "mocaplink/wire/ros2_messages.hpp"

#include <cstring>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mocaplink::wire {
namespace {

std::vector<std::uint8_t> bytes_of(std::initializer_list<int> v) {
  std::vector<std::uint8_t> out;
  for (int b : v) out.push_back(static_cast<std::uint8_t>(b));
  return out;
}

void append_double(std::vector<std::uint8_t>& out, double d) {
  std::uint8_t b[8];
  std::memcpy(b, &d, 8);  // the test runs on little-endian hosts only, as the encoder does
  out.insert(out.end(), b, b + 8);
}

double double_at(const std::vector<std::uint8_t>& v, std::size_t offset) {
  double d = 0;
  std::memcpy(&d, v.data() + offset, 8);
  return d;
}

std::uint32_t u32_at(const std::vector<std::uint8_t>& v, std::size_t offset) {
  return static_cast<std::uint32_t>(v[offset] | (v[offset + 1] << 8) | (v[offset + 2] << 16) |
                                    (v[offset + 3] << 24));
}

TEST(Ros2Messages, PoseStampedWorkedBytes) {
  core::RosBodyState s;
  s.position_m = {1.0, 2.0, 3.0};
  s.orientation = Eigen::Quaterniond::Identity();
  std::vector<std::uint8_t> out;
  encode_pose_stamped(RosStamp{1'700'000'000, 500'000'000}, "world", s, out);
  // ros2-dds.md §2: encapsulation, sec, nanosec, len 6, "world\0", padding to 8, seven doubles.
  std::vector<std::uint8_t> expected = bytes_of(
      {0x00, 0x01, 0x00, 0x00, 0x00, 0xf1, 0x53, 0x65, 0x00, 0x65, 0xcd, 0x1d, 0x06, 0x00,
       0x00, 0x00, 0x77, 0x6f, 0x72, 0x6c, 0x64, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
  for (double d : {1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0}) append_double(expected, d);  // x y z w last
  EXPECT_EQ(out, expected);
  EXPECT_EQ(out.size(), 84u);
}

TEST(Ros2Messages, OdometryLayout) {
  core::RosBodyState s;
  s.position_m = {1.5, -2.5, 0.25};
  s.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);  // w, x, y, z
  s.linear_velocity_mps = {0.1, 0.2, 0.3};
  s.angular_velocity_radps = {-0.1, -0.2, -0.3};
  for (int i = 0; i < 36; ++i) {
    s.pose_covariance(i / 6, i % 6) = 100.0 + i;  // row-major: element i is (i / 6, i % 6)
    s.twist_covariance(i / 6, i % 6) = 200.0 + i;
  }
  std::vector<std::uint8_t> out;
  encode_odometry(RosStamp{7, 8}, "odom", "base_link", s, out);
  // ros2-dds.md §2: "odom"/"base_link" → 720 bytes of payload.
  ASSERT_EQ(out.size(), 4u + 720u);
  const std::size_t p = 4;  // payload offsets count from here
  EXPECT_EQ(u32_at(out, p + 0), 7u);
  EXPECT_EQ(u32_at(out, p + 4), 8u);
  EXPECT_EQ(u32_at(out, p + 8), 5u);  // "odom\0"
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data() + p + 12), 4), "odom");
  // child_frame_id at align4(17) = 20: len 10, "base_link\0" to 34; pose at align8(34) = 40.
  EXPECT_EQ(u32_at(out, p + 20), 10u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data() + p + 24), 9), "base_link");
  EXPECT_EQ(double_at(out, p + 40), 1.5);
  EXPECT_EQ(double_at(out, p + 48), -2.5);
  EXPECT_EQ(double_at(out, p + 56), 0.25);
  EXPECT_EQ(double_at(out, p + 64), 0.5);              // x
  EXPECT_EQ(double_at(out, p + 72), -0.5);             // y
  EXPECT_EQ(double_at(out, p + 80), 0.5);              // z
  EXPECT_EQ(double_at(out, p + 88), 0.5);              // w
  EXPECT_EQ(double_at(out, p + 96), 100.0);            // covariance[0]
  EXPECT_EQ(double_at(out, p + 96 + 8 * 7), 107.0);    // covariance[7] = (1, 1)
  EXPECT_EQ(double_at(out, p + 96 + 8 * 35), 135.0);   // covariance[35]
  EXPECT_EQ(double_at(out, p + 384), 0.1);             // twist.linear.x
  EXPECT_EQ(double_at(out, p + 416), -0.2);            // twist.angular.y
  EXPECT_EQ(double_at(out, p + 432), 200.0);           // twist covariance[0]
  EXPECT_EQ(double_at(out, p + 432 + 8 * 35), 235.0);  // … and [35], the last 8 bytes
}

TEST(Ros2Messages, TfMessageLayout) {
  const RosTransform one{RosStamp{1, 2}, "world", "drone1", Eigen::Vector3d(4, 5, 6),
                         Eigen::Quaterniond::Identity()};
  std::vector<std::uint8_t> out;
  encode_tf_message(std::span(&one, 1), out);
  // ros2-dds.md §2: one "world"/"drone1" entry → 96 bytes of payload.
  ASSERT_EQ(out.size(), 4u + 96u);
  EXPECT_EQ(u32_at(out, 4), 1u);  // the sequence count
  // header at 4: stamp, "world" (len at 12, chars 16..21), child at align4(22) = 24: len 7,
  // "drone1\0" to 35, translation at align8(35) = 40.
  EXPECT_EQ(u32_at(out, 4 + 24), 7u);
  EXPECT_EQ(double_at(out, 4 + 40), 4.0);
  EXPECT_EQ(double_at(out, 4 + 88), 1.0);  // rotation.w, the last field
  std::vector<std::uint8_t> empty;
  encode_tf_message({}, empty);
  EXPECT_EQ(empty, bytes_of({0, 1, 0, 0, 0, 0, 0, 0}));
}

TEST(Ros2Messages, StampsFromUnixNanoseconds) {
  EXPECT_EQ(ros_stamp_from_unix_ns(1'700'000'000'500'000'000),
            (RosStamp{1'700'000'000, 500'000'000}));
  EXPECT_EQ(ros_stamp_from_unix_ns(0), (RosStamp{0, 0}));
  EXPECT_EQ(ros_stamp_from_unix_ns(-1), (RosStamp{-1, 999'999'999}));
}

}  // namespace
}  // namespace mocaplink::wire
