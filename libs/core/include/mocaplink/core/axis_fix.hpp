// Gravity against mocap: the vehicle's tilt (roll and pitch from its IMU, whatever it fuses for
// yaw and position) compared with mocap's tilt of its body, and the axis settings that make the
// two agree (issue 48). Pure math; thread-safe.
//
// The comparison is of the gravity direction in the body (FRD "down" as each side sees it), not
// of Euler angles, so no yaw leaks in: the angle between
//   vehicle   d = (−sin θ, sin φ cos θ, cos φ cos θ)   (ATTITUDE roll φ, pitch θ; ZYX Euler)
//   mocap     d = R_ned_frdᵀ · (0, 0, 1)                (the Tracker's q_ned_frd)
// is the tilt offset, 0–180°.
#pragma once

#include <Eigen/Geometry>

namespace mocaplink::core {

/// Tilt offsets above this disagree. A vehicle at rest on a sloped floor or a rigid body defined
/// a little off level is a few degrees; the IMU's level trim (AHRS_TRIM, SENS_BOARD_*_OFF) a few
/// more; an axis mistake (up, body up) is 90° or 180°. 15° keeps 75° of margin below the smallest
/// axis mistake and lets a rigid body defined up to ~10° off level pass.
inline constexpr double kMaxTiltOffsetDeg = 15.0;

/// The body's down vector in FRD from roll and pitch (rad): gravity as the IMU sees it.
[[nodiscard]] Eigen::Vector3d down_frd_from_roll_pitch(double roll_rad, double pitch_rad);

/// The angle (deg, 0–180) between the vehicle's gravity direction (roll, pitch in rad) and
/// mocap's, from its attitude q_ned_frd (unit). NaN when an input is not finite.
[[nodiscard]] double tilt_offset_deg(const Eigen::Quaterniond& q_ned_frd, double roll_rad,
                                     double pitch_rad);

}  // namespace mocaplink::core
