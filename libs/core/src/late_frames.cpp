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

std::optional<LateWarning> LateFrames::warning(HostTime now) noexcept {
  if (pending_.skipped == 0) return std::nullopt;
  if (warned_ && now - *warned_ < kLateWarningPeriod) return std::nullopt;
  warned_ = now;
  const LateWarning out = pending_;
  pending_ = LateWarning{};
  return out;
}

}  // namespace mocaplink::core
