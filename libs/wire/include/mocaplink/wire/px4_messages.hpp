// PX4's uXRCE-DDS messages (ros2-dds.md §4, docs/ros2.md "PX4 over uXRCE-DDS") as DDS samples:
// XCDR1 little endian behind the 4-byte encapsulation header, px4_msgs' field order. PX4's client
// copies fields at fixed offsets, so VehicleOdometry is always its 114-byte payload.
//
// px4_vehicle_odometry_of() carries an ODOMETRY message (the `px4` profile's, message_builders.hpp)
// into VehicleOdometry field by field, as PX4's own MAVLink receiver maps them into the same uORB
// topic: frames, velocity, variances (the covariances' diagonals), reset_counter and quality;
// only the times are the caller's. Pure; thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::wire {

/// DDS type names (px4_msgs as PX4's client names them: "px4_msgs::msg::dds_::<Type>_").
inline constexpr std::string_view kPx4VehicleOdometryType = "px4_msgs::msg::dds_::VehicleOdometry_";
inline constexpr std::string_view kPx4VehicleStatusType = "px4_msgs::msg::dds_::VehicleStatus_";
/// VehicleOdometry's payload (PX4's ucdr_topic_size_vehicle_odometry()), header not counted.
inline constexpr std::size_t kPx4VehicleOdometryPayload = 114;

/// px4_msgs/VehicleOdometry (v1.14–v1.17: the same fields).
struct Px4VehicleOdometry {
  static constexpr std::uint8_t kFrameUnknown = 0;
  static constexpr std::uint8_t kFrameNed = 1;
  static constexpr std::uint8_t kFrameFrd = 2;
  static constexpr std::uint8_t kVelocityFrameBodyFrd = 3;  ///< velocity_frame only

  std::uint64_t timestamp = 0;         ///< µs
  std::uint64_t timestamp_sample = 0;  ///< µs: the one EKF2 fuses the sample at
  std::uint8_t pose_frame = kFrameUnknown;
  std::array<float, 3> position{};  ///< m
  std::array<float, 4> q{};         ///< w, x, y, z: FRD body → pose frame
  std::uint8_t velocity_frame = kFrameUnknown;
  std::array<float, 3> velocity{};              ///< m/s
  std::array<float, 3> angular_velocity{};      ///< rad/s, body FRD
  std::array<float, 3> position_variance{};     ///< m²
  std::array<float, 3> orientation_variance{};  ///< rad²
  std::array<float, 3> velocity_variance{};     ///< (m/s)²
  std::uint8_t reset_counter = 0;
  std::int8_t quality = 0;
  friend bool operator==(const Px4VehicleOdometry&, const Px4VehicleOdometry&) = default;
};

/// What the link reads of px4_msgs/VehicleStatus: the leading fields, laid out alike in v1.14
/// to v1.17 (later fields differ between versions and are not read).
struct Px4VehicleStatus {
  static constexpr std::uint8_t kArmingStateArmed = 2;  ///< the same value in every version

  std::uint64_t timestamp = 0;  ///< µs
  std::uint64_t armed_time = 0;
  std::uint64_t takeoff_time = 0;
  std::uint8_t arming_state = 0;
  std::uint8_t nav_state = 0;  ///< NAVIGATION_STATE_*
  [[nodiscard]] bool armed() const { return arming_state == kArmingStateArmed; }
};

/// The 4-byte header and the 114-byte payload.
void encode_px4_vehicle_odometry(const Px4VehicleOdometry& m, std::vector<std::uint8_t>& out);
/// nullopt unless `sample` is a CDR (either byte order) VehicleOdometry of at least 114 bytes.
[[nodiscard]] std::optional<Px4VehicleOdometry> decode_px4_vehicle_odometry(
    std::span<const std::uint8_t> sample);
/// nullopt unless `sample` is a CDR VehicleStatus long enough for the fields read.
[[nodiscard]] std::optional<Px4VehicleStatus> decode_px4_vehicle_status(
    std::span<const std::uint8_t> sample);

/// ODOMETRY → VehicleOdometry (see the file comment). MAV_FRAME_LOCAL_NED / LOCAL_FRD give a NED /
/// FRD pose, any other frame_id an unknown one with NaN position and q (PX4 fuses none of it);
/// child_frame_id BODY_FRD / LOCAL_NED / LOCAL_FRD give that velocity frame, any other NaN
/// velocity. A NaN first covariance entry (ODOMETRY's "unknown") gives NaN variances.
[[nodiscard]] Px4VehicleOdometry px4_vehicle_odometry_of(const mavlink::Odometry& m,
                                                         std::uint64_t timestamp_us,
                                                         std::uint64_t timestamp_sample_us);

}  // namespace mocaplink::wire
