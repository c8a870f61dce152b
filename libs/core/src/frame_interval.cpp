#include "mocaplink/core/frame_interval.hpp"

namespace mocaplink::core {

void FrameInterval::observe(SourceTime capture) noexcept {
  if (last_ && capture > *last_) {
    const Duration sample = capture - *last_;
    if (!interval_ || sample < *interval_) {
      interval_ = sample;
    } else {
      *interval_ += (sample - *interval_) / 16;
    }
  }
  last_ = capture;
}

}  // namespace mocaplink::core
