// Bridge (bridge.hpp): the step function tying Station, Trackers, Senders and VehicleStates.
#include "mocaplink/core/bridge.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::core {
namespace {

/// "vehicle[N].key", numbered from 1 as the configuration numbers its [[vehicle]] tables (slot i
/// holds config vehicle i at make()).
std::string vehicle_field(std::size_t slot, std::string_view key) {
  return "vehicle[" + std::to_string(slot + 1) + "]." + std::string(key);
}

/// Where the vehicle's yaw and position come from, by the parameters its set-up list has read
/// (over uXRCE-DDS, where none can be read: px4_dds_sources).
EstimateSources sources_of(const VehicleSetup& setup, VehicleLink link) {
  // Only the px4 profile reaches such a link (config: check_ros2_link), so it is PX4 from the
  // first status, before the set-up has learnt the autopilot.
  if (link == VehicleLink::px4_dds) return px4_dds_sources();
  return estimate_sources(setup.autopilot(), setup.version(), setup.input(),
                          [&setup](std::string_view name) { return setup.parameter(name); });
}

/// Where the axes fit the vehicle at rest but the verdict disagrees, it is the vehicle's own
/// yaw or position that is off (its compass, an estimator still converging, an origin elsewhere):
/// the fix says so rather than leave "no axis change needed" beside a disagreement.
std::string own_estimate_off(const Agreement& a, const AgreementThresholds& t) {
  std::string parts;
  char text[96];
  if (a.yaw_offset_deg && std::abs(*a.yaw_offset_deg) > t.max_yaw_offset_deg) {
    std::snprintf(text, sizeof text, "its yaw is %.1f° from mocap's (%g° allowed)",
                  *a.yaw_offset_deg, t.max_yaw_offset_deg);
    parts += text;
  }
  if (a.position_offset_m && *a.position_offset_m > t.max_position_offset_m) {
    std::snprintf(text, sizeof text, "its position is %.2f m from mocap's (%g m allowed)",
                  *a.position_offset_m, t.max_position_offset_m);
    parts += (parts.empty() ? "" : " and ") + std::string(text);
  }
  if (parts.empty()) return {};
  return "; what disagrees is the vehicle's own estimate, not the axes: " + parts +
         " (a compass that is off, an estimator still converging, an origin elsewhere)";
}

/// A disagreement at rest: the axis settings that make mocap agree with the vehicle (issue 48).
/// The raw orientation undoes the configured mapping (R_world_body = Wᵀ · R_ned_frd · Bᵀ); the
/// vehicle's yaw is a heading only where it is its own (a compass), never mocap's fed back; where
/// it is mocap's, its compass's heading (RAW_IMU, HIGHRES_IMU) is, when it has one
/// (estimate_sources.hpp).
void name_axis_fix(const WorldAxisMapping& world, const BodyAxisMapping& body,
                   std::optional<SignedAxis> source_up, const BodyEstimate& mocap,
                   VehicleState& state) {
  const Agreement& a = state.agreement();
  if (a.verdict != AgreementVerdict::disagree || !a.roll_rad || !a.pitch_rad ||
      mocap.state != TrackingState::tracking) {
    return;
  }
  const Eigen::Matrix3d r_ned_frd = mocap.q_ned_frd.normalized().toRotationMatrix();
  const Eigen::Matrix3d raw =
      world.r_ned_world().transpose() * r_ned_frd * body.r_body_frd().transpose();
  VehicleAtRest vehicle{*a.roll_rad, *a.pitch_rad, std::nullopt};
  if (a.sources.yaw.source == EstimateSource::independent) {
    vehicle.heading_rad = a.yaw_rad;
  } else if (state.heading_wanted()) {
    vehicle.heading_rad = a.heading_rad;
  }
  const AxisSettings current{world.up(), world.north(), body.forward(), body.up()};
  AxisFix fix = find_axis_fix(raw, current, vehicle, source_up);
  if (fix.kind == AxisFixKind::agrees) fix.text += own_estimate_off(a, state.config().agreement);
  state.set_axis_fix(std::move(fix));
}

/// A disagreement's fix named before the vehicle's compass heading arrived: named again
/// with it, so the nose is checked too.
bool fix_lacks_heading(const VehicleState& state) {
  const Agreement& a = state.agreement();
  return a.verdict == AgreementVerdict::disagree && a.fix && !a.fix->heading_residual_deg &&
         state.heading_wanted() && a.heading_rad;
}

}  // namespace

