// The boundary between the dashboard server and the daemon (`mocaplink run`). The daemon
// implements DashboardBackend; tests implement it with a fake. The server never touches the core.
#pragma once

#include <optional>

#include "mocaplink/web/status.hpp"
#include "mocaplink/web/vehicle_request.hpp"

namespace mocaplink::web {

/// Thread-safety contract: both functions are called from cpp-httplib's worker threads, possibly
/// several at once (REST requests and one call per event tick), never from the daemon's event
/// loop. An implementation either locks its own state or — what `mocaplink run` does — posts the
/// work to its event loop and waits for the answer. Calls must return promptly (≲ 100 ms): a slow
/// status() slows every dashboard.
class DashboardBackend {
 public:
  virtual ~DashboardBackend() = default;

  /// A consistent snapshot of the Station, bodies and vehicles as of now. Alerts the daemon knows
  /// of may be included; the server adds the ones it derives (alerts.hpp).
  [[nodiscard]] virtual StatusView status() = 0;

  /// Applies one already-validated change, completely or not at all, and returns std::nullopt on
  /// success or the reason it was refused. Expected refusals: 404 unknown vehicle (field ""), 409
  /// a vehicle with that name exists (field "name"), 422 a value the daemon cannot use (field
  /// named: "link" that does not parse or cannot open, "profile"/"messages" needing an [origin]
  /// that is not configured, "messages" the profile cannot send). After a successful return,
  /// status() reflects the change.
  [[nodiscard]] virtual std::optional<ApiError> apply(const VehicleChange& change) = 0;

 protected:
  DashboardBackend() = default;
  DashboardBackend(const DashboardBackend&) = default;
  DashboardBackend& operator=(const DashboardBackend&) = default;
};

}  // namespace mocaplink::web
