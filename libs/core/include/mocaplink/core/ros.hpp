// What a mocap body is to ROS 2 (docs/ros2.md): ROS names for bodies, namespaces and frame ids
// (rmw's validate_full_topic_name rules, ros2-dds.md §1), and a body's state in ROS's frames
// (REP 103: an ENU world, FLU body axes; or the mocap system's own axes) with ROS's covariance
// conventions. Pure functions of values; thread-safe.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Geometry>

#include "mocaplink/core/axis_mapping.hpp"
#include "mocaplink/core/body_estimate.hpp"

namespace mocaplink::core {

/// Longest fully-qualified ROS topic name rmw accepts (RMW_TOPIC_MAX_NAME_LENGTH: 255 − 8 for the
/// DDS prefix and suffixes).
inline constexpr std::size_t kMaxRosTopicLength = 247;

/// A body name as one ROS name token: every byte outside [A-Za-z0-9_] becomes '_', runs of '_'
/// become one (ROS forbids "__"), '_' is trimmed at both ends, and a token that would start with a
/// digit gets a leading "_" ("Rigid Body 1" → "Rigid_Body_1", "1 quad" → "_1_quad"). Empty when
/// nothing of the name is left ("???"): such a body cannot be published.
[[nodiscard]] std::string ros_name_token(std::string_view body);

/// Why `ns` is not a ROS namespace of relative tokens ("mocap", "lab/mocap"; "" = none): nullopt
/// when it is. A leading '/' is allowed (the namespace is absolute either way).
[[nodiscard]] std::optional<std::string> ros_namespace_problem(std::string_view ns);

/// Why `frame_id` is not a tf2 frame id ("world", "map", "lab/world"; no leading '/', which tf2
/// strips with a warning, and the tokens of a ROS name): nullopt when it is.
[[nodiscard]] std::optional<std::string> ros_frame_id_problem(std::string_view frame_id);

/// "/NS/BODY/LEAF", or "/BODY/LEAF" for an empty namespace (`ns` as ros_namespace_problem takes it,
/// `body` already a token).
[[nodiscard]] std::string ros_body_topic(std::string_view ns, std::string_view body,
                                         std::string_view leaf);

/// Which axes a published body uses.
enum class RosAxes {
  /// REP 103: the world ENU (x east, y north, z up) and the body FLU (x forward, y left, z up),
  /// both from the same [mocap] / vehicle axis settings that give the vehicles NED and FRD.
  enu_flu,
  /// The mocap system's own world and rigid-body axes, as it streams them.
  mocap,
};
[[nodiscard]] std::string_view to_string(RosAxes axes);

/// A body's state as ROS messages carry it (geometry_msgs/Pose, nav_msgs/Odometry).
struct RosBodyState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< in the world frame
  /// Body → world (geometry_msgs/Quaternion is x, y, z, w); sign as the tracker's (continuous).
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();     ///< in the body frame
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();  ///< in the body frame
  /// Rows/cols x, y, z (world, m²), then rotation about the world's fixed X, Y, Z axes (rad²):
  /// geometry_msgs/PoseWithCovariance, row-major when written out.
  Matrix6d pose_covariance = Matrix6d::Zero();
  /// Rows/cols vx, vy, vz, wx, wy, wz, all in the body frame (REP 105: the twist of
  /// nav_msgs/Odometry is in child_frame_id).
  Matrix6d twist_covariance = Matrix6d::Zero();
};

/// The estimate (NED world, FRD body: body_estimate.hpp) in `axes`. `world` and `body` are the
/// mappings that made it (only RosAxes::mocap needs them: their inverses give back the mocap
/// system's axes). The attitude covariance, about the FRD body axes in the estimate, is turned
/// into one about the world's fixed axes (Σ_world = R Σ_body Rᵀ), as ROS defines it.
[[nodiscard]] RosBodyState ros_body_state(const BodyEstimate& estimate, RosAxes axes,
                                          const WorldAxisMapping& world,
                                          const BodyAxisMapping& body);

}  // namespace mocaplink::core
