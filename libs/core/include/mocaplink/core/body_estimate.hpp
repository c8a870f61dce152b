// BodyEstimate: what a Tracker publishes for one rigid body after every mocap frame, and what the
// Senders' message builders read (ODOMETRY, VISION_*, HIL_GPS, GPS_INPUT, ...).
//
// Frames (docs/frames.md): positions and linear velocities in local NED (m, m/s), attitude
// q_ned_frd (Hamilton, w first, rotating FRD body vectors into NED), angular rates about the FRD
// body axes (rad/s). Plain value type; copy it to hand it to another thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// Tracking state of one rigid body (DESIGN.md "Behaviour under faults").
enum class TrackingState {
  unseen,    ///< no valid sample yet: the estimate holds no information
  tracking,  ///< a valid sample arrived within loss_timeout_ms
  lost,      ///< no valid sample for loss_timeout_ms; estimate frozen at the last one
};
[[nodiscard]] std::string_view to_string(TrackingState state);

/// What the Tracker did with the latest input.
enum class SampleOutcome {
  accepted,          ///< measurement fused into the filter
  initialised,       ///< first valid sample ever: filter started at it (reset_counter unchanged)
  reset,             ///< the pose jumped: back from a gap (or a source clock restart) farther from
                     ///< the prediction than the jump thresholds, or a jump confirmed by
                     ///< jump_confirm_frames; filter re-initialised there (reset_counter++)
  rejected_outlier,  ///< outside the innovation gate: not fused, estimate is the prediction
  invalid_input,     ///< refused (see InvalidInput), not fused
  untracked,         ///< body occluded / absent in this frame
  resumed,  ///< back from a gap where the body could have got to: the stream continues, the filter
            ///< re-initialised there with its velocity unknown (reset_counter unchanged)
};
[[nodiscard]] std::string_view to_string(SampleOutcome outcome);

/// Why an input was refused before reaching the filter.
enum class InvalidInput : std::uint8_t {
  non_finite_position,    ///< NaN/inf in the position
  non_finite_quaternion,  ///< NaN/inf in the quaternion
  non_unit_quaternion,    ///< | ||q|| - 1 | > kQuaternionUnitTolerance
  time_not_increasing,  ///< capture time <= the previous input's (duplicate or out-of-order frame)
};
inline constexpr std::size_t kInvalidInputCount = 4;
[[nodiscard]] std::string_view to_string(InvalidInput reason);

/// Monotonic counters since the Tracker was created (never reset, not even by a filter reset).
struct TrackerCounters {
  std::uint64_t samples = 0;    ///< tracked samples offered (valid or not)
  std::uint64_t accepted = 0;   ///< fused (accepted + initialised + reset + resumed outcomes)
  std::uint64_t untracked = 0;  ///< frames in which the body was occluded or absent
  std::uint64_t rejected_outliers =
      0;                      ///< gated out (includes a jump's samples before it is confirmed)
  std::uint64_t resets = 0;   ///< pose jumps announced (reset_counter increments)
  std::uint64_t resumed = 0;  ///< returns after a gap that continued the stream (no increment)
  std::array<std::uint64_t, kInvalidInputCount> invalid_input{};  ///< indexed by InvalidInput

  [[nodiscard]] std::uint64_t invalid(InvalidInput reason) const {
    return invalid_input[static_cast<std::size_t>(reason)];
  }
  [[nodiscard]] std::uint64_t invalid_total() const {
    std::uint64_t total = 0;
    for (auto n : invalid_input) total += n;
    return total;
  }
};

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// The filtered state of one rigid body at `capture_time`.
struct BodyEstimate {
  /// Source-clock time the state refers to: the capture time of the latest frame processed (the
  /// state is predicted to it when that frame had no usable sample).
  SourceTime capture_time{};
  /// Capture time of the last measurement fused into the filter.
  SourceTime measurement_time{};
  TrackingState state = TrackingState::unseen;
  SampleOutcome last_outcome = SampleOutcome::untracked;

  Eigen::Vector3d p_ned_m = Eigen::Vector3d::Zero();    ///< position, local NED, m
  Eigen::Vector3d v_ned_mps = Eigen::Vector3d::Zero();  ///< velocity, local NED, m/s
  /// Unit; starts with w >= 0, then sign-continuous (never jumps to -q, so w may go negative).
  Eigen::Quaterniond q_ned_frd = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_frd_radps = Eigen::Vector3d::Zero();  ///< body rates p, q, r about FRD axes

  /// Pose covariance, rows/cols x, y, z (NED, m^2) then roll, pitch, yaw (rad^2): the attitude
  /// block is the covariance of the small rotation error about the FRD body axes, the usual
  /// stand-in for roll/pitch/yaw variances (exact for the variances near level flight). Position
  /// and attitude are estimated independently, so the off-diagonal 3x3 blocks are zero. ODOMETRY's
  /// pose_covariance is the upper triangle of this matrix.
  Matrix6d pose_covariance = Matrix6d::Zero();
  /// Velocity covariance, rows/cols vx, vy, vz (NED, (m/s)^2) then p, q, r (FRD, (rad/s)^2).
  /// For a body-frame velocity use v_frd_mps() and velocity_covariance_frd().
  Matrix6d velocity_covariance = Matrix6d::Zero();

  /// Incremented (wrapping 255 -> 0) when the pose jumped (SampleOutcome::reset) and never for a
  /// gap alone; MAVLink ODOMETRY.reset_counter.
  std::uint8_t reset_counter = 0;
  TrackerCounters counters;

  /// True when the pose at capture_time stands for fresh mocap data: state tracking and this frame
  /// was fused (accepted / initialised / reset) or was a single gated outlier bridged by the
  /// prediction. False for occluded frames, invalid input, and when lost or unseen.
  [[nodiscard]] bool pose_valid() const;

  /// Linear velocity in FRD body axes (m/s): R(q_ned_frd)^T * v_ned_mps.
  [[nodiscard]] Eigen::Vector3d v_frd_mps() const;
  /// velocity_covariance with its linear block rotated into FRD body axes (rates unchanged).
  [[nodiscard]] Matrix6d velocity_covariance_frd() const;
};

}  // namespace mocaplink::core