WorldAxisMapping default_world_axes() {
  return *WorldAxisMapping::parse("+z", "+x");
}

BodyAxisMapping default_body_axes() {
  return *BodyAxisMapping::parse("+x", "+z");
}

std::string_view to_string(BridgeEventKind kind) {
  switch (kind) {
    case BridgeEventKind::body_tracking:
      return "body_tracking";
    case BridgeEventKind::body_lost:
      return "body_lost";
    case BridgeEventKind::body_reset:
      return "body_reset";
    case BridgeEventKind::body_mirrored:
      return "body_mirrored";
    case BridgeEventKind::vehicle_link:
      return "vehicle_link";
    case BridgeEventKind::origin_state:
      return "origin_state";
    case BridgeEventKind::agreement:
      return "agreement";
    case BridgeEventKind::vehicle_streams:
      return "vehicle_streams";
    case BridgeEventKind::vehicle_setup:
      return "vehicle_setup";
    case BridgeEventKind::vehicle_clock:
      return "vehicle_clock";
  }
  return "unknown";
}

std::variant<Bridge, BridgeConfigError> Bridge::make(const BridgeConfig& config, HostTime start) {
  if (auto error = validate(config.tracking)) {
    return BridgeConfigError{"tracking." + error->field, error->message};
  }
  if (config.origin && !LocalGeodeticFrame::make(*config.origin)) {
    return BridgeConfigError{"origin", "latitude/longitude/altitude out of range or not finite"};
  }
  // Checked one by one against the ones before, exactly as add_vehicle() would.
  BridgeConfig empty = config;
  empty.vehicles.clear();
  Bridge bridge(empty, start);
  for (const VehicleSpec& spec : config.vehicles) {
    auto added = bridge.add_vehicle(spec);
    if (auto* error = std::get_if<BridgeConfigError>(&added)) return std::move(*error);
  }
  bridge.config_.vehicles = config.vehicles;
  if (config.published.enabled && !config.published.all) {
    for (const std::string& name : config.published.names) bridge.publish_body(name);
  }
  return bridge;
}

bool is_valid_vehicle_name(std::string_view name) {
  return !name.empty() && name.size() <= kMaxVehicleNameLength &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                  c == '_' || c == '.' || c == '-';
         });
}

