// DecodedFrame (wire units and axes) → core::MocapFrame (metres, w-first quaternions, Z-up).
// Decisions (spec §9): body = subject, pose = its root segment's global pose; frame_number = the
// wire FrameInfo id as sent (the SDK >= 1.11 reports id + 1; we do not add 1); a Y-up server is
// turned Z-up exactly as the SDK's default axis mapping does (§9.4). Pure; thread-safe.
#pragma once

#include <cstddef>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/wire/vicon_client_stream.hpp"

namespace mocaplink::wire::vicon {

struct MappedFrame {
  core::MocapFrame frame;
  /// Tracked segments whose rotation was not a rotation matrix (non-finite, not orthonormal) or
  /// whose translation was not finite: reported as untracked and counted here (a reflection,
  /// det −1, is also marked BodySample::mirrored).
  std::size_t invalid_poses = 0;
};

/// Converts one decoded frame.
/// - bodies: one per subject, in SubjectInfo order, named by the subject; tracked = root segment
///   present in GlobalSegments; p_world_m = translation / 1000; q_world_body from R (§9.2).
/// - frame_rate_hz = 135 MHz / StreamInfo period (absent when the period is unknown).
/// - capture_time = frame_id × period on the 135 MHz clock (0 when the period is unknown).
/// - source_latency = sum of the LatencyInfo samples (absent without a LatencyInfo item).
[[nodiscard]] MappedFrame to_mocap_frame(const DecodedFrame& decoded);

}  // namespace mocaplink::wire::vicon
