#include "mocaplink/sources/replay_config.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace mocaplink::sources {

core::Duration ReplaySchedule::due(core::SourceTime capture) {
  if (!first_capture_) first_capture_ = capture;
  if (speed_ <= 0.0) return core::Duration{0};
  const double since_first_ns = static_cast<double>((capture - *first_capture_).count()) / speed_;
  core::Duration due = pass_start_ + core::Duration{std::llround(std::max(0.0, since_first_ns))};
  if (due < last_due_) due = last_due_;  // never schedule backwards
  last_due_ = due;
  return due;
}

void ReplaySchedule::next_pass() {
  first_capture_.reset();
  pass_start_ = last_due_;
}

}  // namespace mocaplink::sources
