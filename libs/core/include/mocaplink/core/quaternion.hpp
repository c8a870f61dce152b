// Quaternion utilities shared by the axis mapping, the Tracker and the message builders.
//
// Convention (docs/frames.md "Quaternions"): Hamilton quaternions, written and constructed w first
// (Eigen::Quaterniond(w, x, y, z)), rotating body-frame vectors into the world frame:
// v_world = q_world_body * v_body * conj(q_world_body). q and -q are the same rotation.
//
// All functions are pure and thread-safe (no shared state).
#pragma once

#include <string_view>

#include <Eigen/Geometry>

namespace mocaplink::core {

/// Largest accepted | ||q|| - 1 | for a quaternion from a mocap source. A source that sends doubles
/// or floats (Vicon SDK, NatNet, VRPN) is within ~1e-6; anything beyond 1e-3 is a decoding bug or
/// garbage, and silently normalising it would hide that.
inline constexpr double kQuaternionUnitTolerance = 1e-3;

/// Why a quaternion was refused.
enum class QuaternionFault {
  none,        ///< finite and unit within tolerance
  non_finite,  ///< a component is NaN or infinite
  non_unit,    ///< | ||q|| - 1 | > tolerance (includes the zero quaternion)
};

[[nodiscard]] std::string_view to_string(QuaternionFault fault);

/// Checks a quaternion from outside. `tolerance` >= 0 is the allowed | ||q|| - 1 |.
[[nodiscard]] QuaternionFault check_quaternion(const Eigen::Quaterniond& q,
                                               double tolerance = kQuaternionUnitTolerance);

/// `q` normalised and sign-flipped, if needed, into the hemisphere of `previous`
/// (dot(q, previous) >= 0), so that a stream of attitudes has no q/-q jumps. `q` must be finite and
/// non-zero (check it first); `previous` must be finite.
[[nodiscard]] Eigen::Quaterniond continuous_with(const Eigen::Quaterniond& q,
                                                 const Eigen::Quaterniond& previous);

/// Tait-Bryan angles, intrinsic z-y'-x'' (yaw, then pitch, then roll), in radians: the "3-2-1"
/// Euler angles of VISION_POSITION_ESTIMATE and of PX4/ArduPilot's Euler-to-quaternion routines.
struct Euler321 {
  double roll_rad = 0.0;   ///< about body x (forward), [-pi, pi]
  double pitch_rad = 0.0;  ///< about y', [-pi/2, pi/2]
  double yaw_rad = 0.0;    ///< about world z (down), (-pi, pi]; 0 = nose north, +pi/2 = nose east
};

/// Euler 3-2-1 angles of a unit quaternion q_ned_frd (body FRD -> world NED). At pitch = +-90 deg
/// (gimbal lock) roll and yaw are not separable; the result then still reproduces the rotation.
/// q and -q give identical angles. A yaw of -pi is reported as +pi.
[[nodiscard]] Euler321 euler_321_from_quaternion(const Eigen::Quaterniond& q_ned_frd);

/// Unit quaternion (w >= 0 not guaranteed) from Euler 3-2-1 angles: q = Rz(yaw) Ry(pitch) Rx(roll).
[[nodiscard]] Eigen::Quaterniond quaternion_from_euler_321(const Euler321& angles);

/// Rotation vector (axis * angle, rad) of a unit quaternion, angle in [0, pi] (the shorter of q and
/// -q is used). Inverse of quaternion_from_rotation_vector.
[[nodiscard]] Eigen::Vector3d rotation_vector_from_quaternion(const Eigen::Quaterniond& q);

/// Unit quaternion exp(v/2) for a rotation vector v (axis * angle, rad); exact for any |v|.
[[nodiscard]] Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& v);

}  // namespace mocaplink::core