bool is_valid_body_name(std::string_view body) {
  return !body.empty() && body.size() <= kMaxBodyNameLength &&
         std::none_of(body.begin(), body.end(),
                      [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

std::optional<BridgeConfigError> Bridge::validate_vehicle(const VehicleSpec& v,
                                                          std::size_t slot) const {
  if (v.name.empty()) return BridgeConfigError{vehicle_field(slot, "name"), "must not be empty"};
  if (find_vehicle(v.name)) {
    return BridgeConfigError{vehicle_field(slot, "name"),
                             "duplicate vehicle name '" + v.name + "'"};
  }
  if (v.body.empty()) return BridgeConfigError{vehicle_field(slot, "body"), "must not be empty"};
  if (v.system_id == 0) {
    return BridgeConfigError{vehicle_field(slot, "system_id"), "must be 1..255"};
  }
  if (v.component_id <= 1) {
    return BridgeConfigError{vehicle_field(slot, "component_id"),
                             "must be 2..255 (1 is the autopilot itself)"};
  }
  if (!(std::isfinite(v.rate_hz) && v.rate_hz > 0.0 && v.rate_hz <= kMaxSenderRateHz)) {
    return BridgeConfigError{vehicle_field(slot, "rate_hz"),
                             "must be in (0, " + max_rate_text() + "]"};
  }
  if (v.profile == Profile::custom && v.messages.empty()) {
    return BridgeConfigError{vehicle_field(slot, "messages"), "profile custom needs messages"};
  }
  if (messages_for(v.profile, v.messages).needs_origin() && !config_.origin) {
    return BridgeConfigError{"origin", "vehicle '" + v.name + "' sends " +
                                           std::string(to_string(v.profile)) +
                                           " messages, which need [origin]"};
  }
  return std::nullopt;
}

Bridge::Bridge(const BridgeConfig& config, HostTime start)
    : config_(config),
      start_(start),
      station_(config.station),
      capture_mapper_(config.capture_time) {
  if (config.origin) geodetic_ = LocalGeodeticFrame::make(*config.origin);
}

void Bridge::place_vehicle(const VehicleSpec& spec, std::size_t slot) {
  // One Tracker per distinct (body, body axes): vehicles following the same body share it.
  auto same = [&](const Body& b) {
    return b.name == spec.body && b.axes.r_body_frd().isApprox(spec.body_axes.r_body_frd());
  };
  auto it = std::find_if(bodies_.begin(), bodies_.end(), same);
  if (it == bodies_.end()) {
    bodies_.push_back(Body{spec.body, spec.body_axes,
                           Tracker(config_.tracking, AxisMapping(config_.world, spec.body_axes)),
                           TrackingState::unseen, 0, BodyEstimate{}});
    it = std::prev(bodies_.end());
  }
  SenderConfig sc;
  sc.vehicle = slot;
  sc.system_id = spec.system_id;
  sc.component_id = spec.component_id;
  sc.messages = messages_for(spec.profile, spec.messages);
  sc.rate_hz = spec.rate_hz;
  sc.signing_key = spec.signing_key;
  // One physical channel per vehicle (mavlink-wire.md §7.3): link ids 1, 2, ... by slot
  // (wrapping after 255 is harmless: each vehicle is its own link).
  sc.signing_link_id = static_cast<std::uint8_t>((slot % 255) + 1);
  const bool origin = config_.origin.has_value() && sends_origin(spec.profile, sc.messages);
  VehicleStateConfig vc;
  vc.system_id = spec.system_id;
  if (origin) vc.origin = config_.origin;
  vc.agreement = config_.agreement;
  const auto body = static_cast<std::size_t>(it - bodies_.begin());
  const VehicleStreams streams(spec.system_id, spec.component_id);
  VehicleSetup setup(spec.system_id, spec.component_id, spec.profile, sc.messages, spec.link);
  Vehicle vehicle{spec, body, Sender(sc), VehicleState(vc), origin, streams, std::move(setup), 0};
  if (slot == vehicles_.size()) {
    vehicles_.emplace_back(std::move(vehicle));
  } else {
    vehicles_[slot].emplace(std::move(vehicle));
  }
}

void Bridge::publish_body(std::string_view name) {
  const auto named = [&](const Body& b) { return b.name == name; };
  if (std::any_of(bodies_.begin(), bodies_.end(),
                  [&](const Body& b) { return b.exported && named(b); })) {
    return;
  }
  auto it = std::find_if(bodies_.begin(), bodies_.end(), named);
  if (it == bodies_.end()) {
    const BodyAxisMapping& axes = config_.published.axes;
    bodies_.push_back(Body{std::string(name), axes,
                           Tracker(config_.tracking, AxisMapping(config_.world, axes)),
                           TrackingState::unseen, 0, BodyEstimate{}});
    it = std::prev(bodies_.end());
  }
  it->exported = true;
  published_names_.emplace(name);
}

std::size_t Bridge::next_slot() const {
  const auto empty = std::find_if(vehicles_.begin(), vehicles_.end(),
                                  [](const std::optional<Vehicle>& v) { return !v.has_value(); });
  return static_cast<std::size_t>(empty - vehicles_.begin());
}

std::variant<std::size_t, BridgeConfigError> Bridge::add_vehicle(const VehicleSpec& spec) {
  const std::size_t slot = next_slot();
  if (auto error = validate_vehicle(spec, slot)) return std::move(*error);
  place_vehicle(spec, slot);
  return slot;
}

bool Bridge::remove_vehicle(std::size_t slot) {
  if (live(slot) == nullptr) return false;
  const std::size_t body = vehicles_[slot]->body;
  vehicles_[slot].reset();
  while (!vehicles_.empty() && !vehicles_.back()) vehicles_.pop_back();
  const bool followed = std::any_of(vehicles_.begin(), vehicles_.end(),
                                    [&](const auto& v) { return v && v->body == body; });
  if (followed || bodies_[body].exported) return true;
  bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(body));
  for (auto& v : vehicles_) {
    if (v && v->body > body) --v->body;
  }
  return true;
}

const VehicleSpec* Bridge::vehicle(std::size_t slot) const {
  if (slot >= vehicles_.size() || !vehicles_[slot]) return nullptr;
  return &vehicles_[slot]->spec;
}

std::optional<std::size_t> Bridge::find_vehicle(std::string_view name) const {
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (vehicles_[i] && vehicles_[i]->spec.name == name) return i;
  }
  return std::nullopt;
}

std::size_t Bridge::vehicle_count() const {
  return static_cast<std::size_t>(std::count_if(vehicles_.begin(), vehicles_.end(),
                                                [](const auto& v) { return v.has_value(); }));
}

Bridge::Vehicle* Bridge::live(std::size_t slot) {
  if (slot >= vehicles_.size() || !vehicles_[slot]) return nullptr;
  return &*vehicles_[slot];
}

std::optional<GpsTime> Bridge::gps_time(HostTime t) const {
  if (!unix_minus_host_) return std::nullopt;
  const auto unix_us = std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch() +
                                                                             *unix_minus_host_)
                           .count();
  return gps_time_from_unix_us(unix_us);
}

