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

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/core/axis_mapping.hpp"

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

// ---- The fix (issue 48) ----
//
// With the vehicle at rest, its gravity direction (and its heading, where it has one independent
// of mocap) and the body's raw mocap orientation decide the axis settings: every proper choice
// of `up` (6) × `north` (4 axes at right angles, or the configured angle) and `body_forward` (6)
// × `body_up` (4) — 24 × 24 — is tried, R_ned_frd = W · R_world_body · B (axis_mapping.hpp), and
// one fits when its tilt offset is ≤ kMaxTiltOffsetDeg and, with a heading, its yaw is within
// kMaxHeadingOffsetDeg of it. Of the fits, the fewest changed keys wins; ties are broken by
// cost: +0.5 for an `up` other than the source's customary one (Vicon, QTM, Tracker UDP +z,
// Motive +y; none for VRPN), +0.25 for changing `north` (it moves every vehicle; a nose mistake
// is the body's), then the smaller residual. An equally good other choice is named beside it (a
// vehicle standing with its nose along a mocap axis cannot tell a wrong `up` from a wrong
// `body_up` once `up` is not the source's customary one: only its pose could).
// Without a heading, yaw is not observable: `north` and `body_forward` are kept, and the text
// says the nose is unchecked.
// Mirrors: when no proper choice fits but a left-handed one does (a reflected world or body
// side, or a raw orientation with determinant −1), the fix is named a mirror that no axis setting
// can repair. A world mirrored in a way that conjugates every rotation (M·R·M) is a proper
// rotation at every pose and fits (−M, −M) exactly: at rest no orientation check can see it; only
// motion (a step forward that mocap sees backward) does.

/// Yaw offsets from an independent heading (a compass) above this disagree: indoor compasses
/// are 10–30° off near steel and motors, a nose mistake is 90° or 180°; 45° is the middle.
inline constexpr double kMaxHeadingOffsetDeg = 45.0;

/// The four axis keys (docs/config.md `[mocap] up`, `north`, `body_forward`, `body_up`).
struct AxisSettings {
  SignedAxis up = axis::pos_z;
  North north = axis::pos_x;
  SignedAxis body_forward = axis::pos_x;
  SignedAxis body_up = axis::pos_z;
  friend bool operator==(const AxisSettings&, const AxisSettings&) = default;
};

/// What the vehicle says of itself at rest.
struct VehicleAtRest {
  double roll_rad = 0.0;   ///< ATTITUDE roll (IMU)
  double pitch_rad = 0.0;  ///< ATTITUDE pitch (IMU)
  /// A heading independent of mocap (rad, from north, NED yaw), e.g. its compass's
  /// (RAW_IMU's field) while EKF3 takes yaw from ExternalNav; nullopt when the vehicle has none.
  std::optional<double> heading_rad;
};

enum class AxisFixKind : std::uint8_t {
  agrees,  ///< the configured settings fit: nothing to change
  fix,     ///< other settings fit: `lines`
  mirror,  ///< only a left-handed choice fits: no setting can fix it
  no_fit,  ///< nothing fits (not at rest? another body?)
};
/// "agrees", "fix", "mirror", "no_fit".
[[nodiscard]] std::string_view to_string(AxisFixKind kind);

struct AxisFix {
  AxisFixKind kind = AxisFixKind::no_fit;
  AxisSettings settings;           ///< agrees, fix: the settings that fit
  std::vector<std::string> lines;  ///< fix: `[mocap] up = "+z"`, `[[vehicle]] body_up = "+y"`
  double tilt_residual_deg = 0.0;  ///< of the best choice (for no_fit: the best tried)
  std::optional<double> heading_residual_deg;  ///< with a heading
  std::vector<std::string> alternative_lines;  ///< fix: an equally good other choice, if any
  std::string text;                            ///< one sentence (log, dashboard, vehicle setup)
};

/// The fix for a body whose raw mocap orientation is `r_world_body` (mocap body → mocap world, as
/// the source reports it: before any axis mapping; a matrix so that a left-handed one can be
/// given), configured with `current`, on a vehicle at rest reporting `vehicle`. `source_up`: the
/// source's customary up axis (nullopt: none, VRPN).
[[nodiscard]] AxisFix find_axis_fix(const Eigen::Matrix3d& r_world_body,
                                    const AxisSettings& current, const VehicleAtRest& vehicle,
                                    std::optional<SignedAxis> source_up = std::nullopt);

}  // namespace mocaplink::core
