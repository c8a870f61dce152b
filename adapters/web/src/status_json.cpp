#include "mocaplink/web/status_json.hpp"

#include <string_view>

namespace mocaplink::web {
namespace {

template <typename T>
nlohmann::json optional_json(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json fix_json(const std::optional<AxisFixView>& fix) {
  if (!fix) return nullptr;
  return {{"kind", fix->kind},
          {"lines", fix->lines},
          {"alternative_lines", fix->alternative_lines},
          {"tilt_residual_deg", fix->tilt_residual_deg},
          {"heading_residual_deg", optional_json(fix->heading_residual_deg)},
          {"text", fix->text}};
}

std::string text(std::string_view s) {
  return std::string(s);
}

nlohmann::json texts(const std::vector<std::string>& items) {
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& item : items) out.push_back(text(item));
  return out;
}

}  // namespace

std::string_view to_string(LinkHealth state) {
  switch (state) {
    case LinkHealth::up:
      return "up";
    case LinkHealth::silent:
      return "silent";
    case LinkHealth::down:
      return "down";
  }
  return "silent";
}

std::string_view to_string(TimesyncState state) {
  switch (state) {
    case TimesyncState::off:
      return "off";
    case TimesyncState::waiting:
      return "waiting";
    case TimesyncState::synced:
      return "synced";
  }
  return "off";
}

std::string_view to_string(AlertLevel level) {
  return level == AlertLevel::error ? "error" : "warning";
}

void to_json(nlohmann::json& j, const BodyView& body) {
  j = nlohmann::json{{"name", body.name},
                     {"state", text(core::to_string(body.state))},
                     {"tracked", body.tracked},
                     {"mirrored", body.mirrored},
                     {"p_m", optional_json(body.p_m)},
                     {"q_wxyz", optional_json(body.q_wxyz)},
                     {"frames_tracked", body.frames_tracked},
                     {"rejected", body.rejected},
                     {"resets", body.resets}};
}

void to_json(nlohmann::json& j, const BridgeLatencyView& latency) {
  j = nlohmann::json{
      {"last", latency.last}, {"p50", latency.p50}, {"p99", latency.p99}, {"max", latency.max}};
}

void to_json(nlohmann::json& j, const StationView& station) {
  j = nlohmann::json{{"source", station.source},
                     {"connected", station.connected},
                     {"error", station.error},
                     {"frame_rate_hz", station.frame_rate_hz},
                     {"nominal_rate_hz", optional_json(station.nominal_rate_hz)},
                     {"latency_ms", optional_json(station.latency_ms)},
                     {"jitter_ms", optional_json(station.jitter_ms)},
                     {"frames", station.frames},
                     {"dropped", station.drops_counted ? nlohmann::json(station.dropped)
                                                       : nlohmann::json(nullptr)},
                     {"bodies", station.bodies},
                     {"bridge_latency_ms", optional_json(station.bridge_latency_ms)},
                     {"late_frames_skipped", station.late_frames_skipped},
                     {"superseded_frames", station.superseded_frames},
                     {"rejected", station.rejected},
                     {"rejected_reason", station.rejected_reason.empty()
                                             ? nlohmann::json(nullptr)
                                             : nlohmann::json(station.rejected_reason)}};
}

void to_json(nlohmann::json& j, const HeartbeatView& heartbeat) {
  j = nlohmann::json{{"type", heartbeat.type},
                     {"autopilot", heartbeat.autopilot},
                     {"armed", heartbeat.armed},
                     {"mode", heartbeat.mode},
                     {"age_s", heartbeat.age_s}};
}

void to_json(nlohmann::json& j, const SetupItemView& item) {
  j = nlohmann::json{{"parameter", item.parameter},
                     {"current", optional_json(item.current)},
                     {"needed", item.needed},
                     {"severity", item.severity},
                     {"status", item.status},
                     {"why", item.why},
                     {"fix", optional_json(item.fix)},
                     {"reboot", item.reboot},
                     {"apply", item.apply},
                     {"apply_note", item.apply_note}};
}

void to_json(nlohmann::json& j, const StatusTextView& text_view) {
  j = nlohmann::json{
      {"severity", text_view.severity}, {"text", text_view.text}, {"age_s", text_view.age_s}};
}

void to_json(nlohmann::json& j, const EstimatorView& estimator) {
  j = nlohmann::json{{"source", estimator.source},
                     {"good", estimator.good},
                     {"problems", estimator.problems},
                     {"age_s", estimator.age_s}};
}

void to_json(nlohmann::json& j, const GcsEndpointView& e) {
  j = nlohmann::json{{"url", e.url},
                     {"state", e.state},
                     {"peers", e.peers},
                     {"frames_to_gcs", e.frames_to_gcs},
                     {"frames_from_gcs", e.frames_from_gcs},
                     {"dropped", e.dropped},
                     {"no_route", e.no_route},
                     {"timesync_answers", e.timesync_answers},
                     {"bad_frames", e.bad_frames}};
}

void to_json(nlohmann::json& j, const LinkShareView& s) {
  j = nlohmann::json{{"capacity_bytes_per_s", optional_json(s.capacity_bytes_per_s)},
                     {"own_bytes_per_s", s.own_bytes_per_s},
                     {"forwarded_bytes_per_s", s.forwarded_bytes_per_s},
                     {"forwarded", s.forwarded},
                     {"forwarded_dropped", s.forwarded_dropped},
                     {"queued_bytes", s.queued_bytes}};
}

void to_json(nlohmann::json& j, const VehicleView& vehicle) {
  j = nlohmann::json{
      {"name", vehicle.name},
      {"body", vehicle.body},
      {"link", vehicle.link},
      {"system_id", vehicle.system_id},
      {"profile", vehicle.profile},
      {"messages", vehicle.messages},
      {"available_messages", vehicle.available_messages},
      {"rate_hz", vehicle.rate_hz},
      {"paused", vehicle.paused},
      {"link_state", text(to_string(vehicle.link_state))},
      {"last_heard_s", optional_json(vehicle.last_heard_s)},
      {"sent_total", vehicle.sent_total},
      {"sent", vehicle.sent},
      {"send_rate_hz", vehicle.send_rate_hz},
      {"heartbeat", optional_json(vehicle.heartbeat)},
      {"timesync",
       {{"state", text(to_string(vehicle.timesync.state))},
        {"offset_ms", optional_json(vehicle.timesync.offset_ms)},
        {"rtt_ms", optional_json(vehicle.timesync.rtt_ms)}}},
      {"clock",
       {{"verdict", vehicle.clock.verdict ? nlohmann::json(text(to_string(*vehicle.clock.verdict)))
                                          : nlohmann::json()},
        {"rate_ppm", optional_json(vehicle.clock.rate_ppm)},
        {"residual_ms", optional_json(vehicle.clock.residual_ms)},
        {"pose_stamps", optional_json(vehicle.clock.pose_stamps)},
        {"withheld", vehicle.clock.withheld},
        {"reset_answers", vehicle.clock.reset_answers},
        {"text", vehicle.clock.text}}},
      {"origin",
       {{"state", text(to_string(vehicle.origin))},
        {"advice", optional_json(vehicle.origin_advice)}}},
      {"agreement",
       {{"verdict", text(to_string(vehicle.agreement.verdict))},
        {"tilt_offset_deg", optional_json(vehicle.agreement.tilt_offset_deg)},
        {"yaw_offset_deg", optional_json(vehicle.agreement.yaw_offset_deg)},
        {"position_offset_m", optional_json(vehicle.agreement.position_offset_m)},
        {"heading_offset_deg", optional_json(vehicle.agreement.heading_offset_deg)},
        {"checked", vehicle.agreement.checked},
        {"reason", optional_json(vehicle.agreement.reason)},
        {"fix", fix_json(vehicle.agreement.fix)}}},
      {"streams", vehicle.streams},
      {"autopilot",
       {{"name", vehicle.autopilot.name},
        {"version", optional_json(vehicle.autopilot.version)},
        {"profile_in_effect", vehicle.autopilot.profile_in_effect}}},
      {"setup",
       {{"state", vehicle.setup.state},
        {"items", vehicle.setup.items},
        {"reboot_for", vehicle.setup.reboot_for},
        {"last_refusal", vehicle.setup.last_refusal},
        {"note", vehicle.setup.note}}},
      {"statustext", vehicle.statustext},
      {"estimator", optional_json(vehicle.estimator)},
      {"delay_ms",
       {{"measured", optional_json(vehicle.delay_ms.measured)},
        {"recommended", optional_json(vehicle.delay_ms.recommended)},
        {"parameter", vehicle.delay_ms.parameter},
        {"current", optional_json(vehicle.delay_ms.current)},
        {"basis", vehicle.delay_ms.basis}}},
      {"gcs", vehicle.gcs},
      {"link_share", vehicle.link_share}};
}

void to_json(nlohmann::json& j, const Alert& alert) {
  j = nlohmann::json{{"level", text(to_string(alert.level))},
                     {"kind", alert.kind},
                     {"subject", alert.subject},
                     {"message", alert.message}};
}

void to_json(nlohmann::json& j, const Ros2TopicView& topic) {
  j = nlohmann::json{{"name", text(topic.name)},
                     {"type", text(topic.type)},
                     {"subscribers", topic.subscribers},
                     {"published", topic.published}};
}

void to_json(nlohmann::json& j, const Ros2View& ros2) {
  j = nlohmann::json{{"running", ros2.running},
                     {"error", text(ros2.error)},
                     {"domain_id", ros2.domain_id},
                     {"interface", text(ros2.network_interface)},
                     {"namespace", text(ros2.ns)},
                     {"frame_id", text(ros2.frame_id)},
                     {"axes", text(ros2.axes)},
                     {"implementation", text(ros2.implementation)},
                     {"topics", ros2.topics},
                     {"frames_published", ros2.frames_published},
                     {"frames_dropped", ros2.frames_dropped},
                     {"write_errors", ros2.write_errors},
                     {"unnamed", texts(ros2.unnamed)},
                     {"clashes", texts(ros2.clashes)}};
}

void to_json(nlohmann::json& j, const StatusView& status) {
  j = nlohmann::json{{"uptime_s", status.uptime_s},
                     {"station", status.station},
                     {"vehicles", status.vehicles},
                     {"alerts", status.alerts},
                     {"http",
                      {{"connections_open", status.http.open},
                       {"connections_refused", status.http.refused},
                       {"requests_timed_out", status.http.timed_out},
                       {"requests_host_refused", status.http.host_refused}}},
                     {"ros2", status.ros2 ? nlohmann::json(*status.ros2) : nlohmann::json()}};
}

}  // namespace mocaplink::web