std::uint64_t Bridge::signing_now_10us(HostTime t) const {
  if (!unix_minus_host_) return 0;
  const auto unix_us = std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch() +
                                                                             *unix_minus_host_)
                           .count();
  return mavlink::signing_timestamp_from_unix_us(unix_us);
}

void Bridge::set_wall_clock(HostTime host, std::int64_t unix_us) {
  unix_minus_host_ = std::chrono::microseconds(unix_us) - host.time_since_epoch();
}

void Bridge::on_source_connection(bool connected) {
  station_.on_connection(connected);
}

void Bridge::track_body(Body& body) {
  if (body.tracked_frame == frame_number_) return;
  // Only between begin_frame and end_frame, and not after track_bodies(): emit_frame may then run
  // on several threads, which must not write a body (bridge.hpp).
  assert(frame_ != nullptr && "emit_frame outside begin_frame ... end_frame");
  assert(!all_tracked_ && "a body left untracked after track_bodies()");
  body.tracked_frame = frame_number_;
  const MocapFrame& frame = *frame_;
  if (frame_restarted_) body.tracker.on_clock_restart(frame.capture_time, restart_gap_);
  auto sample = frame.bodies.end();
  if (body.frame_index_hint < frame.bodies.size() &&
      frame.bodies[body.frame_index_hint].name == body.name) {
    sample = frame.bodies.begin() + static_cast<std::ptrdiff_t>(body.frame_index_hint);
  } else {
    sample = std::find_if(frame.bodies.begin(), frame.bodies.end(),
                          [&](const BodySample& s) { return s.name == body.name; });
    if (sample != frame.bodies.end()) {
      body.frame_index_hint = static_cast<std::size_t>(sample - frame.bodies.begin());
    }
  }
  body.mirrored = sample != frame.bodies.end() && sample->mirrored;
  if (sample != frame.bodies.end()) {
    (void)body.tracker.on_sample(frame.capture_time, *sample);
  } else {
    (void)body.tracker.on_missing(frame.capture_time);
  }
  body.published = body.tracker.estimate();
}

void Bridge::body_events(BridgeOutput& out) {
  const HostTime capture = frame_context_.capture;
  for (Body& body : bodies_) {
    const BodyEstimate& e = body.published;
    if (e.reset_counter != body.last_reset_counter) {
      body.last_reset_counter = e.reset_counter;
      out.events.push_back({BridgeEventKind::body_reset, capture, std::nullopt, body.name,
                            "pose jumped, reset_counter " + std::to_string(e.reset_counter)});
    }
    if (body.mirrored && !body.named_mirrored) {
      out.events.push_back(
          {BridgeEventKind::body_mirrored, capture, std::nullopt, body.name,
           "the source's rotation is mirrored (a left-handed matrix, determinant -1): not a pose, "
           "so none is sent; no up, north, body_forward or body_up setting can fix it: check the "
           "handedness of the mocap system's or its streaming tool's frame"});
    }
    body.named_mirrored =
        body.mirrored || (body.named_mirrored && e.state != TrackingState::tracking);
    if (e.state != body.last_state) {
      const bool lost = e.state == TrackingState::lost;
      if (lost || e.state == TrackingState::tracking) {
        out.events.push_back({lost ? BridgeEventKind::body_lost : BridgeEventKind::body_tracking,
                              capture, std::nullopt, body.name,
                              lost ? "lost: no valid sample for loss_timeout_ms" : "tracking"});
      }
      body.last_state = e.state;
    }
  }
}

BridgeOutput Bridge::on_frame(const MocapFrame& frame, HostTime received) {
  BridgeOutput out;
  on_frame(frame, received, out);
  return out;
}

