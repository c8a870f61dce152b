// Rotation conventions of the DataStream wire (spec §9.2, §9.4) ↔ Hamilton quaternions, w first.
// The wire's R is row-major and maps segment vectors into the world: p_world = R·p_segment + t.
// Pure; thread-safe.
#pragma once

#include <array>
#include <optional>

#include <Eigen/Geometry>

namespace mocaplink::wire::vicon {

/// Largest |RᵀR − I| element (and |det R − 1|) accepted as a rotation. Doubles from a real server
/// are orthonormal to ~1e-15; float-rounded matrices to ~1e-7. Anything further off is not a pose.
inline constexpr double kRotationTolerance = 1e-3;

/// Quaternion of a row-major rotation matrix, with the SDK's sign choice (Shoemake's trace method:
/// w > 0 when trace > 0, otherwise the component of the largest diagonal element is positive),
/// normalised. nullopt if an element is not finite or R is not a rotation within
/// kRotationTolerance (e.g. the all-zero matrix of an occluded segment).
[[nodiscard]] std::optional<Eigen::Quaterniond> quaternion_from_rotation(
    const std::array<double, 9>& r_row_major);

/// Whether R is orthonormal within kRotationTolerance but a reflection (det R = −1): a mirrored,
/// left-handed frame — no pose, and no axis setting (a proper rotation) makes one of it.
[[nodiscard]] bool is_mirrored_rotation(const std::array<double, 9>& r_row_major);

/// Row-major rotation matrix of a (normalised) quaternion, for encoding.
[[nodiscard]] std::array<double, 9> rotation_from_quaternion(const Eigen::Quaterniond& q);

/// §9.4: a Y-up server (ApplicationInfo = 1) has axes (x forward, y up, z right); the SDK's default
/// output is Z-up (x forward, y left, z up): t' = Qᵀt = (x, −z, y), R' = QᵀRQ with
/// Q = [[1,0,0],[0,0,1],[0,−1,0]]. Applied by the client so that Vicon is always Z-up downstream.
[[nodiscard]] Eigen::Vector3d y_up_to_z_up(const Eigen::Vector3d& t);
[[nodiscard]] Eigen::Quaterniond y_up_to_z_up(const Eigen::Quaterniond& q);

}  // namespace mocaplink::wire::vicon
