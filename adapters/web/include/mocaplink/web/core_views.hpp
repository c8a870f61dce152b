// Glue from the core's snapshots to the dashboard's views, so the daemon writes little code.
// Pure functions; thread-safety of the inputs is the caller's business (pass copies).
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/station.hpp"
#include "mocaplink/web/status.hpp"

namespace mocaplink::web {

/// A body as the Station saw it, with its Tracker's state and counters when `estimate` is given.
/// Without an estimate the state falls back to the Station's view: tracking when tracked in the
/// latest frame, unseen when never tracked, lost otherwise.
[[nodiscard]] BodyView make_body_view(const core::StationBody& body,
                                      const core::BodyEstimate* estimate);

/// Returns the Tracker estimate of a body by name, or nullptr when the body has no Tracker.
using EstimateLookup = std::function<const core::BodyEstimate*(std::string_view body)>;

/// The Station card: source URL, figures and every body (make_body_view with `estimate_of`).
[[nodiscard]] StationView make_station_view(std::string source,
                                            const core::StationSnapshot& snapshot,
                                            const EstimateLookup& estimate_of);

}  // namespace mocaplink::web