void Bridge::on_frame(const MocapFrame& frame, HostTime received, BridgeOutput& out) {
  begin_frame(frame, received, out);
  emit_frame(0, vehicles_.size(), out.messages);
  end_frame(out);
}

bool source_clock_restarted(SourceTime last_capture, HostTime last_received, SourceTime capture,
                            HostTime received, Duration step_back) {
  if (capture + step_back < last_capture) return true;
  return (capture - last_capture) - (received - last_received) > kSourceClockLeap;
}

Duration Bridge::max_capture_step_back() const {
  return std::chrono::duration_cast<Duration>(
      std::chrono::duration<double, std::milli>(config_.tracking.loss_timeout_ms));
}

Duration Bridge::frame_age(const MocapFrame& frame, HostTime received, HostTime now) const {
  const Duration since_received = now - received;
  const std::optional<HostTime> captured = capture_mapper_.to_host(frame.capture_time);
  if (!captured || !last_capture_ ||
      frame.capture_time + max_capture_step_back() < *last_capture_) {
    return since_received;  // nothing to place it by, or a restart (begin_frame re-seeds)
  }
  // A capture "after" now (a source clock that jumped forward) gives a negative age: by arrival.
  return std::max(since_received, now - *captured);
}

void Bridge::begin_frame(const MocapFrame& frame, HostTime received, BridgeOutput& out) {
  out.messages.clear();
  out.events.clear();
  const HostTime capture =
      capture_mapper_.on_frame(frame.capture_time, received, frame.source_latency);
  capture_age_.add(std::max(Duration::zero(), received - capture));
  // A step back of more than loss_timeout_ms cannot be a reordered datagram (those are a few
  // frame periods late): the source's clock started again. Smaller steps are left to the
  // Trackers, which refuse non-increasing times.
  frame_restarted_ = last_capture_ && last_received_ &&
                     source_clock_restarted(*last_capture_, *last_received_, frame.capture_time,
                                            received, max_capture_step_back());
  if (frame_restarted_) {
    ++source_restarts_;
    restart_gap_ = std::max(Duration::zero(), received - *last_received_);
  }
  last_received_ = received;
  if (!last_capture_ || frame_restarted_ || frame.capture_time > *last_capture_) {
    last_capture_ = frame.capture_time;
  }
  frame_ = &frame;
  ++frame_number_;
  all_tracked_ = false;
  frame_context_.now = received;
  frame_context_.capture = capture;
  frame_context_.start = start_;
  frame_context_.origin = geodetic_ ? &*geodetic_ : nullptr;
  frame_context_.gps = config_.gps;
  frame_context_.gps_time = gps_time(capture);
  frame_context_.signing_now_10us = signing_now_10us(received);
}

void Bridge::track_bodies() {
  for (Body& body : bodies_) track_body(body);
  all_tracked_ = true;
}

void Bridge::emit_frame(std::size_t first, std::size_t end,
                        std::vector<OutgoingMessage>& messages) {
  end = std::min(end, vehicles_.size());
  for (std::size_t slot = first; slot < end; ++slot) {
    auto& v = vehicles_[slot];
    if (!v || !v->spec.enabled) continue;
    Body& body = bodies_[v->body];
    track_body(body);
    v->sender.on_estimate(body.published, frame_context_, messages);
  }
}

void Bridge::end_frame(BridgeOutput& out) {
  assert(frame_ != nullptr && "end_frame without begin_frame");
  if (config_.published.enabled && config_.published.all) {
    for (const BodySample& sample : frame_->bodies) {
      if (!published_names_.contains(sample.name)) publish_body(sample.name);
    }
  }
  all_tracked_ = false;  // a body published from this frame on is still to be tracked
  track_bodies();
  body_events(out);
  station_.on_frame(*frame_, frame_context_.now);  // figures for the dashboard: after the sends
  frame_ = nullptr;
  all_tracked_ = false;
}

void Bridge::published_bodies(std::vector<PublishedBody>& out) const {
  for (const Body& body : bodies_) {
    if (body.exported && body.tracked_frame == frame_number_ && body.published.pose_valid()) {
      out.push_back({body.name, &body.published, &body.axes});
    }
  }
}

