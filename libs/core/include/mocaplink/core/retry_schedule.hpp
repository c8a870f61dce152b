// RetrySchedule: when to try a lost server (mocap source) or vehicle link again — the one
// schedule every reconnecting source and link uses (docs/daemon.md "Reconnecting").
//
//   RetrySchedule retry(policy);
//   on failure:  timer.expires_after(retry.next());   // 50 ms, then 200 ms, 200 ms, ...
//   on success:  retry.reset();                       // the next loss starts at `first` again
//
// A mocap server restart or a network blip is over in about a second, so the first attempt is
// almost at once and the next ones follow at short intervals for the first seconds: an outage of
// T seconds then costs at most T + `fast` of poses (with the defaults T + 0.2 s; PX4's EKF2 resets
// to vision by itself after 1 s without it, so a 0.8 s blip must not cost more than 1 s). A server
// that stays away is then tried less and less often, doubling up to `max`.
//
// Pure: no clock. The "first seconds" are counted as the sum of the delays handed out since the
// last reset, so the schedule is the same on every machine (the time the attempts themselves take
// only stretches it). Not thread-safe (one owner).
#pragma once

#include <chrono>
#include <cstdint>

namespace mocaplink::core {

struct RetryPolicy {
  /// Delay before the first attempt after a loss (and before the very first retry). >= 0.
  std::chrono::milliseconds first{50};
  /// Delay between the next attempts, while the delays so far add up to less than fast_for. >= 1.
  std::chrono::milliseconds fast{200};
  /// How long (sum of delays) the short interval lasts. >= 0.
  std::chrono::milliseconds fast_for{5000};
  /// After that the delay doubles, from 2 x fast, up to this. >= fast.
  std::chrono::milliseconds max{5000};
};

class RetrySchedule {
 public:
  /// Out-of-range fields are clamped (first >= 0, fast >= 1 ms, fast_for >= 0, max >= fast).
  explicit RetrySchedule(const RetryPolicy& policy = {});

  /// The delay before the next attempt; advances the schedule.
  [[nodiscard]] std::chrono::milliseconds next() noexcept;
  /// A connection worked: the next loss starts the schedule again.
  void reset() noexcept;

  /// Delays handed out since the last reset.
  [[nodiscard]] std::uint64_t attempts() const { return attempts_; }
  /// Their sum: how long the retries have waited since the loss.
  [[nodiscard]] std::chrono::milliseconds waited() const { return waited_; }
  [[nodiscard]] const RetryPolicy& policy() const { return policy_; }

 private:
  RetryPolicy policy_;
  std::uint64_t attempts_ = 0;
  std::chrono::milliseconds waited_{0};
  std::chrono::milliseconds backoff_{0};  ///< the last doubled delay (0: not doubling yet)
};

/// When the schedule first tries at or after `outage` (both counted from the loss, attempts
/// taking no time): a server back after `outage` is reached then, so
/// first_attempt_after(policy, T) - T is what the schedule adds to an outage of T.
[[nodiscard]] std::chrono::milliseconds first_attempt_after(const RetryPolicy& policy,
                                                            std::chrono::milliseconds outage);

}  // namespace mocaplink::core
