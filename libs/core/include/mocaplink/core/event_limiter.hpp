// EventLimiter: how often the log repeats an event of one kind about one subject (a body's
// tracking, a vehicle's agreement verdict...): at most once per `gap`, and never losing the last
// word. An event within `gap` of the last one let through is held back (the newest replaces an
// older held one, which is then only counted); once `gap` has passed, flush() gives the held one
// out. A burst — an agreement re-judged as each of the vehicle's parameters arrives, 100 ms
// apart — thus logs its first and its last line, 1 s apart at most, instead of the first alone:
// the log's last agreement line is the one the dashboard shows.
// Pure: time is passed in. Not thread-safe (one owner).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// An event to log, with how many of its kind and subject were dropped before it (held back and
/// replaced by a newer one).
struct LimitedEvent {
  BridgeEvent event;
  std::uint64_t suppressed = 0;
};

class EventLimiter {
 public:
  explicit EventLimiter(Duration gap = std::chrono::seconds(1)) : gap_(gap) {}

  /// The event to log now (with the count dropped since the last one logged), or nullopt when it
  /// is held back for flush(). Keyed by kind and subject.
  [[nodiscard]] std::optional<LimitedEvent> offer(const BridgeEvent& event, HostTime now);

  /// The held events whose gap has passed by `now` (every held one with `all`: at exit), in key
  /// order; each then counts as logged at `now`.
  [[nodiscard]] std::vector<LimitedEvent> flush(HostTime now, bool all = false);

  /// Forgets subjects with nothing held and nothing logged for `quiet` (bodies and vehicles come
  /// and go: the map must not grow with every name ever seen).
  void forget_quiet(HostTime now, Duration quiet);

  [[nodiscard]] std::size_t size() const { return keys_.size(); }

 private:
  struct State {
    std::optional<HostTime> last;     ///< when one was last logged
    std::uint64_t dropped = 0;        ///< held back and replaced since then
    std::optional<BridgeEvent> held;  ///< the newest held back
  };
  Duration gap_;
  std::map<std::string, State> keys_;
};

}  // namespace mocaplink::core
