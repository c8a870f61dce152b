// ROS 2 messages as DDS samples (ros2-dds.md §1–§2, docs/ros2.md): plain CDR (XCDR1), little
// endian, the 4-byte encapsulation header 00 01 00 00 first, every primitive aligned to its size
// (at most 8) from the start of the payload, strings as a uint32 length that counts the NUL, then
// the bytes and the NUL; @final structures in .msg field order. What a Fast DDS or Cyclone DDS
// reader generated from ROS's own .msg files decodes. Pure; thread-safe.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "mocaplink/core/ros.hpp"

namespace mocaplink::wire {

/// DDS type names of the messages encoded here (rmw's "<pkg>::msg::dds_::<Type>_").
inline constexpr std::string_view kRosPoseStampedType = "geometry_msgs::msg::dds_::PoseStamped_";
inline constexpr std::string_view kRosOdometryType = "nav_msgs::msg::dds_::Odometry_";
inline constexpr std::string_view kRosTfMessageType = "tf2_msgs::msg::dds_::TFMessage_";

/// builtin_interfaces/Time: seconds and nanoseconds since the Unix epoch (ROS time is the wall
/// clock unless a node uses simulated time).
struct RosStamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;  ///< 0..999'999'999
  friend bool operator==(const RosStamp&, const RosStamp&) = default;
};
/// The stamp of `unix_ns` (negative values count down from the epoch: sec < 0, nanosec ≥ 0).
[[nodiscard]] RosStamp ros_stamp_from_unix_ns(std::int64_t unix_ns);

/// Appends XCDR1 little-endian values to a byte vector. The constructor clears it and writes the
/// encapsulation header; alignment counts from the byte after the header.
class CdrWriter {
 public:
  explicit CdrWriter(std::vector<std::uint8_t>& out);
  void u8(std::uint8_t v);
  void i8(std::int8_t v);
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void i32(std::int32_t v);
  void f32(float v);
  void f64(double v);
  /// uint32 length including the NUL, the bytes, the NUL. `s` must hold no NUL.
  void string(std::string_view s);
  /// Pads with zeros to a multiple of `n` (1, 2, 4 or 8) of the payload.
  void align(std::size_t n);

 private:
  void put(const void* bytes, std::size_t size);
  std::vector<std::uint8_t>& out_;
};

/// geometry_msgs/PoseStamped: header {stamp, frame_id}, pose {position, orientation x y z w}.
void encode_pose_stamped(const RosStamp& stamp, std::string_view frame_id,
                         const core::RosBodyState& state, std::vector<std::uint8_t>& out);

/// nav_msgs/Odometry: header, child_frame_id, pose with covariance (in frame_id), twist with
/// covariance (in child_frame_id). Covariances row-major, 36 values each.
void encode_odometry(const RosStamp& stamp, std::string_view frame_id,
                     std::string_view child_frame_id, const core::RosBodyState& state,
                     std::vector<std::uint8_t>& out);

/// One geometry_msgs/TransformStamped of a tf2_msgs/TFMessage: frame_id → child_frame_id.
struct RosTransform {
  RosStamp stamp;
  std::string_view frame_id;
  std::string_view child_frame_id;
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};
/// tf2_msgs/TFMessage: a uint32 count, then each transform.
void encode_tf_message(std::span<const RosTransform> transforms, std::vector<std::uint8_t>& out);

}  // namespace mocaplink::wire
