#include "mocaplink/core/late_frames.hpp"

#include <algorithm>

namespace mocaplink::core {

bool LateFrames::skip_if_late(HostTime received, HostTime now) noexcept {
  const Duration wait = now - received;
  if (wait <= max_wait_) return false;
  ++skipped_;
  ++pending_.skipped;
  pending_.longest_wait = std::max(pending_.longest_wait, wait);
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
