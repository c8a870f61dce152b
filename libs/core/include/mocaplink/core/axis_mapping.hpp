// Axis mapping: a mocap system's world and rigid-body axes -> the internal NED world frame and FRD
// body frame (DESIGN.md "Conventions"; every convention is defined once in docs/frames.md).
//
// Config strings (the `[mocap]` table: `up`, `north`, `body_forward`, `body_up`):
//   signed axis   "+x" "-x" "+y" "-y" "+z" "-z"
//   up            a signed axis of the mocap world frame that points up (Vicon/QTM "+z",
//                 Motive "+y")
//   north         a signed horizontal world axis, or "angle:DEG": north is the reference axis
//                 rotated by DEG degrees about `up` (right-hand rule: counter-clockwise seen from
//                 above). The reference axis is +x, or +y when up is +-x. "angle:0" with up "+z"
//                 equals "+x"; "angle:90" with up "+z" equals "+y".
//   body_forward  the rigid body's axis that points out of the nose (default "+x")
//   body_up       the rigid body's axis that points up out of the top (default "+z")
// The defaults are Vicon-style FLU body axes, mapped to FRD.
//
// Mocap world frames are right-handed; the mapping is a proper rotation (det = +1) by construction.
// All types are immutable values; thread-safe to share.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include <Eigen/Geometry>

namespace mocaplink::core {

/// Why a mapping string was refused. `field` names the config key ("up", "north", "body_forward",
/// "body_up"); `message` says what was expected.
struct AxisMappingError {
  std::string field;
  std::string message;
};

/// Either a value or an AxisMappingError (std::expected is C++23).
template <typename T>
class [[nodiscard]] AxisMappingResult {
 public:
  AxisMappingResult(T value) : v_(std::move(value)) {}                 // NOLINT implicit by design
  AxisMappingResult(AxisMappingError error) : v_(std::move(error)) {}  // NOLINT implicit by design
  [[nodiscard]] bool has_value() const { return std::holds_alternative<T>(v_); }
  explicit operator bool() const { return has_value(); }
  /// Precondition: has_value().
  [[nodiscard]] const T& value() const { return std::get<T>(v_); }
  [[nodiscard]] const T& operator*() const { return value(); }
  [[nodiscard]] const T* operator->() const { return &value(); }
  /// Precondition: !has_value().
  [[nodiscard]] const AxisMappingError& error() const { return std::get<AxisMappingError>(v_); }

 private:
  std::variant<T, AxisMappingError> v_;
};

/// A signed coordinate axis: index 0 = x, 1 = y, 2 = z; sign +1 or -1.
struct SignedAxis {
  int index = 0;
  int sign = 1;
  [[nodiscard]] Eigen::Vector3d unit() const;
  friend bool operator==(const SignedAxis&, const SignedAxis&) = default;
};

/// "+x" -> {0, +1} ... "-z" -> {2, -1}. Exactly these six strings (lower case, sign required).
[[nodiscard]] AxisMappingResult<SignedAxis> parse_signed_axis(std::string_view text,
                                                              std::string_view field);

/// "+x", "-y", ... for a SignedAxis.
[[nodiscard]] std::string to_string(const SignedAxis& axis);
/// True when two axes are at right angles (different coordinate, either sign): the one rule for
/// up ⟂ north and body_forward ⟂ body_up (the config reports it with file:line).
[[nodiscard]] constexpr bool are_perpendicular(SignedAxis a, SignedAxis b) {
  return a.index != b.index;
}

/// The six signed axes by name (the config's defaults and tests).
namespace axis {
inline constexpr SignedAxis pos_x{0, 1};
inline constexpr SignedAxis neg_x{0, -1};
inline constexpr SignedAxis pos_y{1, 1};
inline constexpr SignedAxis neg_y{1, -1};
inline constexpr SignedAxis pos_z{2, 1};
inline constexpr SignedAxis neg_z{2, -1};
}  // namespace axis

/// North given as an angle in the horizontal plane of the mocap frame: north is the reference
/// axis rotated by `deg` degrees about up (right-handed: counter-clockwise seen from above). The
/// reference axis is +x, or +y when up is ±x.
struct NorthAngle {
  double deg = 0.0;
  friend bool operator==(const NorthAngle&, const NorthAngle&) = default;
};
/// The mocap direction that becomes NED north: a horizontal axis or an angle.
using North = std::variant<SignedAxis, NorthAngle>;
/// "+x" or "angle:37.5" (shortest round-trip decimal).
[[nodiscard]] std::string to_string(const North& north);

/// Mocap world frame -> NED. Rotation only (the NED origin is the mocap origin).
class WorldAxisMapping {
 public:
  /// Identity: the mocap world frame already is NED (used by tests, the benchmark and sources that
  /// deliver NED).
  WorldAxisMapping() = default;

