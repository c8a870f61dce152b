// StatusView → JSON, exactly as docs/api.md documents it (GET /api/status, /api/events).
// Optional values become null; enums their to_string spelling. Thread-safety: pure functions.
#pragma once

#include <nlohmann/json.hpp>

#include "mocaplink/web/status.hpp"

namespace mocaplink::web {

void to_json(nlohmann::json& j, const BodyView& body);
void to_json(nlohmann::json& j, const BridgeLatencyView& latency);
void to_json(nlohmann::json& j, const StationView& station);
void to_json(nlohmann::json& j, const HeartbeatView& heartbeat);
void to_json(nlohmann::json& j, const GcsEndpointView& endpoint);
void to_json(nlohmann::json& j, const LinkShareView& share);
void to_json(nlohmann::json& j, const VehicleView& vehicle);
void to_json(nlohmann::json& j, const Alert& alert);
void to_json(nlohmann::json& j, const StatusView& status);

}  // namespace mocaplink::web