void Bridge::vehicle_events(std::size_t index, const VehicleReaction& reaction, HostTime now,
                            BridgeOutput& out) const {
  const Vehicle& v = *vehicles_[index];
  if (reaction.link_changed) {
    out.events.push_back({BridgeEventKind::vehicle_link, now, index, v.spec.name,
                          "link " + std::string(to_string(v.state.link_state()))});
  }
  if (reaction.origin_changed) {
    std::string text = "origin " + std::string(to_string(v.state.origin_state()));
    if (v.state.origin_state() == OriginState::unconfirmed) {
      const VehicleSetupSnapshot setup = v.setup.snapshot();
      text += ": not confirmed after " +
              std::to_string(
                  std::chrono::duration_cast<std::chrono::seconds>(kOriginGiveUpAfter).count()) +
              " s, no longer sent. " + unconfirmed_origin_advice(setup.autopilot, setup.version);
    }
    if (v.state.origin_state() == OriginState::withheld) {
      text += ": " + withheld_origin_advice(v.setup.version());
    }
    if (v.state.origin_state() == OriginState::conflict) {
      text +=
          ": ArduPilot already has a different EKF origin; reboot the vehicle or change "
          "[origin] (nothing more is sent)";
    }
    out.events.push_back({BridgeEventKind::origin_state, now, index, v.spec.name, text});
  }
  if (reaction.agreement_changed) {
    const Agreement& a = v.state.agreement();
    // A sentence for the log ("estimate agrees"), not the API spelling of the verdict.
    std::string text = a.verdict == AgreementVerdict::agree      ? "estimate agrees"
                       : a.verdict == AgreementVerdict::disagree ? "estimate disagrees"
                                                                 : "estimate unknown";
    if (a.tilt_offset_deg) text += ", tilt offset " + std::to_string(*a.tilt_offset_deg) + " deg";
    if (a.yaw_offset_deg) text += ", yaw offset " + std::to_string(*a.yaw_offset_deg) + " deg";
    if (a.position_offset_m) {
      text += ", position offset " + std::to_string(*a.position_offset_m) + " m";
    }
    if (a.heading_offset_deg) {
      text += ", compass offset " + std::to_string(*a.heading_offset_deg) + " deg";
    }
    if (a.settling) text += " (the vehicle booted moments ago: compared once it has settled)";
    if (a.fix) text += "; " + a.fix->text;
    if (const auto unchecked = describe_unchecked(a.sources, a.heading_offset_deg.has_value())) {
      text += "; " + *unchecked;
    }
    out.events.push_back({BridgeEventKind::agreement, now, index, v.spec.name, text});
  }
  if (reaction.clock_changed) {
    out.events.push_back({BridgeEventKind::vehicle_clock, now, index, v.spec.name,
                          vehicle_clock_text(v.state.clock().figures(), v.state.autopilot())});
  }
}

void Bridge::stream_events(std::size_t index, std::vector<std::string>& notes, HostTime now,
                           BridgeOutput& out, BridgeEventKind kind) const {
  for (std::string& note : notes) {
    out.events.push_back({kind, now, index, vehicles_[index]->spec.name, std::move(note)});
  }
  notes.clear();
}

DelayInputs Bridge::delay_inputs(std::optional<double> capture_age_ms,
                                 const VehicleSnapshot& heard) const {
  DelayInputs d;
  d.capture_age_ms = capture_age_ms;
  if (heard.timesync) d.link_rtt_ms = static_cast<double>(heard.timesync->rtt_ns) / 1e6;
  d.vehicle_timesync = heard.capture_stamps;
  return d;
}

BridgeOutput Bridge::on_vehicle_message(std::size_t vehicle, const ReceivedMessage& message,
                                        HostTime received) {
  BridgeOutput out;
  Vehicle* found = live(vehicle);
  if (found == nullptr) return out;
  Vehicle& v = *found;
  const BodyEstimate& mocap = bodies_[v.body].published;
  const VehicleReaction sources =
      v.state.set_estimate_sources(sources_of(v.setup, v.spec.link), received);
  if (sources.agreement_changed) {
    name_axis_fix(config_.world, v.spec.body_axes, config_.source_up, mocap, v.state);
  }
  vehicle_events(vehicle, sources, received, out);
  const VehicleReaction reaction = v.state.on_message(message, received, &mocap);
  if (reaction.agreement_changed) {
    name_axis_fix(config_.world, v.spec.body_axes, config_.source_up, mocap, v.state);
  } else if (fix_lacks_heading(v.state)) {
    name_axis_fix(config_.world, v.spec.body_axes, config_.source_up, mocap, v.state);
    if (const auto& fix = v.state.agreement().fix) {
      out.events.push_back({BridgeEventKind::agreement, received, vehicle, v.spec.name,
                            "named again with the vehicle's compass heading: " + fix->text});
    }
  }
  if (reaction.timesync_reply && v.spec.enabled) {
    v.sender.send(*reaction.timesync_reply, received, signing_now_10us(received), out.messages);
  }
  vehicle_events(vehicle, reaction, received, out);
  std::vector<std::string> notes;
  v.streams.on_message(message, received, notes);
  stream_events(vehicle, notes, received, out);
  v.setup.on_message(message, received, notes);
  stream_events(vehicle, notes, received, out, BridgeEventKind::vehicle_setup);
  return out;
}

