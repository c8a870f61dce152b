#include "mocaplink/core/retry_schedule.hpp"

#include <algorithm>

namespace mocaplink::core {

using std::chrono::milliseconds;

RetrySchedule::RetrySchedule(const RetryPolicy& policy) : policy_(policy) {
  policy_.first = std::max(policy_.first, milliseconds{0});
  policy_.fast = std::max(policy_.fast, milliseconds{1});
  policy_.fast_for = std::max(policy_.fast_for, milliseconds{0});
  policy_.max = std::max(policy_.max, policy_.fast);
}

milliseconds RetrySchedule::next() noexcept {
  milliseconds delay{0};
  if (attempts_ == 0) {
    delay = policy_.first;
  } else if (waited_ < policy_.fast_for) {
    delay = policy_.fast;
  } else {
    backoff_ = backoff_.count() == 0 ? policy_.fast * 2 : backoff_ * 2;
    backoff_ = std::min(backoff_, policy_.max);
    delay = backoff_;
  }
  ++attempts_;
  waited_ += delay;
  return delay;
}

void RetrySchedule::reset() noexcept {
  attempts_ = 0;
  waited_ = milliseconds{0};
  backoff_ = milliseconds{0};
}

milliseconds first_attempt_after(const RetryPolicy& policy, milliseconds outage) {
  RetrySchedule schedule(policy);
  while (schedule.waited() < outage) (void)schedule.next();
  return schedule.waited();
}

}  // namespace mocaplink::core
