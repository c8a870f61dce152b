#include "mocaplink/web/bridge_views.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
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

LinkHealth link_state(core::HeartbeatState state, bool down) {
  if (down) return LinkHealth::down;
  return state == core::HeartbeatState::alive ? LinkHealth::up : LinkHealth::silent;
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

namespace {

/// The set-up list, the vehicle's own words and the delay recommendation (core::VehicleSetup).
void fill_setup(const core::VehicleStatus& in, core::HostTime now, VehicleView& v) {
  const core::VehicleSetupSnapshot& setup = in.setup;
  v.autopilot.name = std::string(core::to_string(setup.autopilot));
  if (setup.version) v.autopilot.version = core::to_string(*setup.version);
  v.autopilot.profile_in_effect = core::profile_in_effect(in.profile, setup.autopilot);
  if (in.vehicle.origin == core::OriginState::unconfirmed) {
    v.origin_advice = core::unconfirmed_origin_advice(setup.autopilot, setup.version);
  } else if (in.vehicle.origin == core::OriginState::withheld) {
    v.origin_advice = core::withheld_origin_advice(setup.version);
  }
  v.setup.state = std::string(core::to_string(setup.state));
  for (const core::SetupLine& line : setup.lines) {
    const core::SetupItem& item = line.item;
    v.setup.items.push_back(SetupItemView{
        item.parameter, item.current, item.needed, std::string(core::to_string(item.severity)),
        std::string(core::to_string(item.status)), item.why, item.fix, item.reboot,
        std::string(core::to_string(line.apply)), line.apply_note});
  }
  v.setup.reboot_for = setup.reboot_for;
  v.setup.last_refusal = setup.last_refusal;
  if (setup.state == core::SetupState::unavailable) {
    v.setup.note = std::string(core::unavailable_reason(in.link));
  }
  for (const core::StatusText& t : setup.statustext) {
    v.statustext.push_back(StatusTextView{std::string(core::severity_name(t.severity)), t.text,
                                          std::max(0.0, seconds_between(t.time, now))});
  }
  if (setup.estimator) {
    EstimatorView e;
    e.source = std::string(setup.estimator->source);
    e.good.assign(setup.estimator->good.begin(), setup.estimator->good.end());
    e.problems.assign(setup.estimator->problems.begin(), setup.estimator->problems.end());
    e.age_s = std::max(0.0, seconds_between(setup.estimator->time, now));
    v.estimator = std::move(e);
  }
  v.delay_ms = DelayView{setup.delay.measured_ms, setup.delay.recommended_ms, setup.delay.parameter,
                         setup.delay.current_ms, setup.delay.basis};
}

/// Why the agreement check has no verdict yet, the first cause that applies (docs/api.md
/// `agreement.reason`); with a verdict, its fix and what it did not check (nullopt if neither).
std::optional<std::string> agreement_reason(const core::BridgeSnapshot& snapshot,
                                            const core::VehicleStatus& in, const VehicleView& v) {
  // With a verdict: what it did not measure (mocap compared with itself), if anything.
  // A disagreement also names its fix first (axis_fix.hpp).
  if (in.vehicle.agreement.verdict != core::AgreementVerdict::unknown) {
    const auto& fix = in.vehicle.agreement.fix;
    const auto unchecked = core::describe_unchecked(
        in.vehicle.agreement.sources, in.vehicle.agreement.heading_offset_deg.has_value());
    if (fix && unchecked) return fix->text + "; " + *unchecked;
    if (fix) return fix->text;
    return unchecked;
  }
  if (!in.enabled) return "the vehicle is disabled: nothing is sent to it or asked of it";
  if (v.link_state == LinkHealth::down) return "the link cannot send";
  if (!in.vehicle.heartbeat) return "no HEARTBEAT from the vehicle yet";
  if (v.link_state == LinkHealth::silent) return "nothing heard from the vehicle lately";
  const auto body = std::find_if(snapshot.bodies.begin(), snapshot.bodies.end(),
                                 [&](const core::BodySnapshot& b) { return b.name == in.body; });
  if (body == snapshot.bodies.end() || body->estimate.state != core::TrackingState::tracking) {
    return "the mocap body " + in.body + " is not tracked";
  }
  for (const core::VehicleStream stream : core::kAgreementStreams) {
    if (auto why = core::describe_missing(stream, in.streams[stream])) return why;
  }
  const core::Agreement& a = in.vehicle.agreement;
  std::array<char, 160> text{};
  if (a.settling) {
    std::snprintf(text.data(), text.size(),
                  "the vehicle booted less than %g s ago: its estimate is compared once it has "
                  "settled",
                  core::to_seconds(core::kAgreementSettle));
    return std::string(text.data());
  }
  if (a.disagreeing_since) {
    std::snprintf(text.data(), text.size(),
                  "the vehicle's estimate is beyond a threshold for %.1f s: it disagrees if that "
                  "lasts %g s",
                  std::max(0.0, core::to_seconds(snapshot.time - *a.disagreeing_since)),
                  core::to_seconds(core::kAgreementHold));
    return std::string(text.data());
  }
  const core::EstimateSources& sources = a.sources;
  if (sources.yaw.source == core::EstimateSource::unknown ||
      sources.position.source == core::EstimateSource::unknown ||
      sources.heading.source == core::EstimateSource::unknown) {
    return core::describe_unchecked(sources);  // no agreement until it is known
  }
  return "comparing the vehicle's estimate with mocap";
}

/// What the agreement measured independently (docs/api.md `agreement.checked`): gravity
/// always, yaw and position where they are the vehicle's own, the compass where it was compared.
std::vector<std::string> checked_quantities(const core::Agreement& a) {
  std::vector<std::string> out{"tilt"};
  if (a.sources.yaw.source == core::EstimateSource::independent) out.emplace_back("yaw");
  if (a.sources.position.source == core::EstimateSource::independent) {
    out.emplace_back("position");
  }
  if (core::checks_second_heading(a.sources) && a.heading_offset_deg) out.emplace_back("compass");
  return out;
}

}  // namespace

void fill_setup_view(const core::VehicleStatus& in, core::HostTime now, VehicleView& v) {
  fill_setup(in, now, v);
}

BridgeStatusBuilder::BridgeStatusBuilder(core::HostTime started) : started_(started) {}

StatusView BridgeStatusBuilder::build(const core::BridgeSnapshot& snapshot,
                                      const BridgeStatusContext& context) const {
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
  status.station.superseded_frames = context.superseded_frames;
  status.station.rejected = context.source_rejected;
  status.station.rejected_reason = context.source_rejected_reason;

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
    for (const core::MessageDescriptor& row : core::kMessages) {
      const std::string name(row.name);
      const auto k = static_cast<std::size_t>(row.kind);
      // Over uXRCE-DDS only ODOMETRY becomes a pose (VehicleOdometry): nothing else to offer.
      if (in.link == core::VehicleLink::mavlink || row.kind == core::MessageKind::odometry) {
        v.available_messages.push_back(name);
      }
      if (sender.messages.contains(row.kind)) v.messages.push_back(name);
      if (sender.counters.sent[k] > 0)
        v.sent[std::string(row.mavlink_name)] = sender.counters.sent[k];
    }
    if (sender.counters.heartbeats > 0) v.sent["HEARTBEAT"] = sender.counters.heartbeats;
    if (sender.counters.origins > 0) v.sent["SET_GPS_GLOBAL_ORIGIN"] = sender.counters.origins;
    if (sender.counters.origin_requests > 0) {
      v.sent["REQUEST_MESSAGE"] = sender.counters.origin_requests;
    }
    if (sender.counters.interval_requests > 0) {
      v.sent["SET_MESSAGE_INTERVAL"] = sender.counters.interval_requests;
    }
    if (sender.counters.data_stream_requests > 0) {
      v.sent["REQUEST_DATA_STREAM"] = sender.counters.data_stream_requests;
    }
    const std::uint64_t timesyncs =
        sender.counters.timesync_replies + sender.counters.timesync_requests;
    if (timesyncs > 0) v.sent["TIMESYNC"] = timesyncs;
    v.sent_total = sender.counters.frames;
    v.rate_hz = sender.rate_hz;
    v.paused = sender.paused || !in.enabled;

    // Measured by the core over its fixed window up to the snapshot's time (sender.hpp), so
    // the first request of a run reads the rate that flows.
    v.send_rate_hz = sender.send_rate_hz;

    if (i < context.gcs.size()) v.gcs = context.gcs[i];
    if (i < context.link_share.size()) v.link_share = context.link_share[i];
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
    if (in.link != core::VehicleLink::mavlink) {
      // Over uXRCE-DDS PX4 syncs with the Agent, not with us: the link judges that sync and
      // picks the stamps (io::Link::clock()).
      v.timesync.state = TimesyncState::off;
      v.clock = ClockView{};
      v.clock.verdict = std::nullopt;
      v.clock.text = "no TIMESYNC goes over uXRCE-DDS: PX4 syncs with the Agent's host";
      if (i < context.link_clocks.size() && context.link_clocks[i]) {
        v.clock.pose_stamps = std::string(core::to_string(context.link_clocks[i]->pose_stamps));
        v.clock.text = context.link_clocks[i]->text;
      }
    } else {
      if (state.timesync) {
        v.timesync = TimesyncView{TimesyncState::synced,
                                  static_cast<double>(state.timesync->offset_ns) / 1e6,
                                  static_cast<double>(state.timesync->rtt_ns) / 1e6};
      } else {
        v.timesync.state = TimesyncState::waiting;
      }
      v.clock.verdict = state.clock.verdict;
      v.clock.rate_ppm = state.clock.rate_ppm;
      v.clock.residual_ms = state.clock.residual_ms;
      if (state.heartbeat && state.heartbeat->autopilot == core::kMavAutopilotPx4) {
        v.clock.pose_stamps = state.capture_stamps ? "capture" : "arrival";
      }
      v.clock.withheld = state.counters.timesync_withheld;
      v.clock.reset_answers = state.counters.timesync_resets;
      v.clock.text = core::vehicle_clock_text(
          state.clock, state.heartbeat ? state.heartbeat->autopilot : std::uint8_t{0});
    }
    v.origin = state.origin;
    v.agreement = AgreementView{state.agreement.verdict, state.agreement.yaw_offset_deg,
                                state.agreement.position_offset_m,
                                agreement_reason(snapshot, in, v), state.agreement.tilt_offset_deg};
    v.agreement.heading_offset_deg = state.agreement.heading_offset_deg;
    v.agreement.checked = checked_quantities(state.agreement);
    if (const auto& fix = state.agreement.fix) {
      v.agreement.fix = AxisFixView{std::string(core::to_string(fix->kind)),
                                    fix->lines,
                                    fix->alternative_lines,
                                    fix->tilt_residual_deg,
                                    fix->heading_residual_deg,
                                    fix->text};
    }
    const std::uint8_t autopilot = state.heartbeat ? state.heartbeat->autopilot : 0;
    for (const core::VehicleStream stream : core::kVehicleStreams) {
      // The estimator's only once the autopilot says which message it is; the compass heading
      // (RAW_IMU, HIGHRES_IMU) only where it is asked for or arrives.
      if (stream == core::VehicleStream::estimator && !core::asked_of(stream, autopilot)) continue;
      if (stream == core::VehicleStream::heading &&
          !core::checks_second_heading(state.agreement.sources) &&
          in.streams[stream].state == core::StreamState::idle) {
        continue;
      }
      v.streams[std::string(core::mavlink_name(stream, autopilot))] =
          core::to_string(in.streams[stream].state);
    }
    fill_setup(in, now, v);
    status.vehicles.push_back(std::move(v));
  }
  return status;
}

}  // namespace mocaplink::web
