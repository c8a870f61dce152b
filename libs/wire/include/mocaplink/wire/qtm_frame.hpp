// QTM data ↔ core::MocapFrame (qtm-rt.md §4.3, §4.4, §7). Decisions:
// - body i of the 6DOF component is named by the i-th <Body> of the parameters; a count that
//   differs is an error (the caller re-reads the parameters, §5.2);
// - mm → m; the nine matrix floats are read column by column (§4.3, unverified) into a rotation
//   body → QTM global frame; Euler variants use QTM's default "Qualisys standard" definition,
//   rotated axes roll about x, then pitch about y, then yaw about z: R = Rx(roll)·Ry(pitch)·Rz(yaw)
//   (unverified against a real server; prefer 6D / 6DRes);
// - a body is tracked only if all its floats are finite and the matrix is a rotation; NaN is
//   QTM's "not tracked" (§4.3); anything else non-finite or not a rotation is counted invalid;
// - frame_number = marker frame number, capture_time = marker timestamp (µs from the start of
//   the measurement), frame_rate_hz = General <Frequency> when known.
// Pure; thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/wire/qtm_parameters.hpp"
#include "mocaplink/wire/qtm_protocol.hpp"

namespace mocaplink::wire::qtm {

struct MappedFrame {
  core::MocapFrame frame;
  /// Bodies neither all-NaN nor a valid pose (a reflection matrix, det −1, is also marked
  /// BodySample::mirrored).
  std::size_t invalid_poses = 0;
};

/// Maps the `preferred` component of `data` (else its first 6DOF component) with `bodies` as the
/// names. Errors: no 6DOF component; body count different from bodies.size().
[[nodiscard]] Result<MappedFrame> to_mocap_frame(const DataPacket& data, Component preferred,
                                                 std::span<const BodyParameters> bodies,
                                                 std::optional<double> frequency_hz);

/// Euler angles (degrees, Qualisys standard) of a rotation, and back.
[[nodiscard]] std::array<double, 3> euler_from_quaternion(const Eigen::Quaterniond& q);
[[nodiscard]] Eigen::Quaterniond quaternion_from_euler(const std::array<double, 3>& deg);

/// One body as the emulator sends it: every field filled (matrix column by column, Euler,
/// residual), or all NaN when untracked.
[[nodiscard]] Body6d body_from_sample(const core::BodySample& sample, float residual_mm);

/// A frame as the emulator serves it: the body list (names) and the wire bodies.
struct ServedFrame {
  std::int64_t timestamp_us = 0;
  std::uint32_t frame_number = 0;
  std::vector<std::string> names;
  std::vector<Body6d> bodies;
};
[[nodiscard]] ServedFrame served_frame(const core::MocapFrame& frame);

}  // namespace mocaplink::wire::qtm
