// EventLimiter (event_limiter.hpp): one event per kind and subject per gap, the last one kept.
#include "mocaplink/core/event_limiter.hpp"

#include <utility>

namespace mocaplink::core {

std::optional<LimitedEvent> EventLimiter::offer(const BridgeEvent& event, HostTime now) {
  State& s = keys_[std::string(to_string(event.kind)) + "/" + event.subject];
  if (s.last && now - *s.last < gap_) {
    if (s.held) ++s.dropped;
    s.held = event;
    return std::nullopt;
  }
  // The gap has passed: this one is newer than anything held, which is only counted.
  LimitedEvent out{event, s.dropped + (s.held ? 1 : 0)};
  s = State{now, 0, std::nullopt};
  return out;
}

std::vector<LimitedEvent> EventLimiter::flush(HostTime now, bool all) {
  std::vector<LimitedEvent> out;
  for (auto& [key, s] : keys_) {
    if (!s.held || (!all && s.last && now - *s.last < gap_)) continue;
    out.push_back({std::move(*s.held), s.dropped});
    s = State{now, 0, std::nullopt};
  }
  return out;
}

void EventLimiter::forget_quiet(HostTime now, Duration quiet) {
  std::erase_if(keys_, [&](const auto& entry) {
    return !entry.second.held && (!entry.second.last || now - *entry.second.last > quiet);
  });
}

}  // namespace mocaplink::core
