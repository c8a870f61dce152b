#include "mocaplink/core/quaternion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mocaplink::core {

std::string_view to_string(QuaternionFault fault) {
  switch (fault) {
    case QuaternionFault::none:
      return "none";
    case QuaternionFault::non_finite:
      return "non_finite";
    case QuaternionFault::non_unit:
      return "non_unit";
  }
  return "unknown";
}

QuaternionFault check_quaternion(const Eigen::Quaterniond& q, double tolerance) {
  if (!q.coeffs().allFinite()) return QuaternionFault::non_finite;
  if (!(std::abs(q.norm() - 1.0) <= tolerance)) return QuaternionFault::non_unit;
  return QuaternionFault::none;
}

Eigen::Quaterniond continuous_with(const Eigen::Quaterniond& q,
                                   const Eigen::Quaterniond& previous) {
  Eigen::Quaterniond out = q.normalized();
  if (out.dot(previous) < 0.0) out.coeffs() = -out.coeffs();
  return out;
}

Euler321 euler_321_from_quaternion(const Eigen::Quaterniond& q_ned_frd) {
  // Standard ZYX extraction from the rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll):
  // R20 = -sin(pitch), R21 = cos(pitch) sin(roll), R22 = cos(pitch) cos(roll),
  // R10 = cos(pitch) sin(yaw), R00 = cos(pitch) cos(yaw). Written in quaternion components so that
  // q and -q give bit-identical results (every term is a product of two components).
  const Eigen::Quaterniond q = q_ned_frd.normalized();
  const double w = q.w();
  const double x = q.x();
  const double y = q.y();
  const double z = q.z();
  Euler321 e;
  const double sin_pitch = std::clamp(2.0 * (w * y - x * z), -1.0, 1.0);
  e.pitch_rad = std::asin(sin_pitch);
  if (std::abs(sin_pitch) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw -/+ roll is defined; put it all in yaw (roll = 0).
    e.roll_rad = 0.0;
    // With roll = 0 and pitch = +-90 deg: R01 = -sin(yaw), R11 = cos(yaw).
    e.yaw_rad = std::atan2(-2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z));
  } else {
    e.roll_rad = std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
    e.yaw_rad = std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
  }
  if (e.yaw_rad <= -std::numbers::pi) e.yaw_rad = std::numbers::pi;
  return e;
}

Eigen::Quaterniond quaternion_from_euler_321(const Euler321& angles) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angles.yaw_rad, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(angles.pitch_rad, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(angles.roll_rad, Eigen::Vector3d::UnitX()));
}

Eigen::Vector3d rotation_vector_from_quaternion(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond u = q.normalized();
  if (u.w() < 0.0) u.coeffs() = -u.coeffs();
  const double s = u.vec().norm();
  if (s < 1e-9) return 2.0 * u.vec();  // angle = 2 asin(s) ~ 2 s, error O(s^3)
  const double angle = 2.0 * std::atan2(s, u.w());
  return u.vec() * (angle / s);
}

Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-9) {
    return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

}  // namespace mocaplink::core