BridgeOutput Bridge::on_tick(HostTime now) {
  BridgeOutput out;
  begin_tick();
  tick_vehicles(now, 0, vehicles_.size(), out);
  return out;
}

void Bridge::begin_tick() {
  // The median capture age is the same for every vehicle: one sort of the window per tick.
  tick_capture_age_ms_.reset();
  if (const auto age = capture_age_.summary()) {
    tick_capture_age_ms_ = std::chrono::duration<double, std::milli>(age->p50).count();
  }
}

void Bridge::tick_vehicles(HostTime now, std::size_t first, std::size_t end, BridgeOutput& out) {
  out.messages.clear();
  out.events.clear();
  end = std::min(end, vehicles_.size());
  for (std::size_t i = first; i < end; ++i) {
    if (!vehicles_[i]) continue;
    Vehicle& v = *vehicles_[i];
    const VehicleReaction reaction = v.state.on_tick(now);
    vehicle_events(i, reaction, now, out);
    if (!v.spec.enabled) continue;
    const std::size_t sent_before = out.messages.size();
    // The origin goes only to a vehicle heard, and to a PX4 only from 1.15 (origin_gate).
    // The heartbeat's autopilot at once (the set-up learns it on its own tick); the set-up's
    // version only when it is of that autopilot.
    const AutopilotFamily heard_as = autopilot_family(v.state.autopilot());
    const bool setup_current = v.setup.autopilot() == heard_as;
    const OriginGate gate =
        origin_gate(v.state.heard(), heard_as,
                    setup_current ? v.setup.version() : std::optional<FirmwareVersion>{},
                    setup_current && v.setup.identified());
    if (v.sends_origin && gate == OriginGate::withhold) {
      vehicle_events(i, v.state.withhold_origin(), now, out);
    }
    const GeodeticPosition* origin =
        v.sends_origin && v.state.wants_origin() && gate == OriginGate::send ? &*config_.origin
                                                                             : nullptr;
    // Over uXRCE-DDS only poses go: the link could carry nothing else (VehicleLink::px4_dds).
    const bool mavlink = v.spec.link == VehicleLink::mavlink;
    if (mavlink) {
      v.sender.on_tick(now, signing_now_10us(now), origin, config_.timesync_requests, out.messages);
    }
    for (std::size_t k = sent_before; k < out.messages.size(); ++k) {
      const auto* ts = std::get_if<mavlink::Timesync>(&out.messages[k].message);
      if (ts != nullptr && ts->tc1 == 0) v.state.on_timesync_request_sent(ts->ts1);
    }
    // The agreement check's messages: asked of the vehicle whose heartbeat is heard.
    const VehicleSnapshot heard = v.state.snapshot();
    StreamTarget target;
    target.alive = heard.heartbeat && heard.last_heartbeat &&
                   now - *heard.last_heartbeat <= kVehicleSilentAfter;
    if (heard.heartbeat) {
      target.autopilot = heard.heartbeat->autopilot;
      target.compid = heard.heartbeat->compid;
    }
    target.want_heading = v.state.heading_wanted();
    std::vector<mavlink::Message> requests;
    std::vector<std::string> notes;
    if (mavlink) v.streams.on_tick(now, target, requests, notes);
    stream_events(i, notes, now, out);
    // After a reboot (VehicleStreams sees its boot clock go back) the set-up list is read again
    // and the origin, lost with the vehicle's estimator, is sent again: without it ArduPilot
    // never arms ("PreArm: AHRS: waiting for home", seen against ArduCopter SITL).
    if (const std::uint64_t reboots = v.streams.snapshot().reboots; reboots != v.reboots_seen) {
      v.reboots_seen = reboots;
      v.setup.on_reboot(now);
      // A withheld origin was never sent: the gate decides again, with its own line.
      const bool was_withheld = v.state.origin_state() == OriginState::withheld;
      if (v.state.on_reboot().origin_changed && !was_withheld) {
        out.events.push_back({BridgeEventKind::origin_state, now, i, v.spec.name,
                              "origin sending: the vehicle rebooted and lost the origin it had"});
      }
    }
    SetupTarget setup_target;
    setup_target.alive = target.alive;
    setup_target.autopilot = target.autopilot;
    setup_target.compid = target.compid;
    setup_target.armed = heard.heartbeat && heard.heartbeat->armed;
    DelayInputs delay = delay_inputs(tick_capture_age_ms_, heard);
    delay.dds_time_sync = !mavlink && v.capture_stamps;
    v.setup.on_tick(now, setup_target, delay, requests, notes);
    stream_events(i, notes, now, out, BridgeEventKind::vehicle_setup);
    const VehicleReaction sources =
        v.state.set_estimate_sources(sources_of(v.setup, v.spec.link), now);
    if (sources.agreement_changed) {
      name_axis_fix(config_.world, v.spec.body_axes, config_.source_up, bodies_[v.body].published,
                    v.state);
    }
    vehicle_events(i, sources, now, out);
    for (const mavlink::Message& m : requests) {
      v.sender.send(m, now, signing_now_10us(now), out.messages);
    }
  }
}

