// VehicleState (vehicle_state.hpp): heartbeat, TIMESYNC, origin state machine, agreement check.
#include "mocaplink/core/vehicle_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>

#include "mocaplink/core/message_builders.hpp"
#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

constexpr std::uint8_t kMavTypeGcs = 6;
/// Origin match tolerances (docs/messages.md "Origin"): 1e-7 deg is one degE7 unit; 1 cm is the
/// resolution ArduPilot stores the origin altitude with (it converts mm → cm, §3.9).
constexpr std::int64_t kOriginTolE7 = 1;
constexpr std::int64_t kOriginTolMm = 10;

std::int64_t alt_mm(double altitude_m) {
  return std::llround(altitude_m * 1000.0);
}

}  // namespace

std::string_view to_string(HeartbeatState state) {
  switch (state) {
    case HeartbeatState::waiting:
      return "waiting";
    case HeartbeatState::alive:
      return "alive";
    case HeartbeatState::silent:
      return "silent";
  }
  return "unknown";
}

std::string_view to_string(OriginState state) {
  switch (state) {
    case OriginState::not_needed:
      return "not_needed";
    case OriginState::sending:
      return "sending";
    case OriginState::confirmed:
      return "confirmed";
    case OriginState::conflict:
      return "conflict";
    case OriginState::unconfirmed:
      return "unconfirmed";
    case OriginState::withheld:
      return "withheld";
  }
  return "unknown";
}

std::string_view to_string(AgreementVerdict verdict) {
  switch (verdict) {
    case AgreementVerdict::unknown:
      return "unknown";
    case AgreementVerdict::agree:
      return "agree";
    case AgreementVerdict::disagree:
      return "disagree";
  }
  return "unknown";
}

std::string vehicle_clock_text(const VehicleClockFigures& f, std::uint8_t autopilot) {
  const bool ardupilot = autopilot == kMavAutopilotArdupilot;
  char figures[96] = "";
  if (f.rate_ppm && f.residual_ms) {
    std::snprintf(figures, sizeof figures, "%+.0f ppm against this host's, %.1f ms off a line",
                  *f.rate_ppm, *f.residual_ms);
  }
  switch (f.verdict) {
    case VehicleClockVerdict::measuring:
      return f.restarts > 0 ? "clock measured afresh: the vehicle restarted"
                            : "clock being measured: a verdict after 20 s of its TIMESYNC requests";
    case VehicleClockVerdict::steady:
      return std::string("clock steady (") + figures + ")" +
             (ardupilot ? ""
                        : ": PX4 places poses at their capture time once its time sync "
                          "has converged");
    case VehicleClockVerdict::unsteady:
      if (ardupilot) {
        return std::string("clock unsteady (") + figures +
               "): ArduPilot's jitter correction never places a pose after its arrival; nothing "
               "changes";
      }
      return std::string("clock unsteady (") + figures +
             ", a simulator's lockstep clock?): PX4's time sync cannot follow it and would place "
             "poses in its future, so its TIMESYNC requests are no longer answered and it stamps "
             "poses on arrival; set EKF2_EV_DELAY as the set-up list recommends";
  }
  return {};
}