  /// From the config strings. Errors: malformed strings, up parallel to north ("+z" with "-z"),
  /// non-finite or malformed angle. Angles of any finite size are accepted (taken modulo 360).
  [[nodiscard]] static AxisMappingResult<WorldAxisMapping> parse(std::string_view up,
                                                                 std::string_view north);
  /// From parsed values (the config's): the one place that checks north ⟂ up.
  [[nodiscard]] static AxisMappingResult<WorldAxisMapping> make(SignedAxis up, const North& north);

  /// Rotation matrix taking mocap-world coordinates to NED coordinates: p_ned = R * p_world.
  /// Rows are the N, E, D unit vectors expressed in mocap-world coordinates.
  [[nodiscard]] const Eigen::Matrix3d& r_ned_world() const { return r_ned_world_; }
  /// The same rotation as a unit quaternion (w >= 0).
  [[nodiscard]] const Eigen::Quaterniond& q_ned_world() const { return q_ned_world_; }

  /// The settings that made this mapping (identity: "-z" and "+x"), so that it can be written
  /// back as its config keys (the agreement's fix, axis_fix.hpp).
  [[nodiscard]] SignedAxis up() const { return up_; }
  [[nodiscard]] const North& north() const { return north_; }

  /// Any world vector (position m, velocity m/s) in NED coordinates.
  [[nodiscard]] Eigen::Vector3d to_ned(const Eigen::Vector3d& v_world) const {
    return r_ned_world_ * v_world;
  }

 private:
  WorldAxisMapping(SignedAxis up, North north, const Eigen::Matrix3d& r_ned_world);
  SignedAxis up_ = axis::neg_z;
  North north_ = axis::pos_x;
  Eigen::Matrix3d r_ned_world_ = Eigen::Matrix3d::Identity();
  Eigen::Quaterniond q_ned_world_ = Eigen::Quaterniond::Identity();
};

/// Mocap rigid-body axes -> FRD.
class BodyAxisMapping {
 public:
  /// Identity: the rigid body's axes already are FRD.
  BodyAxisMapping() = default;

  /// From the config strings (defaults "+x", "+z"). Errors: malformed strings, forward parallel to
  /// up.
  [[nodiscard]] static AxisMappingResult<BodyAxisMapping> parse(std::string_view forward,
                                                                std::string_view up);
  /// From parsed values (the config's): the one place that checks forward ⟂ up.
  [[nodiscard]] static AxisMappingResult<BodyAxisMapping> make(SignedAxis forward, SignedAxis up);

  /// The mocap body axis out of the nose and the one up out of the top that made this mapping
  /// (identity: "+x" and "-z"), so a mapping can be written back as its config keys.
  [[nodiscard]] SignedAxis forward() const { return forward_; }
  [[nodiscard]] SignedAxis up() const { return up_; }

  /// Rotation FRD -> mocap body: v_body = R * v_frd. Columns are the F, R, D unit vectors in mocap
  /// body coordinates.
  [[nodiscard]] const Eigen::Matrix3d& r_body_frd() const { return r_body_frd_; }
  /// The same rotation as a unit quaternion (w >= 0).
  [[nodiscard]] const Eigen::Quaterniond& q_body_frd() const { return q_body_frd_; }

 private:
  BodyAxisMapping(SignedAxis forward, SignedAxis up, const Eigen::Matrix3d& r_body_frd);
  SignedAxis forward_ = axis::pos_x;
  SignedAxis up_ = axis::neg_z;
  Eigen::Matrix3d r_body_frd_ = Eigen::Matrix3d::Identity();
  Eigen::Quaterniond q_body_frd_ = Eigen::Quaterniond::Identity();
};

/// World and body mapping together: what a Tracker needs to turn a BodySample into NED/FRD.
class AxisMapping {
 public:
  /// Identity on both sides.
  AxisMapping() = default;
  AxisMapping(const WorldAxisMapping& world, const BodyAxisMapping& body)
      : world_(world), body_(body) {}

  /// All four config strings at once; the first error wins (fields are checked in argument order).
  [[nodiscard]] static AxisMappingResult<AxisMapping> parse(std::string_view up,
                                                            std::string_view north,
                                                            std::string_view body_forward = "+x",
                                                            std::string_view body_up = "+z");

  [[nodiscard]] const WorldAxisMapping& world() const { return world_; }
  [[nodiscard]] const BodyAxisMapping& body() const { return body_; }

  /// Mocap-world position (m) -> NED position (m).
  [[nodiscard]] Eigen::Vector3d position_ned(const Eigen::Vector3d& p_world_m) const {
    return world_.to_ned(p_world_m);
  }
  /// Mocap attitude (mocap body -> mocap world) -> q_ned_frd (FRD body -> NED):
  /// q_ned_frd = q_ned_world * q_world_body * q_body_frd. Not normalised: the input's norm is kept
  /// so that the caller can still check it (check_quaternion).
  [[nodiscard]] Eigen::Quaterniond attitude_ned_frd(const Eigen::Quaterniond& q_world_body) const;

 private:
  WorldAxisMapping world_;
  BodyAxisMapping body_;
};

}  // namespace mocaplink::core
