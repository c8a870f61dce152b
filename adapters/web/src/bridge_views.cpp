#include "mocaplink/web/bridge_views.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

#include "mocaplink/web/core_views.hpp"

namespace mocaplink::web {
namespace {

using namespace std::string_literals;

struct Named {
  std::uint32_t value;
  const char* name;
};

std::string lookup(std::span<const Named> table, std::uint32_t value, const std::string& fallback) {
  for (const Named& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return fallback;
}

// MAV_TYPE (common.xml), the values a mocap lab meets.
constexpr std::array<Named, 17> kTypes{{{0, "generic"},
                                        {1, "fixed_wing"},
                                        {2, "quadrotor"},
                                        {3, "coaxial"},
                                        {4, "helicopter"},
                                        {10, "ground_rover"},
                                        {11, "surface_boat"},
                                        {12, "submarine"},
                                        {13, "hexarotor"},
                                        {14, "octorotor"},
                                        {15, "tricopter"},
                                        {19, "vtol_tailsitter_duo"},
                                        {20, "vtol_tailsitter_quad"},
                                        {21, "vtol_tiltrotor"},
                                        {22, "vtol_fixedrotor"},
                                        {29, "dodecarotor"},
                                        {35, "decarotor"}}};
// MAV_AUTOPILOT.
constexpr std::array<Named, 4> kAutopilots{
    {{0, "generic"}, {3, "ardupilotmega"}, {8, "invalid"}, {12, "px4"}}};
// PX4 main modes (px4_custom_mode.h, custom_mode byte 2) and AUTO sub-modes (byte 3).
constexpr std::array<Named, 9> kPx4Main{{{1, "MANUAL"},
                                         {2, "ALTCTL"},
                                         {3, "POSCTL"},
                                         {4, "AUTO"},
                                         {5, "ACRO"},
                                         {6, "OFFBOARD"},
                                         {7, "STABILIZED"},
                                         {8, "RATTITUDE"},
                                         {9, "SIMPLE"}}};
constexpr std::array<Named, 9> kPx4Auto{{{1, "AUTO_READY"},
                                         {2, "AUTO_TAKEOFF"},
                                         {3, "AUTO_LOITER"},
                                         {4, "AUTO_MISSION"},
                                         {5, "AUTO_RTL"},
                                         {6, "AUTO_LAND"},
                                         {8, "AUTO_FOLLOW_TARGET"},
                                         {9, "AUTO_PRECLAND"},
                                         {10, "AUTO_VTOL_TAKEOFF"}}};
// ArduPilot mode numbers (ArduCopter/mode.h, ArduPlane/mode.h, Rover/mode.h).
constexpr std::array<Named, 15> kCopter{{{0, "STABILIZE"},
                                         {1, "ACRO"},
                                         {2, "ALT_HOLD"},
                                         {3, "AUTO"},
                                         {4, "GUIDED"},
                                         {5, "LOITER"},
                                         {6, "RTL"},
                                         {7, "CIRCLE"},
                                         {9, "LAND"},
                                         {11, "DRIFT"},
                                         {13, "SPORT"},
                                         {16, "POSHOLD"},
                                         {17, "BRAKE"},
                                         {20, "GUIDED_NOGPS"},
                                         {21, "SMART_RTL"}}};
constexpr std::array<Named, 10> kPlane{{{0, "MANUAL"},
                                        {1, "CIRCLE"},
                                        {2, "STABILIZE"},
                                        {5, "FBWA"},
                                        {6, "FBWB"},
                                        {10, "AUTO"},
                                        {11, "RTL"},
                                        {12, "LOITER"},
                                        {15, "GUIDED"},
                                        {19, "QLOITER"}}};
constexpr std::array<Named, 9> kRover{{{0, "MANUAL"},
                                       {1, "ACRO"},
                                       {3, "STEERING"},
                                       {4, "HOLD"},
                                       {5, "LOITER"},
                                       {10, "AUTO"},
                                       {11, "RTL"},
                                       {12, "SMART_RTL"},
                                       {15, "GUIDED"}}};

double seconds_between(core::HostTime from, core::HostTime to) {
  return core::to_seconds(to - from);
}

LinkState link_state(core::LinkState state, bool down) {
  if (down) return LinkState::down;
  return state == core::LinkState::alive ? LinkState::up : LinkState::silent;
}

}  // namespace

std::string mav_type_name(std::uint8_t type) {
  return lookup(kTypes, type, std::to_string(type));
}

std::string mav_autopilot_name(std::uint8_t autopilot) {
  return lookup(kAutopilots, autopilot, std::to_string(autopilot));
}

std::string flight_mode_name(std::uint8_t autopilot, std::uint8_t type, std::uint32_t custom_mode) {
  const std::string fallback = "custom_mode " + std::to_string(custom_mode);
  if (autopilot == core::kMavAutopilotPx4) {
    const std::uint32_t main_mode = (custom_mode >> 16) & 0xFFU;
    const std::uint32_t sub_mode = (custom_mode >> 24) & 0xFFU;
    if (main_mode == 4 && sub_mode != 0) return lookup(kPx4Auto, sub_mode, "AUTO");
    return lookup(kPx4Main, main_mode, fallback);
  }
  if (autopilot == core::kMavAutopilotArdupilot) {
    if (type == 1 || (type >= 19 && type <= 22)) return lookup(kPlane, custom_mode, fallback);
    if (type == 10 || type == 11) return lookup(kRover, custom_mode, fallback);
    return lookup(kCopter, custom_mode, fallback);
  }
  return fallback;
}

BridgeStatusBuilder::BridgeStatusBuilder(core::HostTime started) : started_(started) {}

StatusView BridgeStatusBuilder::build(const core::BridgeSnapshot& snapshot,
                                      const BridgeStatusContext& context) {
  StatusView status;
  const core::HostTime now = snapshot.time;
  status.uptime_s = std::max(0.0, seconds_between(started_, now));
  status.station =
      make_station_view(context.source, snapshot.station,
                        [&snapshot](std::string_view body) -> const core::BodyEstimate* {
                          for (const core::BodySnapshot& b : snapshot.bodies) {
                            if (b.name == body) return &b.estimate;
                          }
                          return nullptr;
                        });
  status.station.error = snapshot.station.connected ? "" : context.source_error;
  if (context.bridge_latency) {
    const auto ms = [](core::Duration d) { return core::to_seconds(d) * 1e3; };
    const core::LatencySummary& l = *context.bridge_latency;
    status.station.bridge_latency_ms =
        BridgeLatencyView{ms(l.last), ms(l.p50), ms(l.p99), ms(l.max)};
  }
  status.station.late_frames_skipped = context.late_frames_skipped;

  std::map<std::string, RateWindow, std::less<>> next_rates;
  for (std::size_t i = 0; i < snapshot.vehicles.size(); ++i) {
    const core::VehicleStatus& in = snapshot.vehicles[i];
    const core::SenderSnapshot& sender = in.sender;
    const core::VehicleSnapshot& state = in.vehicle;
    VehicleView v;
    v.name = in.name;
    v.body = in.body;
    v.link = i < context.links.size() ? context.links[i] : "";
    v.system_id = sender.system_id;
    v.profile = std::string(core::to_string(in.profile));
    std::uint64_t poses = 0;
    for (const core::MessageDescriptor& row : core::kMessages) {
      const std::string name(row.name);
      const auto k = static_cast<std::size_t>(row.kind);
      v.available_messages.push_back(name);
      if (sender.messages.contains(row.kind)) v.messages.push_back(name);
      if (sender.counters.sent[k] > 0)
        v.sent[std::string(row.mavlink_name)] = sender.counters.sent[k];
      poses += sender.counters.sent[k];
    }
    if (sender.counters.heartbeats > 0) v.sent["HEARTBEAT"] = sender.counters.heartbeats;
    if (sender.counters.origins > 0) v.sent["SET_GPS_GLOBAL_ORIGIN"] = sender.counters.origins;
    if (sender.counters.origin_requests > 0) {
      v.sent["REQUEST_MESSAGE"] = sender.counters.origin_requests;
    }
    const std::uint64_t timesyncs =
        sender.counters.timesync_replies + sender.counters.timesync_requests;
    if (timesyncs > 0) v.sent["TIMESYNC"] = timesyncs;
    v.sent_total = sender.counters.frames;
    v.rate_hz = sender.rate_hz;
    v.paused = sender.paused || !in.enabled;

    // Actual rate: pose frames over a window of at least one second, kept between calls.
    RateWindow window{now, poses, 0.0};
    if (auto it = rates_.find(in.name); it != rates_.end() && poses >= it->second.poses) {
      const double dt = seconds_between(it->second.time, now);
      if (dt >= 1.0) {
        window.rate_hz = static_cast<double>(poses - it->second.poses) / dt;
      } else {
        window = it->second;  // keep the older start until a second has passed
      }
    }
    v.send_rate_hz = window.rate_hz;
    next_rates[in.name] = window;

    const bool down = i < context.links_down.size() && context.links_down[i];
    v.link_state = link_state(state.link, down);
    if (state.last_message)
      v.last_heard_s = std::max(0.0, seconds_between(*state.last_message, now));
    if (state.heartbeat) {
      const core::VehicleHeartbeat& hb = *state.heartbeat;
      v.heartbeat = HeartbeatView{
          mav_type_name(hb.type), mav_autopilot_name(hb.autopilot), hb.armed,
          flight_mode_name(hb.autopilot, hb.type, hb.custom_mode),
          state.last_heartbeat ? std::max(0.0, seconds_between(*state.last_heartbeat, now)) : 0.0};
    }
    if (state.timesync) {
      v.timesync =
          TimesyncView{TimesyncState::synced, static_cast<double>(state.timesync->offset_ns) / 1e6,
                       static_cast<double>(state.timesync->rtt_ns) / 1e6};
    } else {
      v.timesync.state = TimesyncState::waiting;
    }
    v.origin = state.origin;
    v.agreement = AgreementView{state.agreement.verdict, state.agreement.yaw_offset_deg,
                                state.agreement.position_offset_m};
    status.vehicles.push_back(std::move(v));
  }
  rates_ = std::move(next_rates);
  return status;
}

}  // namespace mocaplink::web
