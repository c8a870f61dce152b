// Gravity against mocap, and the axis settings that fit (axis_fix.hpp).
#include "mocaplink/core/axis_fix.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mocaplink::core {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// The angle between two unit vectors (deg), robust near 0 and 180 (atan2 of |a×b| and a·b).
double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

}  // namespace

Eigen::Vector3d down_frd_from_roll_pitch(double roll_rad, double pitch_rad) {
  // Third row of R_ned_frd = Rz(ψ) Ry(θ) Rx(φ): independent of ψ.
  return {-std::sin(pitch_rad), std::sin(roll_rad) * std::cos(pitch_rad),
          std::cos(roll_rad) * std::cos(pitch_rad)};
}

double tilt_offset_deg(const Eigen::Quaterniond& q_ned_frd, double roll_rad, double pitch_rad) {
  if (!std::isfinite(roll_rad) || !std::isfinite(pitch_rad) || !q_ned_frd.coeffs().allFinite()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const Eigen::Vector3d mocap = q_ned_frd.normalized().toRotationMatrix().row(2).transpose();
  return angle_deg(down_frd_from_roll_pitch(roll_rad, pitch_rad), mocap);
}

}  // namespace mocaplink::core
