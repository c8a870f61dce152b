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

Duration LateFrames::catch_up_after() const noexcept {
  const auto period = interval_.value();
  if (!period) return kCatchUpAfter;
  return std::clamp(kCatchUpPeriods * *period, kCatchUpAfter, kMaxCatchUpAfter);
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
