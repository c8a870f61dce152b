// What `mocaplink run` says on stderr while it runs: one line per vehicle at start, the core's
// events (rate-limited per subject), and a periodic summary (source frames and drops, per-vehicle
// pose rate, sent and dropped frames, link and vehicle state). With more than kDetailedVehicles
// vehicles the periodic summary aggregates, and lists only vehicles with problems.
// Rates (issue 29): a periodic summary gives each vehicle's pose rate over the period since the
// last one, and the source's as the Station measures it (the last second); the final one gives
// the whole run's averages instead — frames and poses over the time since begin(), or since the
// vehicle was added — and says so.
// Not thread-safe (event loop only).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/event_limiter.hpp"
#include "run_links.hpp"

namespace mocaplink::app {

inline constexpr std::size_t kDetailedVehicles = 10;

class Summary {
 public:
  Summary(const config::Config& config, std::chrono::milliseconds period);

  /// The start-up line of one vehicle, started (or added) at host time `now`: the final summary's
  /// average pose rate counts from then.
  void describe_vehicle(const config::Vehicle& vehicle, const io::Link& link, core::HostTime now);
  void on_frames(std::size_t frames) { frames_ += frames; }
  /// Marks when counting starts, so the first summary's rates divide by the time actually elapsed
  /// and the final one's averages by the run's length.
  void begin(core::HostTime now) {
    previous_time_ = now;
    begun_ = now;
  }
  /// Logs a core event, at most one per (kind, subject) per second (core::EventLimiter): one
  /// within the second is held back, the newest of them logged by flush() once the second has
  /// passed, the others counted and mentioned with it.
  void on_event(const core::BridgeEvent& event, core::HostTime now);
  /// Logs the held-back events whose second has passed (all of them with `all`, at exit). Called
  /// from the daemon's tick.
  void flush(core::HostTime now, bool all = false);
  /// The periodic (or, with `final`, the last) summary. `links` by vehicle slot; the queue's
  /// overflows and the frames skipped as too old or as superseded (core::LateFrames) since the
  /// start.
  void log(const core::BridgeSnapshot& snapshot, const std::vector<VehicleLink>& links,
           std::uint64_t queue_overflows, std::uint64_t late_frames,
           std::uint64_t superseded_frames, bool final);

 private:
  void write(const core::BridgeEvent& event, std::uint64_t suppressed);
  struct Previous {
    std::uint64_t poses = 0;
    std::uint64_t trouble = 0;  ///< frames dropped, errors and frames rejected, so far
  };

  const config::Config& config_;
  std::chrono::milliseconds period_;
  std::uint64_t frames_ = 0;
  core::EventLimiter limiter_;
  std::map<std::string, Previous> previous_;       // by vehicle name
  std::map<std::string, core::HostTime> started_;  // by vehicle name: when it was described
  std::optional<core::HostTime> previous_time_;
  std::optional<core::HostTime> begun_;
};

}  // namespace mocaplink::app
