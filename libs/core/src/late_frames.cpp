#include "mocaplink/core/late_frames.hpp"

#include <algorithm>

namespace mocaplink::core {

bool LateFrames::skip_if_late(Duration age) noexcept {
  if (age <= max_wait_) return false;
  ++skipped_;
  ++pending_.skipped;
  pending_.oldest = std::max(pending_.oldest, age);
  return true;
}

bool supersedes(const MocapFrame& newer, const MocapFrame& older) noexcept {
  const auto& have = newer.bodies;
  // The usual case first: the same bodies in the same order (a frame per capture, every body).
  if (have.size() >= older.bodies.size() &&
      std::equal(older.bodies.begin(), older.bodies.end(), have.begin(),
                 [](const BodySample& a, const BodySample& b) { return a.name == b.name; })) {
    return true;
  }
  return std::all_of(older.bodies.begin(), older.bodies.end(), [&](const BodySample& body) {
    return std::any_of(have.begin(), have.end(),
                       [&](const BodySample& b) { return b.name == body.name; });
  });
}

void LateFrames::handed_over(const MocapFrame& frame, HostTime queued) noexcept {
  if (last_handed_over_) {
    if (frame.frame_number == last_frame_number_ && frame.capture_time == last_capture_) return;
    const Duration gap = queued - *last_handed_over_;
    if (gap < Duration::zero()) return;  // not in order: keep the newest as the reference
    if (gap <= kMaxFrameWait) {
      // A running mean with weight 1/16: a source that hands frames over in pairs (0 and two
      // periods apart) comes out within a few % of its period.
      period_ = period_ ? *period_ + (gap - *period_) / 16 : gap;
    }
  }
  last_handed_over_ = queued;
  last_frame_number_ = frame.frame_number;
  last_capture_ = frame.capture_time;
}

Duration LateFrames::catch_up_after() const noexcept {
  if (!period_) return kCatchUpAfter;
  return std::clamp(kCatchUpPeriods * *period_, kCatchUpAfter, kMaxCatchUpAfter);
}

void LateFrames::begin_batch(HostTime first_queued, HostTime now) noexcept {
  if (!batch_done_ || first_queued > *batch_done_) behind_ = false;  // it found the loop idle
  if (now - first_queued > catch_up_after()) behind_ = true;
}

bool LateFrames::skip_if_superseded(const MocapFrame& frame, HostTime received,
                                    const MocapFrame& next, HostTime next_received) noexcept {
  if (!behind_ || next_received - received <= kSameBurst || !supersedes(next, frame)) return false;
  ++superseded_;
  ++pending_.superseded;
  return true;
}

std::optional<LateWarning> LateFrames::warning(HostTime now) noexcept {
  if (pending_.skipped == 0 && pending_.superseded == 0) return std::nullopt;
  if (warned_ && now - *warned_ < kLateWarningPeriod) return std::nullopt;
  warned_ = now;
  const LateWarning out = pending_;
  pending_ = LateWarning{};
  return out;
}

}  // namespace mocaplink::core