SetupRequestResult Bridge::apply_setup(std::size_t slot, std::span<const std::string> parameters,
                                       HostTime now) {
  Vehicle* v = live(slot);
  if (v == nullptr) return {false, "no such vehicle"};
  return v->setup.apply(parameters, now);
}

SetupRequestResult Bridge::reboot_vehicle(std::size_t slot, HostTime now, BridgeOutput& out) {
  Vehicle* v = live(slot);
  if (v == nullptr) return {false, "no such vehicle"};
  std::vector<mavlink::Message> command;
  SetupRequestResult result = v->setup.reboot(now, command);
  for (const mavlink::Message& m : command) {
    v->sender.send(m, now, signing_now_10us(now), out.messages);
  }
  if (result.accepted) {
    out.events.push_back({BridgeEventKind::vehicle_setup, now, slot, v->spec.name,
                          "reboot asked of the autopilot (by the operator)"});
  }
  return result;
}

bool Bridge::set_rate_hz(std::size_t vehicle, double rate_hz) {
  Vehicle* v = live(vehicle);
  return v != nullptr && v->sender.set_rate_hz(rate_hz);
}

bool Bridge::set_messages(std::size_t vehicle, const MessageSet& messages) {
  Vehicle* v = live(vehicle);
  if (v == nullptr) return false;
  if (messages.needs_origin() && !geodetic_) return false;
  v->sender.set_messages(messages);
  v->setup.set_messages(messages);
  return true;
}

bool Bridge::raise_signing_timestamp(std::size_t vehicle, std::uint64_t timestamp_10us) {
  Vehicle* v = live(vehicle);
  if (v == nullptr) return false;
  v->sender.raise_signing_timestamp(timestamp_10us);
  return true;
}

bool Bridge::set_capture_stamps(std::size_t vehicle, bool capture) {
  Vehicle* v = live(vehicle);
  if (v == nullptr) return false;
  v->capture_stamps = capture;
  return true;
}

bool Bridge::set_paused(std::size_t vehicle, bool paused) {
  Vehicle* v = live(vehicle);
  if (v == nullptr) return false;
  v->sender.set_paused(paused);
  return true;
}

BridgeSnapshot Bridge::snapshot(HostTime now) const {
  BridgeSnapshot s;
  s.time = now;
  s.station = station_.snapshot(now);
  s.origin = config_.origin;
  s.capture_offset = capture_mapper_.offset();
  s.bodies.reserve(bodies_.size());
  for (const Body& b : bodies_) s.bodies.push_back({b.name, b.published});
  s.source_restarts = source_restarts_;
  s.vehicles.reserve(vehicles_.size());
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (!vehicles_[i]) continue;
    const Vehicle& v = *vehicles_[i];
    s.vehicles.push_back({i, v.spec.name, v.spec.body, v.spec.profile, v.spec.enabled, v.spec.link,
                          v.sender.snapshot(now), v.state.snapshot(), v.streams.snapshot(),
                          v.setup.snapshot()});
  }
  return s;
}

}  // namespace mocaplink::core