double magnetic_heading_rad(const Eigen::Vector3d& field_frd, double roll_rad, double pitch_rad) {
  const Eigen::Vector3d level = (Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix() *
                                field_frd;
  if (std::hypot(level.x(), level.y()) == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return std::atan2(-level.y(), level.x());
}

double wrap_deg_180(double degrees) {
  double d = std::fmod(degrees, 360.0);  // (−360, 360)
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

VehicleState::VehicleState(VehicleStateConfig config) : config_(std::move(config)) {
  origin_ = config_.origin ? OriginState::sending : OriginState::not_needed;
}

VehicleReaction VehicleState::on_message(const ReceivedMessage& message, HostTime now,
                                         const BodyEstimate* mocap) {
  VehicleReaction reaction;
  ++counters_.messages;
  last_message_ = now;
  if (std::holds_alternative<mavlink::Timesync>(message.message)) {
    on_timesync(message, now, reaction);  // requests are answered whoever asks
    return reaction;
  }
  if (message.sysid != config_.system_id) {
    ++counters_.from_other_systems;
    return reaction;
  }
  if (const auto* hb = std::get_if<mavlink::Heartbeat>(&message.message)) {
    (void)hb;
    on_heartbeat(message, now, reaction);
  } else if (const auto* origin = std::get_if<mavlink::GpsGlobalOrigin>(&message.message)) {
    on_origin(*origin, reaction);
  } else if (const auto* raw = std::get_if<mavlink::RawImu>(&message.message)) {
    // ArduPilot's compass field (milligauss, body frame; estimate_sources.hpp). All zero: it has
    // no compass there.
    const Eigen::Vector3d field(raw->xmag, raw->ymag, raw->zmag);
    if (!field.isZero()) {
      mag_frd_ = field;
      mag_received_ = now;
    }
  } else if (const auto* imu = std::get_if<mavlink::HighresImu>(&message.message)) {
    // Bits 6-8 of fields_updated: the magnetometer's x, y, z are this sample's.
    constexpr std::uint16_t kMagBits = (1U << 6) | (1U << 7) | (1U << 8);
    const Eigen::Vector3d field(imu->xmag, imu->ymag, imu->zmag);
    if ((imu->fields_updated & kMagBits) == kMagBits && field.allFinite()) {
      mag_frd_ = field;
      mag_received_ = now;
    }
  } else if (const auto* att = std::get_if<mavlink::Attitude>(&message.message)) {
    if (settled(att->time_boot_ms, now, reaction) && mocap != nullptr &&
        mocap->state == TrackingState::tracking && std::isfinite(att->yaw)) {
      const double mocap_yaw = euler_321_from_quaternion(mocap->q_ned_frd).yaw_rad;
      const auto offset_deg = [&](double yaw_rad) {
        return wrap_deg_180((yaw_rad - mocap_yaw) * 180.0 / std::numbers::pi);
      };
      const double offset = offset_deg(att->yaw);
      const double tilt = tilt_offset_deg(mocap->q_ned_frd, att->roll, att->pitch);
      if (std::isfinite(offset)) vehicle_yaw_offset_deg_ = offset;
      vehicle_heading_offset_deg_.reset();
      agreement_.heading_rad.reset();
      const auto fresh = [&](const std::optional<HostTime>& t) {
        return t && now - *t <= kHeadingFresh;
      };
      std::optional<double> heading;
      if (heading_wanted() && fresh(mag_received_)) {
        const double h = magnetic_heading_rad(*mag_frd_, att->roll, att->pitch);
        if (std::isfinite(h)) heading = h + agreement_.sources.declination_rad;
      }
      if (heading) {
        vehicle_heading_offset_deg_ = offset_deg(*heading);
        agreement_.heading_rad = heading;
      }
      if (std::isfinite(tilt)) {
        vehicle_tilt_offset_deg_ = tilt;
        agreement_.roll_rad = att->roll;
        agreement_.pitch_rad = att->pitch;
        agreement_.yaw_rad = att->yaw;
      }
      if (std::isfinite(offset) || std::isfinite(tilt)) update_agreement(now, reaction);
    }
  } else if (const auto* pos = std::get_if<mavlink::LocalPositionNed>(&message.message)) {
    if (settled(pos->time_boot_ms, now, reaction) && mocap != nullptr &&
        mocap->state == TrackingState::tracking) {
      const Eigen::Vector3d p(static_cast<double>(pos->x), static_cast<double>(pos->y),
                              static_cast<double>(pos->z));
      const double offset = (p - mocap->p_ned_m).norm();
      if (std::isfinite(offset)) {
        vehicle_position_offset_m_ = offset;
        update_agreement(now, reaction);
      }
    }
  }
  return reaction;
}

void VehicleState::on_heartbeat(const ReceivedMessage& message, HostTime now,
                                VehicleReaction& reaction) {
  const auto& hb = std::get<mavlink::Heartbeat>(message.message);
  // A GCS or a non-autopilot component sharing the vehicle's sysid is not the vehicle (§3.11).
  if (hb.type == kMavTypeGcs || hb.autopilot == kMavAutopilotInvalid) return;
  ++counters_.heartbeats;
  VehicleHeartbeat v;
  v.compid = message.compid;
  v.type = hb.type;
  v.autopilot = hb.autopilot;
  v.base_mode = hb.base_mode;
  v.custom_mode = hb.custom_mode;
  v.system_status = hb.system_status;
  v.armed = (hb.base_mode & kMavModeFlagSafetyArmed) != 0;
  heartbeat_ = v;
  last_heartbeat_ = now;
  if (link_ != HeartbeatState::alive) {
    link_ = HeartbeatState::alive;
    reaction.link_changed = true;
  }
}

void VehicleState::on_timesync(const ReceivedMessage& message, HostTime now,
                               VehicleReaction& reaction) {
  const auto& ts = std::get<mavlink::Timesync>(message.message);
  if (ts.tc1 == 0) {
    // A request (TIMESYNC v2): answer at once. Requests addressed to another system are not ours.
    if (ts.target_system != 0 && ts.target_system != config_.system_id) return;
    std::int64_t tc1_ns = now.time_since_epoch().count();
    if (message.sysid == config_.system_id && ts.ts1 > 0) {
      // The vehicle's own request: its ts1 measures its clock, and the clock decides the answer.
      const std::optional<std::int64_t> answer = answer_own_request(ts.ts1, now, reaction);
      if (!answer) {
        ++counters_.timesync_withheld;
        return;
      }
      tc1_ns = *answer;
    }
    ++counters_.timesync_requests;
    reaction.timesync_reply = build_timesync_reply(ts, message.sysid, message.compid, tc1_ns);
    return;
  }
  // A response: ours only if ts1 is one of our pending requests.
  const auto it = std::find(pending_requests_.begin(), pending_requests_.end(), ts.ts1);
  if (ts.ts1 == 0 || it == pending_requests_.end()) return;
  *it = 0;
  ++counters_.timesync_responses;
  const std::int64_t now_ns = now.time_since_epoch().count();
  TimesyncEstimate e = timesync_.value_or(TimesyncEstimate{});
  e.rtt_ns = now_ns - ts.ts1;
  // offset = remote − local at the midpoint of the round trip (§3.10).
  e.offset_ns = ts.tc1 - (ts.ts1 + (now_ns - ts.ts1) / 2);
  ++e.samples;
  timesync_ = e;
}

void VehicleState::on_timesync_request_sent(std::int64_t ts1_ns) {
  pending_requests_[pending_next_] = ts1_ns;
  pending_next_ = (pending_next_ + 1) % pending_requests_.size();
}

void VehicleState::on_origin(const mavlink::GpsGlobalOrigin& reported, VehicleReaction& reaction) {
  ++counters_.origin_reports;
  reported_origin_ = GeodeticPosition{reported.latitude * 1e-7, reported.longitude * 1e-7,
                                      reported.altitude * 1e-3};
  if (!config_.origin || origin_ == OriginState::not_needed) return;
  const GeodeticPosition& ours = *config_.origin;
  const bool match =
      std::llabs(std::int64_t{reported.latitude} - deg_e7(ours.latitude_deg)) <= kOriginTolE7 &&
      std::llabs(std::int64_t{reported.longitude} - deg_e7(ours.longitude_deg)) <= kOriginTolE7 &&
      std::llabs(std::int64_t{reported.altitude} - alt_mm(ours.altitude_m)) <= kOriginTolMm;
  OriginState next = origin_;
  if (match) {
    next = OriginState::confirmed;
  } else if (origin_ == OriginState::withheld) {
    ++counters_.origin_mismatches;  // not ours, and ours is not to be sent
  } else {
    ++counters_.origin_mismatches;
    const bool ardupilot = heartbeat_ && heartbeat_->autopilot == kMavAutopilotArdupilot;
    // ArduPilot's EKF3 origin is immutable until reboot (§3.9): stop and tell the operator.
    // Others (PX4) take a new origin: keep sending ours.
    next = ardupilot ? OriginState::conflict : OriginState::sending;
  }
  if (next != origin_) {
    origin_ = next;
    reaction.origin_changed = true;
  }
}

bool VehicleState::settled(std::uint32_t time_boot_ms, HostTime now, VehicleReaction& reaction) {
  const bool settling = std::chrono::milliseconds(time_boot_ms) < kAgreementSettle;
  if (!settling) {
    agreement_.settling = false;
    return true;
  }
  // Not converged yet (or just rebooted): nothing of it is compared, nor kept for later.
  vehicle_yaw_offset_deg_.reset();
  vehicle_position_offset_m_.reset();
  vehicle_tilt_offset_deg_.reset();
  vehicle_heading_offset_deg_.reset();
  agreement_.tilt_offset_deg.reset();
  agreement_.heading_offset_deg.reset();
  agreement_.heading_rad.reset();
  agreement_.yaw_offset_deg.reset();
  agreement_.position_offset_m.reset();
  agreement_.disagreeing_since.reset();
  agreement_.updated = now;
  agreement_.fix.reset();
  // Settling is news even when the verdict already was unknown (a reboot seen first in TIMESYNC
  // makes the set-up list read again, and its sources unknown, before this message).
  if (agreement_.verdict != AgreementVerdict::unknown || !agreement_.settling) {
    reaction.agreement_changed = true;
  }
  agreement_.verdict = AgreementVerdict::unknown;
  agreement_.settling = true;
  return false;
}

void VehicleState::update_agreement(HostTime now, VehicleReaction& reaction) {
  const AgreementThresholds& t = config_.agreement;
  AgreementVerdict verdict = AgreementVerdict::unknown;
  const bool yaw_bad =
      vehicle_yaw_offset_deg_ && std::abs(*vehicle_yaw_offset_deg_) > t.max_yaw_offset_deg;
  const bool pos_bad =
      vehicle_position_offset_m_ && *vehicle_position_offset_m_ > t.max_position_offset_m;
  const bool tilt_bad =
      vehicle_tilt_offset_deg_ && *vehicle_tilt_offset_deg_ > t.max_tilt_offset_deg;
  const bool heading_bad = vehicle_heading_offset_deg_ &&
                           std::abs(*vehicle_heading_offset_deg_) > t.max_heading_offset_deg;
  if (yaw_bad || pos_bad || tilt_bad || heading_bad) {
    // Disagree only once it has lasted kAgreementHold; unknown until then (header comment).
    if (!agreement_.disagreeing_since) agreement_.disagreeing_since = now;
    if (now - *agreement_.disagreeing_since >= kAgreementHold) {
      verdict = AgreementVerdict::disagree;
    }
  } else {
    agreement_.disagreeing_since.reset();
    // Mocap compared with itself agrees whatever the axes: an agreement needs to know that
    // (estimate_sources.hpp), and what comes from mocap is named unchecked, not agreed.
    const bool sources_known = agreement_.sources.yaw.source != EstimateSource::unknown &&
                               agreement_.sources.position.source != EstimateSource::unknown &&
                               agreement_.sources.heading.source != EstimateSource::unknown;
    // A heading of the vehicle's own, where it has one, is the only check of the nose.
    const bool heading_known = !heading_wanted() || vehicle_heading_offset_deg_.has_value();
    if (vehicle_tilt_offset_deg_ && vehicle_yaw_offset_deg_ && vehicle_position_offset_m_ &&
        sources_known && heading_known) {
      verdict = AgreementVerdict::agree;
    }
  }
  agreement_.tilt_offset_deg = vehicle_tilt_offset_deg_;
  agreement_.yaw_offset_deg = vehicle_yaw_offset_deg_;
  agreement_.position_offset_m = vehicle_position_offset_m_;
  agreement_.heading_offset_deg = vehicle_heading_offset_deg_;
  agreement_.updated = now;
  if (verdict != agreement_.verdict) {
    agreement_.verdict = verdict;
    agreement_.fix.reset();
    reaction.agreement_changed = true;
  }
}

bool VehicleState::heading_wanted() const {
  return checks_second_heading(agreement_.sources);
}

void VehicleState::set_axis_fix(AxisFix fix) {
  if (agreement_.verdict == AgreementVerdict::disagree) agreement_.fix = std::move(fix);
}

VehicleReaction VehicleState::set_estimate_sources(const EstimateSources& sources, HostTime now) {
  VehicleReaction reaction;
  if (sources == agreement_.sources) return reaction;
  // The declination read after the compass's field arrived turns the heading already compared:
  // so that the fix the Bridge names again now measures from the heading with it.
  const double turn_rad = sources.declination_rad - agreement_.sources.declination_rad;
  agreement_.sources = sources;
  if (!heading_wanted()) {
    vehicle_heading_offset_deg_.reset();
    agreement_.heading_rad.reset();
  } else if (turn_rad != 0.0) {
    if (agreement_.heading_rad) *agreement_.heading_rad += turn_rad;
    if (vehicle_heading_offset_deg_) {
      vehicle_heading_offset_deg_ =
          wrap_deg_180(*vehicle_heading_offset_deg_ + turn_rad * 180.0 / std::numbers::pi);
    }
  }
  if (vehicle_tilt_offset_deg_ || vehicle_yaw_offset_deg_ || vehicle_position_offset_m_) {
    update_agreement(now, reaction);
  }
  // A verdict's sentence names what it did not check: that changed, so it is news.
  if (agreement_.verdict != AgreementVerdict::unknown) reaction.agreement_changed = true;
  return reaction;
}

VehicleReaction VehicleState::on_tick(HostTime now) {
  VehicleReaction reaction;
  if (link_ == HeartbeatState::alive && last_heartbeat_ &&
      now - *last_heartbeat_ > kVehicleSilentAfter) {
    link_ = HeartbeatState::silent;
    reaction.link_changed = true;
  }
  // Only time with a live vehicle counts towards giving up the origin.
  if (origin_ != OriginState::sending || link_ != HeartbeatState::alive) {
    origin_since_.reset();
  } else if (!origin_since_) {
    origin_since_ = now;
  } else if (now - *origin_since_ >= kOriginGiveUpAfter) {
    origin_ = OriginState::unconfirmed;
    origin_since_.reset();
    reaction.origin_changed = true;
  }
  return reaction;
}

std::optional<std::int64_t> VehicleState::answer_own_request(std::int64_t ts1_ns, HostTime now,
                                                             VehicleReaction& reaction) {
  const std::uint64_t restarts = clock_.figures().restarts;
  if (clock_.on_request(ts1_ns, now)) reaction.clock_changed = true;
  if (clock_.figures().restarts != restarts) forget_time_sync();  // its ts1 went back: a new boot
  std::int64_t tc1_ns = now.time_since_epoch().count();
  const bool ardupilot = heartbeat_ && heartbeat_->autopilot == kMavAutopilotArdupilot;
  if (!ardupilot && clock_.verdict() == VehicleClockVerdict::measuring &&
      answered_this_boot_ >= kTimesyncMeasuringAnswers) {
    return std::nullopt;
  }
  if (!ardupilot && clock_.verdict() == VehicleClockVerdict::unsteady) {
    if (resets_this_boot_ >= kTimesyncResetReplies) return std::nullopt;
    ++resets_this_boot_;
    ++counters_.timesync_resets;
    // A second off, on the side that keeps tc1 positive (PX4 takes tc1 > 0 only).
    tc1_ns += tc1_ns > kTimesyncResetOffset.count() ? -kTimesyncResetOffset.count()
                                                    : kTimesyncResetOffset.count();
  }
  ++answered_this_boot_;
  return tc1_ns;
}

void VehicleState::forget_time_sync() {
  answered_this_boot_ = 0;  // PX4's filter starts from nothing with the new boot
  resets_this_boot_ = 0;
}

bool VehicleState::capture_stamps() const {
  const bool px4 = heartbeat_ && heartbeat_->autopilot == kMavAutopilotPx4;
  return px4 && clock_.verdict() == VehicleClockVerdict::steady &&
         answered_this_boot_ >= kPx4TimesyncConvergence;
}

VehicleReaction VehicleState::on_reboot() {
  VehicleReaction reaction;
  if (clock_.verdict() != VehicleClockVerdict::measuring) reaction.clock_changed = true;
  clock_.restart();
  forget_time_sync();
  reported_origin_.reset();
  origin_since_.reset();  // a new 30 s from the next live heartbeat
  if (config_.origin && origin_ != OriginState::sending) {
    origin_ = OriginState::sending;
    reaction.origin_changed = true;
  }
  return reaction;
}

VehicleReaction VehicleState::withhold_origin() {
  VehicleReaction reaction;
  if (origin_ == OriginState::sending) {
    origin_ = OriginState::withheld;
    origin_since_.reset();
    reaction.origin_changed = true;
  }
  return reaction;
}

VehicleSnapshot VehicleState::snapshot() const {
  VehicleSnapshot s;
  s.link = link_;
  s.heartbeat = heartbeat_;
  s.last_heartbeat = last_heartbeat_;
  s.last_message = last_message_;
  s.origin = origin_;
  s.reported_origin = reported_origin_;
  s.timesync = timesync_;
  s.clock = clock_.figures();
  s.capture_stamps = capture_stamps();
  s.agreement = agreement_;
  s.counters = counters_;
  return s;
}

}  // namespace mocaplink::core
